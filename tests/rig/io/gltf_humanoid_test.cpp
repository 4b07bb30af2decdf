// The standing test humanoid as written for other tools: read back with tinygltf, the file is in
// metres, +Y up, facing +Z with the left at +X; joints carry rest rotations along their bones with
// inverse bind matrices to match; the rest pose is the one asked for; the texture is embedded and
// referenced; VRM files carry VRMC_vrm's humanBones; nothing of stirrup's is in it.
#include "rig/io/gltf_humanoid.h"
#include "rig/io/character_mapping_json.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_character.h"
#include "rig/mapping/character_mapping.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

struct ReadBack {
  tinygltf::Model model;
  std::string json;            // the GLB's JSON chunk
  std::vector<int> parent;     // per node
  std::vector<glm::dmat4> world;  // per node, from the file's own TRS
  int node(const std::string& name) const {
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (model.nodes[i].name == name) return static_cast<int>(i);
    return -1;
  }
  glm::dvec3 position(const std::string& name) const { return glm::dvec3(world.at(node(name))[3]); }
  glm::dvec3 axis(const std::string& name, int k) const { return glm::normalize(glm::dvec3(world.at(node(name))[k])); }
};

ReadBack readBack(const std::vector<unsigned char>& bytes) {
  ReadBack r;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&r.model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()))) << err;
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, bytes.data() + 12, 4);
  r.json.assign(reinterpret_cast<const char*>(bytes.data()) + 20, json_length);
  const std::size_t n = r.model.nodes.size();
  r.parent.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    for (int c : r.model.nodes[i].children) r.parent[c] = static_cast<int>(i);
  const auto local = [&](int i) {
    const tinygltf::Node& nd = r.model.nodes[i];
    glm::dmat4 m(1.0);
    if (nd.matrix.size() == 16) return glm::make_mat4(nd.matrix.data());
    if (nd.translation.size() == 3) m = glm::translate(m, glm::dvec3(nd.translation[0], nd.translation[1], nd.translation[2]));
    if (nd.rotation.size() == 4) m *= glm::mat4_cast(glm::dquat(nd.rotation[3], nd.rotation[0], nd.rotation[1], nd.rotation[2]));
    if (nd.scale.size() == 3) m = glm::scale(m, glm::dvec3(nd.scale[0], nd.scale[1], nd.scale[2]));
    return m;
  };
  r.world.assign(n, glm::dmat4(1.0));
  for (std::size_t i = 0; i < n; ++i) {
    glm::dmat4 m = local(static_cast<int>(i));
    for (int p = r.parent[i]; p >= 0; p = r.parent[p]) m = local(p) * m;
    r.world[i] = m;
  }
  return r;
}

std::vector<unsigned char> written(StandingHumanoidParams p) { return humanoidGlb(buildStandingHumanoid(p)); }

StandingHumanoidParams params(HumanoidNames names, HumanoidRestPose pose = HumanoidRestPose::T) {
  StandingHumanoidParams p = humanoidConventionDefaults(names);
  p.pose = pose;
  p.cell = 2.5f;
  return p;
}

double angleDeg(glm::dvec3 a, glm::dvec3 b) { return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * kRadToDeg; }

TEST(GltfHumanoid, MetresYUpFacingPlusZNothingOfStirrups) {
  const ReadBack r = readBack(written(params(HumanoidNames::Mixamo)));
  const tinygltf::Model& m = r.model;
  // Metres: the crown at 1.70 m, the soles at 0, over both primitives.
  double lo = 1e9, hi = -1e9;
  ASSERT_EQ(m.meshes.size(), 1u);
  ASSERT_EQ(m.meshes[0].primitives.size(), 2u);
  for (const tinygltf::Primitive& p : m.meshes[0].primitives) {
    const tinygltf::Accessor& a = m.accessors[p.attributes.at("POSITION")];
    lo = std::min(lo, a.minValues[1]);
    hi = std::max(hi, a.maxValues[1]);
  }
  EXPECT_NEAR(hi, 1.70, 0.005);
  EXPECT_NEAR(lo, 0.0, 0.003);
  // The left hip joint at +X (0.105 x 1.70 / 2 = 0.08925 m), the toes ahead of the ankle (+Z), the head up.
  EXPECT_NEAR(r.position("mixamorig:LeftUpLeg").x, 0.08925, 1e-5);
  EXPECT_NEAR(r.position("mixamorig:RightUpLeg").x, -0.08925, 1e-5);
  EXPECT_GT(r.position("mixamorig:LeftToeBase").z - r.position("mixamorig:LeftFoot").z, 0.1);
  EXPECT_NEAR(r.position("mixamorig:Head").y, 1.53, 1e-5);  // 0.90 x 1.70
  // Blender's layout: the joints under an armature node, the skinned mesh node at the scene root.
  const int armature = r.node("Armature"), body = r.node("Body");
  ASSERT_GE(armature, 0);
  ASSERT_GE(body, 0);
  EXPECT_EQ(r.parent[r.node("mixamorig:Hips")], armature);
  EXPECT_EQ(m.scenes[0].nodes, (std::vector<int>{armature, body}));
  EXPECT_EQ(m.nodes[body].skin, 0);
  EXPECT_EQ(m.nodes[armature].scale.size(), 0u);  // no centimetre node
  // Nothing stirrup writes for its own characters.
  EXPECT_EQ(r.json.find("stirrup_roles"), std::string::npos);
  EXPECT_EQ(r.json.find("stirrup_cm"), std::string::npos);
  EXPECT_EQ(r.json.find("_COLOR"), std::string::npos);
  EXPECT_EQ(r.json.find("extras"), std::string::npos);
}

// glTF 2.0 §3.7.3: a joint's inverse bind matrix undoes its world transform at rest. Each joint's
// +Y runs along its bone (Blender's convention), +Z rolled to the front.
TEST(GltfHumanoid, BoneAlignedRestRotationsWithMatchingInverseBinds) {
  const ReadBack r = readBack(written(params(HumanoidNames::Mixamo)));
  const tinygltf::Model& m = r.model;
  const tinygltf::Skin& skin = m.skins.at(0);
  const std::vector<float> ibm = readAccessor(m, skin.inverseBindMatrices, 16, "ibm");
  ASSERT_EQ(ibm.size(), skin.joints.size() * 16);
  int rotated = 0;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const glm::dmat4 inv = glm::dmat4(glm::make_mat4(ibm.data() + j * 16));
    const glm::dmat4 product = inv * r.world[skin.joints[j]];
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k) ASSERT_NEAR(product[c][k], c == k ? 1.0 : 0.0, 2e-6) << m.nodes[skin.joints[j]].name;
    rotated += m.nodes[skin.joints[j]].rotation.size() == 4;
  }
  EXPECT_GT(rotated, 30);
  for (const auto& [joint, child] : std::vector<std::pair<std::string, std::string>>{
           {"mixamorig:Hips", "mixamorig:Spine"}, {"mixamorig:Spine", "mixamorig:Spine1"}, {"mixamorig:Spine2", "mixamorig:Neck"},
           {"mixamorig:Neck", "mixamorig:Head"}, {"mixamorig:LeftShoulder", "mixamorig:LeftArm"},
           {"mixamorig:LeftArm", "mixamorig:LeftForeArm"}, {"mixamorig:LeftForeArm", "mixamorig:LeftHand"},
           {"mixamorig:RightArm", "mixamorig:RightForeArm"}, {"mixamorig:LeftUpLeg", "mixamorig:LeftLeg"},
           {"mixamorig:LeftLeg", "mixamorig:LeftFoot"}, {"mixamorig:LeftFoot", "mixamorig:LeftToeBase"}})
    EXPECT_LT(angleDeg(r.axis(joint, 1), r.position(child) - r.position(joint)), 1e-3) << joint;
  // T pose by hand: the left upper arm's +Y is +X, its +Z the front; the thigh's +Y points down.
  EXPECT_LT(angleDeg(r.axis("mixamorig:LeftArm", 1), {1, 0, 0}), 1e-3);
  EXPECT_LT(angleDeg(r.axis("mixamorig:LeftArm", 2), {0, 0, 1}), 1e-3);
  EXPECT_LT(angleDeg(r.axis("mixamorig:RightArm", 1), {-1, 0, 0}), 1e-3);
  EXPECT_LT(angleDeg(r.axis("mixamorig:LeftUpLeg", 1), {0, -1, 0}), 1.0);
  EXPECT_LT(angleDeg(r.axis("mixamorig:Head", 2), {0, 0, 1}), 1e-3);
}

// VRoid-style files: translations only, inverse binds pure translations.
TEST(GltfHumanoid, VrmJointsHaveNoRestRotations) {
  const ReadBack r = readBack(written(params(HumanoidNames::Vrm)));
  for (int j : r.model.skins.at(0).joints) EXPECT_TRUE(r.model.nodes[j].rotation.empty()) << r.model.nodes[j].name;
  EXPECT_EQ(r.model.scenes[0].nodes.front(), r.node("Root"));  // the ground root at the scene root
  EXPECT_EQ(r.position("Root"), glm::dvec3(0.0));
}

// The rest pose measured from the written joints' world positions: T, the upper arm within 0.05
// degrees of horizontal; A, 45 degrees down; relaxed, 80 degrees down (10 out from the side).
TEST(GltfHumanoid, RestPoseReadBackFromTheFile) {
  const std::map<HumanoidRestPose, double> down = {{HumanoidRestPose::T, 0.0}, {HumanoidRestPose::A, 45.0},
                                                   {HumanoidRestPose::Relaxed, 80.0}};
  for (const auto& [pose, expected] : down) {
    const ReadBack r = readBack(written(params(HumanoidNames::Rigify, pose)));
    for (const char* side : {"L", "R"}) {
      const glm::dvec3 d = r.position(std::string("DEF-forearm.") + side) - r.position(std::string("DEF-upper_arm.") + side);
      EXPECT_NEAR(std::asin(-d.y / glm::length(d)) * kRadToDeg, expected, 0.05) << side;
      EXPECT_GT(side[0] == 'L' ? d.x : -d.x, 0.0);
      EXPECT_NEAR(glm::length(d), 0.3162, 1e-5);  // 0.186 x 1.70 m
    }
  }
}

TEST(GltfHumanoid, TextureEmbeddedAndReferenced) {
  const ReadBack r = readBack(written(params(HumanoidNames::Unreal)));
  const tinygltf::Model& m = r.model;
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].name, "Body");
  EXPECT_EQ(m.materials[1].name, "Hair");
  for (const tinygltf::Material& mat : m.materials) {
    EXPECT_EQ(mat.pbrMetallicRoughness.baseColorTexture.index, 0);
    EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor, (std::vector<double>{1, 1, 1, 1}));
  }
  ASSERT_EQ(m.textures.size(), 1u);
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.textures[0].source, 0);
  EXPECT_EQ(m.images[0].mimeType, "image/png");
  EXPECT_GE(m.images[0].bufferView, 0);
  EXPECT_TRUE(m.images[0].uri.empty());
  // tinygltf decoded the PNG: 512 x 256, the jacket tile's colour at (5, 5), lossless.
  ASSERT_EQ(m.images[0].width, 512);
  ASSERT_EQ(m.images[0].height, 256);
  const int comp = m.images[0].component;
  const unsigned char* px = m.images[0].image.data() + (5 * 512 + 5) * comp;
  EXPECT_EQ(glm::ivec3(px[0], px[1], px[2]), glm::ivec3(28, 48, 110));
  for (const tinygltf::Primitive& p : m.meshes[0].primitives) {
    ASSERT_TRUE(p.attributes.count("TEXCOORD_0"));
    EXPECT_EQ(m.accessors[p.attributes.at("TEXCOORD_0")].count, m.accessors[p.attributes.at("POSITION")].count);
    EXPECT_EQ(m.accessors[p.attributes.at("JOINTS_0")].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
    EXPECT_FALSE(p.attributes.count("COLOR_0"));
  }
}

// VRM 1.0 (vrm-c/vrm-specification, specification/VRMC_vrm-1.0): meta's required name, authors and
// licenseUrl; humanBones naming every required bone, each on the node VRoid names for it.
TEST(GltfHumanoid, VrmHumanBones) {
  const ReadBack r = readBack(written(params(HumanoidNames::Vrm)));
  const tinygltf::Model& m = r.model;
  EXPECT_EQ(m.extensionsUsed, (std::vector<std::string>{"VRMC_vrm"}));
  ASSERT_TRUE(m.extensions.count("VRMC_vrm"));
  const tinygltf::Value& vrm = m.extensions.at("VRMC_vrm");
  EXPECT_EQ(vrm.Get("specVersion").Get<std::string>(), "1.0");
  EXPECT_EQ(vrm.Get("meta").Get("licenseUrl").Get<std::string>(), "https://vrm.dev/licenses/1.0/");
  EXPECT_TRUE(vrm.Get("meta").Get("name").IsString());
  EXPECT_TRUE(vrm.Get("meta").Get("authors").IsArray());
  const tinygltf::Value& bones = vrm.Get("humanoid").Get("humanBones");
  for (const auto& [bone, node] : std::vector<std::pair<std::string, std::string>>{
           {"hips", "J_Bip_C_Hips"}, {"spine", "J_Bip_C_Spine"}, {"chest", "J_Bip_C_Chest"},
           {"upperChest", "J_Bip_C_UpperChest"}, {"neck", "J_Bip_C_Neck"}, {"head", "J_Bip_C_Head"},
           {"leftShoulder", "J_Bip_L_Shoulder"}, {"leftUpperArm", "J_Bip_L_UpperArm"}, {"leftLowerArm", "J_Bip_L_LowerArm"},
           {"leftHand", "J_Bip_L_Hand"}, {"rightHand", "J_Bip_R_Hand"}, {"leftUpperLeg", "J_Bip_L_UpperLeg"},
           {"leftLowerLeg", "J_Bip_L_LowerLeg"}, {"leftFoot", "J_Bip_L_Foot"}, {"leftToes", "J_Bip_L_ToeBase"},
           {"rightUpperLeg", "J_Bip_R_UpperLeg"}, {"rightLowerLeg", "J_Bip_R_LowerLeg"}, {"rightFoot", "J_Bip_R_Foot"},
           {"rightUpperArm", "J_Bip_R_UpperArm"}, {"rightLowerArm", "J_Bip_R_LowerArm"},
           {"leftThumbMetacarpal", "J_Bip_L_Thumb1"}, {"leftIndexDistal", "J_Bip_L_Index3"}}) {
    ASSERT_TRUE(bones.Has(bone)) << bone;
    const int n = bones.Get(bone).Get("node").Get<int>();
    ASSERT_GE(n, 0);
    ASSERT_LT(n, static_cast<int>(m.nodes.size()));
    EXPECT_EQ(m.nodes[n].name, node) << bone;
  }
  EXPECT_FALSE(bones.Has("Root"));
}

TEST(GltfHumanoid, SameHumanoidSameBytes) {
  const StandingHumanoidParams p = params(HumanoidNames::None, HumanoidRestPose::A);
  EXPECT_EQ(written(p), written(p));
}

// The existing importer (rig::loadCharacterGltf) reads a written humanoid as a rider through a
// hand-written mapping of the rider roles of this version (rig/mapping/character_mapping.h) onto Mixamo
// names, with the file's units and axes (metres, +Z forward, +Y up). Kept to this one test: the rider
// role set and the mapping format are changing, and the mapping below changes with them.
TEST(GltfHumanoid, LoadsAsARiderThroughAHandWrittenMapping) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_gltf_humanoid";
  fs::create_directories(dir);
  const fs::path glb = dir / "mixamo.glb", mapping_file = dir / "mixamo-rider.json";
  {
    const std::vector<unsigned char> bytes = written(params(HumanoidNames::Mixamo));
    std::ofstream(glb, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  std::ofstream(mapping_file) << R"({
    "character": "rider", "scale_cm": 100, "forward": [0, 0, 1], "up": [0, 1, 0],
    "roles": {
      "pelvis": "mixamorig:Hips", "lowerBack": "mixamorig:Spine", "waist": "mixamorig:Spine1", "chest": "mixamorig:Spine2",
      "upperChest": "mixamorig:Spine2", "neck": "mixamorig:Neck", "head": "mixamorig:Head",
      "braid1": "mixamorig:Head", "braid2": "mixamorig:Head", "braid3": "mixamorig:Head", "coatTail": "mixamorig:Hips",
      "spine0": "mixamorig:Spine", "spine1": "mixamorig:Spine", "spine2": "mixamorig:Spine", "spine3": "mixamorig:Spine",
      "spine4": "mixamorig:Spine1", "spine5": "mixamorig:Spine1", "spine6": "mixamorig:Spine1", "spine7": "mixamorig:Spine1",
      "spine8": "mixamorig:Spine2", "spine9": "mixamorig:Spine2", "spine10": "mixamorig:Spine2",
      "lShoulder": "mixamorig:LeftArm", "lElbow": "mixamorig:LeftForeArm", "lWrist": "mixamorig:LeftHand",
      "lHand": "mixamorig:LeftInHandMiddle", "lHip": "mixamorig:LeftUpLeg", "lKnee": "mixamorig:LeftLeg",
      "lAnkle": "mixamorig:LeftFoot", "lBall": "mixamorig:LeftToeBase",
      "rShoulder": "mixamorig:RightArm", "rElbow": "mixamorig:RightForeArm", "rWrist": "mixamorig:RightHand",
      "rHand": "mixamorig:RightInHandMiddle", "rHip": "mixamorig:RightUpLeg", "rKnee": "mixamorig:RightLeg",
      "rAnkle": "mixamorig:RightFoot", "rBall": "mixamorig:RightToeBase"}})";
  const CharacterMapping mapping = loadCharacterMapping(mapping_file, CharacterKind::Rider);
  const Character c = loadCharacterGltf(glb, CharacterKind::Rider, &mapping);
  const Skeleton& s = c.skeleton;
  EXPECT_EQ(s.size(), 43u);
  EXPECT_EQ(s.joints[c.role("lWrist")].name, "mixamorig:LeftHand");
  EXPECT_EQ(s.joints[c.role("pelvis")].name, "mixamorig:Hips");
  // In stirrup's axes (cm, +X forward, +Z the right): the left hip at z = -8.925, the head 153 cm up,
  // the toes forward of the ankles.
  EXPECT_NEAR(s.restPosition(c.role("lHip")).z, -8.925f, 1e-3f);
  EXPECT_NEAR(s.restPosition(c.role("rHip")).z, 8.925f, 1e-3f);
  EXPECT_NEAR(s.restPosition(c.role("head")).y, 153.0f, 1e-3f);
  EXPECT_GT(s.restPosition(c.role("lBall")).x - s.restPosition(c.role("lAnkle")).x, 10.0f);
  float top = -1e9f;
  for (const glm::vec3& v : c.mesh.positions) top = std::max(top, v.y);
  EXPECT_NEAR(top, 170.0f, 0.5f);
  EXPECT_GT(c.mesh.triangleCount(), 5000u);
}

}  // namespace
}  // namespace stirrup::rig
