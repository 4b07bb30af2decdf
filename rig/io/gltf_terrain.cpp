#include "rig/io/gltf_terrain.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_nodes.h"

namespace stirrup::rig {
namespace {

constexpr double kCmPerMetre = 100.0;  // glTF 2.0 (section 3.4): linear distances are metres

// Every node's world transform in the file (the hierarchy checked acyclic, so following parents ends).
std::vector<glm::dmat4> nodeWorlds(const tinygltf::Model& model, const std::vector<int>& parent) {
  std::vector<glm::dmat4> world(model.nodes.size(), glm::dmat4(1.0));
  std::vector<bool> done(model.nodes.size(), false);
  const std::function<const glm::dmat4&(int)> worldOf = [&](int i) -> const glm::dmat4& {
    if (!done[std::size_t(i)]) {
      const glm::dmat4 local = gltfNodeLocal(model.nodes[std::size_t(i)]);
      world[std::size_t(i)] = parent[std::size_t(i)] < 0 ? local : worldOf(parent[std::size_t(i)]) * local;
      done[std::size_t(i)] = true;
    }
    return world[std::size_t(i)];
  };
  for (std::size_t i = 0; i < model.nodes.size(); ++i) worldOf(int(i));
  return world;
}

// The triangles of the nodes `take` picks, each placed by its node's world transform and then `to_cm`.
// Returns false when none of them holds a triangle primitive.
bool collectTriangles(const tinygltf::Model& model, const std::string& where, const std::function<bool(std::size_t)>& take,
                      const glm::dmat4& to_cm, std::vector<glm::dvec3>& vertices, std::vector<std::uint32_t>& indices) {
  const std::vector<int> parent = gltfNodeParents(model, where);
  const std::vector<glm::dmat4> world = nodeWorlds(model, parent);
  for (std::size_t ni = 0; ni < model.nodes.size(); ++ni) {
    const tinygltf::Node& node = model.nodes[ni];
    if (node.mesh < 0 || !take(ni)) continue;
    const glm::dmat4& m = world[ni];
    const std::string mw = where + ": meshes[" + std::to_string(node.mesh) + "]";
    const tinygltf::Mesh& mesh = gltfElement(model.meshes, node.mesh, where + ": nodes[" + std::to_string(ni) + "].mesh", "mesh");
    for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const tinygltf::Primitive& prim = mesh.primitives[pi];
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;  // points and lines carry no ground
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) continue;
      const std::string pw = mw + ".primitives[" + std::to_string(pi) + "]";
      const std::vector<float> p = readAccessor(model, pos->second, 3, pw + ".POSITION");
      const auto base = static_cast<std::uint32_t>(vertices.size());
      const std::size_t count = p.size() / 3;
      for (std::size_t i = 0; i < count; ++i) {
        // Checked before the transform: a NaN would spread to the whole vertex.
        if (!std::isfinite(p[3 * i]) || !std::isfinite(p[3 * i + 1]) || !std::isfinite(p[3 * i + 2]))
          throw InputError(pw + ".POSITION: vertex " + std::to_string(i) + ": expected finite coordinates, got (" +
                           numberText(p[3 * i]) + ", " + numberText(p[3 * i + 1]) + ", " + numberText(p[3 * i + 2]) + ") m");
        vertices.push_back(glm::dvec3(to_cm * (m * glm::dvec4(p[3 * i], p[3 * i + 1], p[3 * i + 2], 1.0))));
      }
      std::vector<std::uint32_t> idx;
      if (prim.indices >= 0) idx = readIndices(model, prim.indices, pw + ".indices");
      else for (std::uint32_t i = 0; i < count; ++i) idx.push_back(i);
      for (std::size_t i = 0; i + 2 < idx.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
          if (idx[i + std::size_t(k)] >= count)
            throw InputError(pw + ".indices: expected vertex indices below " + std::to_string(count) + ", got " +
                             std::to_string(idx[i + std::size_t(k)]));
          indices.push_back(base + idx[i + std::size_t(k)]);
        }
    }
  }
  return !indices.empty();
}

std::shared_ptr<const TerrainMesh> load(const std::filesystem::path& file, const std::string& where) {
  if (!std::filesystem::is_regular_file(file)) throw InputError(where + ": no such file (expected a glTF terrain mesh)");
  const tinygltf::Model model = readGltfFile(file, where);
  std::vector<glm::dvec3> vertices;
  std::vector<std::uint32_t> indices;
  collectTriangles(model, where, [](std::size_t) { return true; }, glm::scale(glm::dmat4(1.0), glm::dvec3(kCmPerMetre)), vertices, indices);
  return std::make_shared<const TerrainMesh>(std::move(vertices), std::move(indices), where);
}

}  // namespace

std::shared_ptr<const TerrainMesh> loadTerrainGltf(const std::filesystem::path& file, const std::string& field) {
  const std::string where = field + ": " + file.string();
  try {
    return load(file, where);
  } catch (const std::out_of_range&) {
    throw InputError(where + ": not a valid glTF file (an index points past the end of its array)");
  }
}

bool isGroundNodeName(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (lower.rfind("ground", 0) != 0) return false;
  return lower.size() == 6 || lower[6] == '_' || lower[6] == '.' || lower[6] == '-';
}

std::shared_ptr<const TerrainMesh> gltfGroundMesh(const tinygltf::Model& model, const std::string& where, const glm::dmat4& file_to_rig) {
  const std::vector<int> parent = gltfNodeParents(model, where);
  const auto named = [&](std::size_t node) {
    if (model.nodes[node].skin >= 0) return false;  // a character's mesh
    for (int n = int(node); n >= 0; n = parent[std::size_t(n)])
      if (isGroundNodeName(model.nodes[std::size_t(n)].name)) return true;
    return false;
  };
  bool any = false;
  for (std::size_t n = 0; n < model.nodes.size() && !any; ++n) any = model.nodes[n].mesh >= 0 && named(n);
  if (!any) return nullptr;
  std::vector<glm::dvec3> vertices;
  std::vector<std::uint32_t> indices;
  if (!collectTriangles(model, where, named, file_to_rig, vertices, indices))
    throw InputError(where + ": the ground (nodes named \"ground\") holds no triangles (expected the ground's mesh)");
  return std::make_shared<const TerrainMesh>(std::move(vertices), std::move(indices), where + ": the ground");
}

}  // namespace stirrup::rig
