#include "rig/io/gltf_nodes.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "rig/error.h"

namespace stirrup::rig {

std::vector<int> gltfNodeParents(const tinygltf::Model& model, const std::string& file) {
  const int count = static_cast<int>(model.nodes.size());
  std::vector<int> parent(model.nodes.size(), -1);
  for (int n = 0; n < count; ++n) {
    const std::vector<int>& children = model.nodes[static_cast<std::size_t>(n)].children;
    for (std::size_t i = 0; i < children.size(); ++i) {
      const int c = children[i];
      const std::string at = file + ": nodes[" + std::to_string(n) + "].children[" + std::to_string(i) + "]: ";
      if (c < 0 || c >= count)
        throw InputError(at + "expected a node index 0.." + std::to_string(count - 1) + ", got " + std::to_string(c));
      if (c == n) throw InputError(at + "node " + std::to_string(c) + " is its own child (expected a tree of nodes)");
      if (parent[static_cast<std::size_t>(c)] >= 0)
        throw InputError(at + "node " + std::to_string(c) + " already has parent node " +
                         std::to_string(parent[static_cast<std::size_t>(c)]) + " (expected a tree of nodes)");
      parent[static_cast<std::size_t>(c)] = n;
    }
  }
  // Every walk up must reach a root: mark nodes known to, and follow each unknown chain once.
  enum : char { Unknown, OnPath, Rooted };
  std::vector<char> state(model.nodes.size(), Unknown);
  for (int n = 0; n < count; ++n) {
    std::vector<int> path;
    int p = n;
    while (p >= 0 && state[static_cast<std::size_t>(p)] == Unknown) {
      state[static_cast<std::size_t>(p)] = OnPath;
      path.push_back(p);
      p = parent[static_cast<std::size_t>(p)];
    }
    if (p >= 0 && state[static_cast<std::size_t>(p)] == OnPath)
      throw InputError(file + ": nodes[" + std::to_string(p) + "]: the node is its own ancestor (expected a tree of nodes)");
    for (const int q : path) state[static_cast<std::size_t>(q)] = Rooted;
  }
  return parent;
}

glm::dmat4 gltfNodeLocal(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3) m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) m *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

}  // namespace stirrup::rig
