// The rider's motion for a user's own rider rig: baked onto a user's rider (another tool's units,
// axes, joint names and rest orientations), read back and put on the user's file by joint name, it
// skins the user's mesh exactly as stirrup's pose skins stirrup's copy of it.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/bake.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_nodes.h"
#include "rig/io/gltf_rider_motion.h"
#include "rig/motion/procedural_gait.h"
#include "rig/pose.h"
#include "scene/rig_profile_json.h"
#include "tests/rig/default_characters.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

const fs::path kCharacters = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "characters";

std::vector<int> parents(const tinygltf::Model& m) {
  std::vector<int> p(m.nodes.size(), -1);
  for (std::size_t n = 0; n < m.nodes.size(); ++n)
    for (int c : m.nodes[n].children) p[c] = static_cast<int>(n);
  return p;
}

glm::dmat4 worldOf(const std::vector<int>& parent, const std::vector<glm::dmat4>& local, int n) {
  glm::dmat4 w = local[n];
  for (int p = parent[n]; p >= 0; p = parent[p]) w = local[p] * w;
  return w;
}

template <typename T>
T* accessorPtr(tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor& a = m.accessors.at(accessor);
  const tinygltf::BufferView& v = m.bufferViews.at(a.bufferView);
  return reinterpret_cast<T*>(m.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset);
}

void setTrs(tinygltf::Node& n, const glm::dmat4& m) {
  n.matrix.clear();
  n.scale.clear();
  const glm::dquat q = glm::normalize(glm::quat_cast(glm::dmat3(m)));
  n.translation = {m[3][0], m[3][1], m[3][2]};
  n.rotation = {q.x, q.y, q.z, q.w};
}

// stirrup (cm, +X forward, +Y up) -> the user's file (metres, +Z forward, +Y up).
const glm::dmat4 kRot = glm::rotate(glm::dmat4(1.0), glm::radians(-90.0), glm::dvec3(0, 1, 0));
const glm::dmat4 kToUser = kRot * glm::scale(glm::dmat4(1.0), glm::dvec3(0.01));

// The shipped rider as another tool would have it: in metres facing +Z, each joint with a rest
// orientation of its own (so locals are not stirrup's), joints named "mixamorig:<name>". The rest
// skinned mesh is the shipped one, moved into the user's space.
void makeUserRider(const fs::path& glb, const fs::path& mapping) {
  tinygltf::Model m;
  tinygltf::TinyGLTF io;
  std::string err, warn;
  ASSERT_TRUE(io.LoadBinaryFromFile(&m, &err, &warn, (kCharacters / "rider.glb").string())) << err;
  const std::vector<int> parent = parents(m);
  std::vector<glm::dmat4> local(m.nodes.size());
  for (std::size_t n = 0; n < m.nodes.size(); ++n) local[n] = gltfNodeLocal(m.nodes[n]);
  tinygltf::Skin& skin = m.skins[0];
  int root = skin.joints[0];
  while (parent[root] >= 0) root = parent[root];  // "stirrup_cm", scale 0.01
  std::vector<glm::dmat4> old_world(m.nodes.size()), new_world(m.nodes.size());
  for (std::size_t n = 0; n < m.nodes.size(); ++n) old_world[n] = worldOf(parent, local, static_cast<int>(n));
  std::map<int, int> joint_index;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) joint_index[skin.joints[j]] = static_cast<int>(j);
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    new_world[n] = kRot * old_world[n];
    if (joint_index.count(static_cast<int>(n))) {
      const int j = joint_index[static_cast<int>(n)];
      const glm::dvec3 axis = glm::normalize(glm::dvec3(1.0 + j % 3, 0.5 * (j % 5) - 1.0, 0.7));
      new_world[n] = new_world[n] * glm::rotate(glm::dmat4(1.0), 0.2 + 0.15 * (j % 7), axis);
    }
  }
  m.nodes[root].matrix.clear();
  m.nodes[root].scale.clear();
  const glm::dmat4 root_world = kRot * old_world[root];
  m.nodes[root].matrix = std::vector<double>(glm::value_ptr(root_world), glm::value_ptr(root_world) + 16);
  for (const auto& [node, j] : joint_index) {
    setTrs(m.nodes[node], glm::inverse(new_world[parent[node]]) * new_world[node]);
    m.nodes[node].name = "mixamorig:" + m.nodes[node].name;
  }
  float* ibm = accessorPtr<float>(m, skin.inverseBindMatrices);
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const glm::dmat4 old_ibm = glm::make_mat4(ibm + 16 * j);
    const glm::mat4 nb(glm::inverse(new_world[skin.joints[j]]) * kRot * old_world[skin.joints[j]] * old_ibm * glm::inverse(kToUser));
    std::memcpy(ibm + 16 * j, glm::value_ptr(nb), 64);
  }
  std::map<int, bool> done;
  for (tinygltf::Mesh& mesh : m.meshes)
    for (tinygltf::Primitive& prim : mesh.primitives)
      for (const char* attr : {"POSITION", "NORMAL"}) {
        const int a = prim.attributes.at(attr);
        if (done[a]) continue;
        done[a] = true;
        float* p = accessorPtr<float>(m, a);
        for (std::size_t v = 0; v < m.accessors[a].count; ++v) {
          const glm::dvec4 q = (std::string(attr) == "POSITION" ? kToUser : kRot) *
                               glm::dvec4(p[v * 3], p[v * 3 + 1], p[v * 3 + 2], std::string(attr) == "POSITION" ? 1.0 : 0.0);
          for (int k = 0; k < 3; ++k) p[v * 3 + k] = static_cast<float>(q[k]);
        }
        m.accessors[a].minValues.clear();
        m.accessors[a].maxValues.clear();
      }
  ASSERT_TRUE(io.WriteGltfSceneToFile(&m, glb.string(), true, true, true, true));
  nlohmann::json j = nlohmann::json::parse(std::ifstream(kCharacters / "rider-mapping.json"));
  for (auto& [role, name] : j["roles"].items()) name = "mixamorig:" + name.get<std::string>();
  j["scale_cm"] = 100;
  j["forward"] = {0, 0, 1};
  j["up"] = {0, 1, 0};
  j.erase("offset_cm");
  std::ofstream(mapping) << j.dump(2);
}

TEST(GltfRiderMotion, RoundTripsOntoTheUsersRider) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_gltf_rider_motion";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path user = dir / "user_rider.glb", mapping = dir / "user_rider_mapping.json";
  makeUserRider(user, mapping);
  if (HasFatalFailure()) return;
  const Character rider = resolveCharacter(CharacterKind::Rider, user.string(), mapping.string());
  EXPECT_EQ(rider.skeleton.joints[rider.role("head")].name.rfind("mixamorig:", 0), 0u);

  // A trot, posed on the default horse: the rider's joint worlds at a few frames.
  const RigProfile profile = scene::loadRigProfile("thesis", fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "profiles");
  const ProceduralGait gait(trotParams());
  RiderMotion motion;
  motion.name = "trot";
  motion.fps = 30.0;  // not the default, so the file's extras are seen to carry it
  for (int frame = 1; frame <= 24; frame += 5) {
    const BakedFrame b = bakeFrame(gait, profile, frame, (frame - 1) / 24.0);
    const MountedPose p = poseMounted(test::defaultHorse(), rider, b.horse, b.rider, profile);
    motion.seconds.push_back(static_cast<float>(b.seconds));
    motion.world.push_back(p.rider);
  }
  const std::vector<unsigned char> bytes = riderMotionGlb(rider, motion);

  tinygltf::Model out, orig;
  tinygltf::TinyGLTF io;
  std::string err, warn;
  ASSERT_TRUE(io.LoadBinaryFromMemory(&out, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()))) << err;
  ASSERT_TRUE(io.LoadBinaryFromFile(&orig, &err, &warn, user.string())) << err;
  EXPECT_TRUE(out.meshes.empty());
  EXPECT_TRUE(out.cameras.empty());
  // The scene's extras: the frame rate, and stirrup's forward (+X) and up (+Y) in the user's space
  // (the mapping says forward +Z, up +Y).
  const tinygltf::Value& extras = out.scenes.at(0).extras;
  EXPECT_EQ(extras.Get("fps").GetNumberAsDouble(), 30.0);
  const auto direction = [&](const char* key) {
    const tinygltf::Value& v = extras.Get(key);
    return glm::dvec3(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble(), v.Get(2).GetNumberAsDouble());
  };
  EXPECT_LT(glm::length(direction("stirrup_forward") - glm::dvec3(0, 0, 1)), 1e-9);
  EXPECT_LT(glm::length(direction("stirrup_up") - glm::dvec3(0, 1, 0)), 1e-9);
  ASSERT_EQ(out.skins.size(), 1u);
  ASSERT_EQ(out.animations.size(), 1u);
  // Exported node -> the user's node of the same name; every user joint is there.
  std::map<std::string, int> user_node;
  for (std::size_t n = 0; n < orig.nodes.size(); ++n) user_node[orig.nodes[n].name] = static_cast<int>(n);
  ASSERT_EQ(out.skins[0].joints.size(), orig.skins[0].joints.size());
  std::map<int, int> to_user;
  for (int n : out.skins[0].joints) {
    ASSERT_TRUE(user_node.count(out.nodes[n].name)) << out.nodes[n].name;
    to_user[n] = user_node[out.nodes[n].name];
    // The exported rest is the user's rest: the action applies to the user's armature as it is.
    const glm::dmat4 a = gltfNodeLocal(out.nodes[n]), b = gltfNodeLocal(orig.nodes[to_user[n]]);
    for (int c = 0; c < 4; ++c) EXPECT_LT(glm::length(a[c] - b[c]), 1e-5) << out.nodes[n].name;
  }
  std::map<std::pair<int, std::string>, std::vector<float>> keys;
  const tinygltf::Animation& anim = out.animations[0];
  for (const auto& ch : anim.channels) {
    const tinygltf::Accessor& a = out.accessors[anim.samplers[ch.sampler].output];
    const float* p = accessorPtr<float>(out, anim.samplers[ch.sampler].output);
    keys[{ch.target_node, ch.target_path}] = std::vector<float>(p, p + a.count * (ch.target_path == "rotation" ? 4 : 3));
  }
  const std::vector<int> user_parent = parents(orig);
  const float* user_ibm = accessorPtr<float>(orig, orig.skins[0].inverseBindMatrices);
  const glm::dmat4 to_rig = glm::inverse(kToUser);  // what the mapping says, undone by hand
  double worst_t = 0.0, worst_r = 0.0, moved = 0.0;
  for (std::size_t k = 0; k < motion.seconds.size(); ++k) {
    // The user's rig with the keys of frame k put on its joints by name.
    std::vector<glm::dmat4> local(orig.nodes.size());
    for (std::size_t n = 0; n < orig.nodes.size(); ++n) local[n] = gltfNodeLocal(orig.nodes[n]);
    for (const auto& [out_node, u] : to_user) {
      const std::vector<float>& t = keys.at({out_node, "translation"});
      const std::vector<float>& r = keys.at({out_node, "rotation"});
      local[u] = glm::translate(glm::dmat4(1.0), glm::dvec3(t[k * 3], t[k * 3 + 1], t[k * 3 + 2])) *
                 glm::mat4_cast(glm::normalize(glm::dquat(r[k * 4 + 3], r[k * 4], r[k * 4 + 1], r[k * 4 + 2])));
    }
    for (std::size_t j = 0; j < orig.skins[0].joints.size(); ++j) {
      const int u = orig.skins[0].joints[j];
      // The user's skin matrix in stirrup's space against stirrup's own for the same joint.
      const glm::dmat4 user_skin = to_rig * worldOf(user_parent, local, u) *
                                   glm::dmat4(glm::make_mat4(user_ibm + 16 * j)) * kToUser;
      const int sj = rider.skeleton.find(orig.nodes[u].name);
      ASSERT_GE(sj, 0) << orig.nodes[u].name;
      const glm::dmat4 ours = glm::dmat4(motion.world[k][sj]) * glm::dmat4(rider.skeleton.joints[sj].inverse_bind);
      worst_t = std::max(worst_t, glm::length(glm::dvec3(user_skin[3] - ours[3])));
      moved = std::max(moved, glm::length(glm::dvec3(ours[3])));
      for (int c = 0; c < 3; ++c) worst_r = std::max(worst_r, glm::length(glm::dvec3(user_skin[c] - ours[c])));
    }
  }
  EXPECT_LT(worst_t, 0.01);  // cm
  EXPECT_LT(worst_r, 1e-4);
  EXPECT_GT(moved, 10.0);  // cm: the rider is posed on the horse, far from its bind pose
}

}  // namespace
}  // namespace stirrup::rig
