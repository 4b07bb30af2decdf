// Reading a glTF file back the way the tests check what stirrup wrote, independently of stirrup's own
// readers: accessor data as it lies in the buffer, every node's transform at each key of the file's
// animations, skinned vertices by the glTF 2.0 formula. Used by the bake tests and the own-horse tests.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

namespace stirrup::test {

// An accessor's elements as they lie in its buffer view (tightly packed, no sparse): what the writers
// under test produce.
template <typename T>
inline std::vector<T> accessorData(const tinygltf::Model& model, int accessor) {
  const tinygltf::Accessor& a = model.accessors.at(accessor);
  const tinygltf::BufferView& v = model.bufferViews.at(a.bufferView);
  std::vector<T> out(a.count * tinygltf::GetNumComponentsInType(a.type));
  std::memcpy(out.data(), model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset, out.size() * sizeof(T));
  return out;
}

// Every node's local TRS at each key of the file's animations.
struct AnimatedNodes {
  const tinygltf::Model& model;
  std::vector<int> parent;
  std::map<std::pair<int, std::string>, std::vector<float>> keys;  // (node, path) -> values
  std::vector<float> times;

  explicit AnimatedNodes(const tinygltf::Model& m) : model(m), parent(m.nodes.size(), -1) {
    for (std::size_t n = 0; n < m.nodes.size(); ++n)
      for (int c : m.nodes[n].children) parent[c] = static_cast<int>(n);
    for (const tinygltf::Animation& a : m.animations)
      for (const tinygltf::AnimationChannel& ch : a.channels) {
        const tinygltf::AnimationSampler& s = a.samplers[ch.sampler];
        EXPECT_EQ(s.interpolation, "LINEAR");
        const std::vector<float> t = accessorData<float>(m, s.input);
        if (times.empty()) times = t;
        EXPECT_EQ(t, times) << "every track keyed at the same times";
        keys[{ch.target_node, ch.target_path}] = accessorData<float>(m, s.output);
      }
  }
  glm::dmat4 local(int node, std::size_t key) const {
    const tinygltf::Node& n = model.nodes[node];
    if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
    glm::dvec3 t(0.0), sc(1.0);
    glm::dquat q(1.0, 0.0, 0.0, 0.0);
    if (n.translation.size() == 3) t = {n.translation[0], n.translation[1], n.translation[2]};
    if (n.rotation.size() == 4) q = glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (n.scale.size() == 3) sc = {n.scale[0], n.scale[1], n.scale[2]};
    if (auto it = keys.find({node, "translation"}); it != keys.end())
      t = {it->second[key * 3], it->second[key * 3 + 1], it->second[key * 3 + 2]};
    if (auto it = keys.find({node, "rotation"}); it != keys.end())
      q = glm::dquat(it->second[key * 4 + 3], it->second[key * 4], it->second[key * 4 + 1], it->second[key * 4 + 2]);
    if (auto it = keys.find({node, "scale"}); it != keys.end())
      sc = {it->second[key * 3], it->second[key * 3 + 1], it->second[key * 3 + 2]};
    return glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(glm::normalize(q)) * glm::scale(glm::dmat4(1.0), sc);
  }
  glm::dmat4 world(int node, std::size_t key) const {
    glm::dmat4 m = local(node, key);
    for (int p = parent[node]; p >= 0; p = parent[p]) m = local(p, key) * m;
    return m;
  }
  // Every `stride`-th vertex of the skinned mesh on `mesh_node`, skinned at `key` (glTF 2.0 section
  // 3.7.3: sum of weight * joint world * inverse bind matrix; the mesh node's own transform ignored): of
  // its first primitive, or with `every_primitive` of all its primitives' vertices one after another.
  std::vector<glm::dvec3> skinned(int mesh_node, std::size_t key, std::size_t stride, bool every_primitive = false) const {
    const tinygltf::Node& n = model.nodes[mesh_node];
    const tinygltf::Skin& skin = model.skins.at(n.skin);
    const std::vector<float> ibm = accessorData<float>(model, skin.inverseBindMatrices);
    std::vector<glm::dmat4> joint(skin.joints.size());
    for (std::size_t j = 0; j < joint.size(); ++j)
      joint[j] = world(skin.joints[j], key) * glm::dmat4(glm::make_mat4(ibm.data() + 16 * j));
    std::vector<float> pos, wts;
    std::vector<std::uint16_t> jts;
    const std::vector<tinygltf::Primitive>& prims = model.meshes.at(n.mesh).primitives;
    for (std::size_t i = 0; i < (every_primitive ? prims.size() : 1); ++i) {
      const auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
      append(pos, accessorData<float>(model, prims.at(i).attributes.at("POSITION")));
      append(wts, accessorData<float>(model, prims.at(i).attributes.at("WEIGHTS_0")));
      append(jts, accessorData<std::uint16_t>(model, prims.at(i).attributes.at("JOINTS_0")));
    }
    std::vector<glm::dvec3> out;
    for (std::size_t v = 0; v < pos.size() / 3; v += stride) {
      const glm::dvec4 p(pos[v * 3], pos[v * 3 + 1], pos[v * 3 + 2], 1.0);
      glm::dvec4 q(0.0);
      for (int k = 0; k < 4; ++k) q += double(wts[v * 4 + k]) * (joint[jts[v * 4 + k]] * p);
      out.emplace_back(q);
    }
    return out;
  }
};

inline int nodeNamed(const tinygltf::Model& model, const std::string& name) {
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    if (model.nodes[n].name == name) return static_cast<int>(n);
  return -1;
}

}  // namespace stirrup::test
