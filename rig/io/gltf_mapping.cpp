#include "rig/io/gltf_mapping.h"

#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include <glm/mat4x4.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_nodes.h"

namespace stirrup::rig {
namespace {


// VRM's humanoid bone table: VRMC_vrm (1.0: humanBones is an object, bone -> {"node": i}) or VRM
// (0.x: an array of {"bone": name, "node": i}). Bones on nodes that are not joints of the skin are left
// out; a malformed table is ignored (the names and the topology still map the file).
// A member of a JSON object value, or null (tinygltf's Get asserts an object).
const tinygltf::Value& member(const tinygltf::Value& v, const std::string& key) {
  static const tinygltf::Value null_value;
  return v.IsObject() ? v.Get(key) : null_value;
}

void readVrmBones(const tinygltf::Model& model, const std::map<int, int>& node_joint, MappingSkeleton& s) {
  const auto joint = [&](const tinygltf::Value& node) {
    if (!node.IsNumber()) return -1;
    const double d = node.GetNumberAsDouble();
    if (!(d >= 0.0 && d < 1e9)) return -1;
    const auto it = node_joint.find(static_cast<int>(d));
    return it == node_joint.end() ? -1 : it->second;
  };
  if (const auto it = model.extensions.find("VRMC_vrm"); it != model.extensions.end()) {
    const tinygltf::Value& bones = member(member(it->second, "humanoid"), "humanBones");
    if (bones.IsObject()) {
      for (const std::string& bone : bones.Keys())
        if (const int j = joint(member(bones.Get(bone), "node")); j >= 0) s.vrm_bones[bone] = j;
      s.vrm_table = "VRMC_vrm";
      return;
    }
  }
  if (const auto it = model.extensions.find("VRM"); it != model.extensions.end()) {
    const tinygltf::Value& bones = member(member(it->second, "humanoid"), "humanBones");
    if (bones.IsArray()) {
      for (std::size_t i = 0; i < bones.ArrayLen(); ++i) {
        const tinygltf::Value& b = bones.Get(static_cast<int>(i));
        const tinygltf::Value& name = member(b, "bone");
        if (!name.IsString()) continue;
        if (const int j = joint(member(b, "node")); j >= 0) s.vrm_bones[name.Get<std::string>()] = j;
      }
      s.vrm_table = "VRM";
    }
  }
}

}  // namespace

std::vector<std::string> gltfJointNames(const tinygltf::Model& model, int skin_index) {
  std::vector<std::string> names;
  if (skin_index < 0 || skin_index >= static_cast<int>(model.skins.size())) return names;
  const tinygltf::Skin& skin = model.skins[std::size_t(skin_index)];
  std::set<std::string> used;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    std::string name = node >= 0 && node < static_cast<int>(model.nodes.size()) ? model.nodes[node].name : "";
    if (name.empty() || used.count(name)) name = "joint" + std::to_string(j);
    for (int k = 1; used.count(name); ++k) name = "joint" + std::to_string(j) + "_" + std::to_string(k);
    used.insert(name);
    names.push_back(name);
  }
  return names;
}

const tinygltf::Skin& checkedSkin(const tinygltf::Model& model, const std::string& f, const std::string& what, int skin_index) {
  if (model.skins.empty()) throw InputError(f + ": no skin (expected a skinned " + what + ")");
  const std::string at = "skins[" + std::to_string(skin_index) + "]";
  if (skin_index < 0 || skin_index >= static_cast<int>(model.skins.size()))
    throw InputError(f + ": no " + at + " (the file has " + std::to_string(model.skins.size()) + " skins)");
  const tinygltf::Skin& skin = model.skins[std::size_t(skin_index)];
  const int nj = static_cast<int>(skin.joints.size());
  if (nj == 0) throw InputError(f + ": " + at + " has no joints");
  for (int j = 0; j < nj; ++j)
    if (skin.joints[j] < 0 || skin.joints[j] >= static_cast<int>(model.nodes.size()))
      throw InputError(f + ": " + at + ".joints[" + std::to_string(j) + "]: expected a node index 0.." +
                       std::to_string(static_cast<int>(model.nodes.size()) - 1) + ", got " + std::to_string(skin.joints[j]));
  return skin;
}

std::vector<glm::mat4> gltfInverseBinds(const tinygltf::Model& model, const std::string& f, int skin_index) {
  const tinygltf::Skin& skin = model.skins.at(std::size_t(skin_index));
  const std::size_t nj = skin.joints.size();
  std::vector<glm::mat4> ibm(nj, glm::mat4(1.0f));
  if (skin.inverseBindMatrices < 0) return ibm;
  const std::string where = f + ": skins[" + std::to_string(skin_index) + "].inverseBindMatrices";
  const std::vector<float> v = readAccessor(model, skin.inverseBindMatrices, 16, where);
  if (v.size() != nj * 16) throw InputError(where + ": expected one per joint");
  for (std::size_t j = 0; j < nj; ++j) std::memcpy(glm::value_ptr(ibm[j]), v.data() + j * 16, 64);
  return ibm;
}

MappingSkeleton mappingSkeletonFromGltf(const tinygltf::Model& model, const std::string& f, int skin_index) {
  const tinygltf::Skin& skin = checkedSkin(model, f, "character", skin_index);
  const std::string at = "skins[" + std::to_string(skin_index) + "]";
  const int nj = static_cast<int>(skin.joints.size());
  MappingSkeleton s;
  s.file = f;
  s.names = gltfJointNames(model, skin_index);

  // Bind places from the inverse bind matrices (identity when absent), as the importer reads them.
  const std::vector<glm::mat4> ibm = gltfInverseBinds(model, f, skin_index);
  std::vector<glm::vec3> bind(nj);
  for (int j = 0; j < nj; ++j) {
    bind[j] = glm::vec3(glm::inverse(ibm[j])[3]);
    if (!std::isfinite(bind[j].x) || !std::isfinite(bind[j].y) || !std::isfinite(bind[j].z))
      throw InputError(f + ": " + at + ".inverseBindMatrices[" + std::to_string(j) + "]: expected an invertible matrix (joint \"" +
                       s.names[j] + "\")");
    s.position.emplace_back(bind[j]);
  }

  // Parents: the nearest ancestor node that is a joint (a Rigify rig's deform bones as Rigify means
  // them); further roots hung from the body.
  const std::vector<int> node_parent = gltfNodeParents(model, f);
  std::map<int, int> node_joint;
  for (int j = 0; j < nj; ++j) node_joint.emplace(skin.joints[j], j);
  s.parent.assign(nj, -1);
  for (int j = 0; j < nj; ++j)
    for (int n = node_parent.at(skin.joints[j]); n >= 0; n = node_parent[n])
      if (const auto it = node_joint.find(n); it != node_joint.end()) {
        s.parent[j] = it->second;
        break;
      }
  rigifyDeformParents(s.parent, s.names);

  // The mesh: every primitive of every node skinned by the skin.
  s.weighted.assign(nj, 0);
  for (std::size_t ni = 0; ni < model.nodes.size(); ++ni) {
    const tinygltf::Node& node = model.nodes[ni];
    if (node.mesh < 0 || node.skin != skin_index) continue;
    const tinygltf::Mesh& mesh = gltfElement(model.meshes, node.mesh, f + ": nodes[" + std::to_string(ni) + "].mesh", "mesh");
    for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const tinygltf::Primitive& prim = mesh.primitives[pi];
      const std::string pw = f + ": meshes[" + std::to_string(node.mesh) + "].primitives[" + std::to_string(pi) + "]";
      for (const char* a : {"POSITION", "JOINTS_0", "WEIGHTS_0"})
        if (!prim.attributes.count(a)) throw InputError(pw + ": expected a " + std::string(a) + " attribute");
      const std::vector<float> pos = readAccessor(model, prim.attributes.at("POSITION"), 3, pw + ".POSITION");
      const std::vector<float> jts = readAccessor(model, prim.attributes.at("JOINTS_0"), 4, pw + ".JOINTS_0");
      const std::vector<float> wts = readAccessor(model, prim.attributes.at("WEIGHTS_0"), 4, pw + ".WEIGHTS_0");
      const std::size_t n = pos.size() / 3;
      if (jts.size() != n * 4 || wts.size() != n * 4) throw InputError(pw + ": attribute counts differ");
      for (std::size_t v = 0; v < n; ++v) {
        int best = -1;
        float best_w = 0.0f;
        for (int k = 0; k < 4; ++k) {
          const float w = wts[v * 4 + k];
          if (!(w > 0.0f)) continue;
          const int j = static_cast<int>(jts[v * 4 + k]);
          if (j < 0 || j >= nj) throw InputError(pw + ".JOINTS_0: joint index " + std::to_string(j) + " outside " + at);
          s.weighted[j] = 1;
          if (w > best_w) best = j, best_w = w;
        }
        const glm::dvec3 p(pos[v * 3], pos[v * 3 + 1], pos[v * 3 + 2]);
        if (best < 0 || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
        s.vertices.push_back(p);
        s.vertex_joint.push_back(best);
      }
    }
  }
  if (s.vertices.empty()) throw InputError(f + ": no skinned vertices in " + at + "'s meshes (expected a skinned character)");
  glm::dvec3 middle(0.0);
  for (const glm::dvec3& v : s.vertices) middle += v / static_cast<double>(s.vertices.size());
  hangFromTrunk(s.parent, s.position, middle, s.hung);
  readVrmBones(model, node_joint, s);
  s.finish();
  return s;
}

AutoMapping autoMapCharacterFile(const std::filesystem::path& file, CharacterKind kind, const AutoMappingParams& params) {
  const std::string f = file.string();
  if (!std::filesystem::exists(file))
    throw InputError(f + ": no such file (expected a skinned glTF " + std::string(characterKindName(kind)) + ")");
  const tinygltf::Model model = readGltfFile(file, f);
  return autoMapCharacter(mappingSkeletonFromGltf(model, f), kind, params);
}

}  // namespace stirrup::rig
