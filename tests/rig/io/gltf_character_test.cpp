// Characters as glTF: the shipped files load back as the generator's characters; a user's skinned
// glTF loads through a mapping from its joint names to the rig's roles; an unknown joint is a one-line
// error naming the role, the joint and the file (the mapping file's own errors: character_mapping_test.cpp).
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/io/atomic_file.h"
#include "rig/io/character_mapping_json.h"
#include "tests/rig/default_characters.h"
#include <nlohmann/json.hpp>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_writer.h"
#include "rig/mapping/character_mapping.h"
#include "rig/pose.h"
#include "rig/skin.h"
#include "tests/fox_horse.h"
#include "tests/input_error.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

const fs::path kCharacters = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "characters";

using test::defaultHorse;
using test::defaultRider;

fs::path tempDir(const std::string& name) { return stirrup::test::freshTestDir("test_gltf_character", name); }

fs::path writeJson(const fs::path& file, const nlohmann::json& j) {
  std::ofstream(file) << j.dump(2);
  return file;
}

std::string errorOf(const std::function<void()>& f) {
  return stirrup::test::errorOf([&] { f(); }, "");
}

void expectSameCharacter(const Character& a, const Character& b) {
  ASSERT_EQ(a.skeleton.size(), b.skeleton.size());
  for (std::size_t j = 0; j < a.skeleton.size(); ++j) {
    EXPECT_EQ(a.skeleton.joints[j].parent, b.skeleton.joints[j].parent) << j;
    EXPECT_LT(glm::length(a.skeleton.restPosition(static_cast<int>(j)) - b.skeleton.restPosition(static_cast<int>(j))), 1e-4f) << j;
  }
  EXPECT_EQ(a.roles, b.roles);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.normals, b.mesh.normals);
  EXPECT_EQ(a.mesh.colors, b.mesh.colors);
  EXPECT_EQ(a.mesh.indices, b.mesh.indices);
  EXPECT_EQ(a.mesh.weights, b.mesh.weights);
  EXPECT_EQ(a.mesh.tack_parts, b.mesh.tack_parts);
  ASSERT_EQ(a.mesh.joints.size(), b.mesh.joints.size());
  std::size_t differ = 0;  // joints that carry weight (unused slots are written as joint 0)
  for (std::size_t v = 0; v < a.mesh.joints.size(); ++v)
    for (int k = 0; k < 4; ++k) differ += b.mesh.weights[v][k] > 0.0f && a.mesh.joints[v][k] != b.mesh.joints[v][k];
  EXPECT_EQ(differ, 0u);
}

TEST(GltfCharacter, ShippedHorseLoadsAsTheGeneratorsHorse) {
  expectSameCharacter(loadCharacterGltf(kCharacters / "horse.glb", CharacterKind::Horse), defaultHorse());
}

TEST(GltfCharacter, ShippedRiderLoadsAsTheGeneratorsRider) {
  expectSameCharacter(loadCharacterGltf(kCharacters / "rider.glb", CharacterKind::Rider), defaultRider());
}

TEST(GltfCharacter, WritesAtMostFourWeightsSummingToOne) {
  for (const Character* c : {&defaultHorse(), &defaultRider()})
    for (std::size_t v = 0; v < c->mesh.vertexCount(); ++v) {
      const glm::vec4 w = c->mesh.weights[v];
      ASSERT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-5f) << c->name << " vertex " << v;
    }
}

// The shipped files read as a user's characters, through the explicit mapping files beside them:
// posed and skinned at a trot frame they land where the built-in characters land.
TEST(GltfCharacter, UserCharactersThroughMappingFilesPoseLikeTheDefaults) {
  const CharacterMapping hm = loadCharacterMapping(kCharacters / "horse-mapping.json", CharacterKind::Horse);
  const CharacterMapping rm = loadCharacterMapping(kCharacters / "rider-mapping.json", CharacterKind::Rider);
  const Character horse = loadCharacterGltf(kCharacters / "horse.glb", CharacterKind::Horse, &hm);
  const Character rider = loadCharacterGltf(kCharacters / "rider.glb", CharacterKind::Rider, &rm);
  for (const auto& [role, j] : defaultHorse().roles) EXPECT_EQ(horse.roles.at(role), j) << role;
  for (const auto& [role, j] : defaultRider().roles) EXPECT_EQ(rider.roles.at(role), j) << role;

  HorseFrame f;
  f.travel_cm = 50.0;
  f.controls[HorseChannel::rearPivotRz] = 8.0;
  f.controls[HorseChannel::lfHoofTy] = 12.0;
  f.neck_rz = -5.0;
  RiderChannels r;
  r[RiderChannel::lowerBackRz] = 6.0;
  r[RiderChannel::cogTy] = 1.0;
  RigProfile profile = RigProfile::thesis();
  profile.rider_unit_cm = 2.54;
  const MountedPose a = poseMounted(horse, rider, f, r, profile);
  const MountedPose b = poseMounted(defaultHorse(), defaultRider(), f, r, profile);
  std::vector<glm::vec3> pa, na, pb, nb;
  skinMesh(horse.mesh, horse.skeleton, a.horse, pa, na);
  skinMesh(defaultHorse().mesh, defaultHorse().skeleton, b.horse, pb, nb);
  float worst = 0.0f;
  for (std::size_t v = 0; v < pa.size(); ++v) worst = std::max(worst, glm::length(pa[v] - pb[v]));
  skinMesh(rider.mesh, rider.skeleton, a.rider, pa, na);
  skinMesh(defaultRider().mesh, defaultRider().skeleton, b.rider, pb, nb);
  for (std::size_t v = 0; v < pa.size(); ++v) worst = std::max(worst, glm::length(pa[v] - pb[v]));
  EXPECT_LT(worst, 1e-3f);  // cm
}

// The role table names each role's joint as well as its index: a tool keeping extras but listing the
// joints in another order (Blender's exporter lists them depth first) leaves the indices pointing at
// other joints, the names still right. Here every index is made to point at joint 0: the names win.
// The second skin of a file loads as well as the first.
TEST(GltfCharacter, TheRoleTableReadsByJointNamesAndAnySkin) {
  const fs::path dir = tempDir("role_names");
  tinygltf::Model m;
  std::vector<unsigned char> bin;
  const GltfCharacterNodes rider = appendCharacterGltf(m, bin, defaultRider(), "rider:");
  const GltfCharacterNodes horse = appendCharacterGltf(m, bin, defaultHorse(), "horse:");
  tinygltf::Value::Object extras = m.nodes[std::size_t(horse.mesh_node)].extras.Get<tinygltf::Value::Object>();
  tinygltf::Value::Object stale = extras["stirrup_roles"].Get<tinygltf::Value::Object>();
  for (auto& [role, index] : stale) index = tinygltf::Value(0);
  extras["stirrup_roles"] = tinygltf::Value(stale);
  m.nodes[std::size_t(horse.mesh_node)].extras = tinygltf::Value(extras);
  m.asset.version = "2.0";
  tinygltf::Scene scene;
  for (const GltfCharacterNodes& n : {rider, horse}) scene.nodes.insert(scene.nodes.end(), {n.joint_nodes[0], n.mesh_node});
  m.scenes = {scene};
  writeFileAtomically(dir / "two.glb", glbBytes(m, bin));

  GltfImageBytes images;
  const tinygltf::Model read = readGltfFile(dir / "two.glb", "two.glb", &images);
  const Character h = loadCharacterGltf(GltfSkinSource{&read, &images, "two.glb", 1}, CharacterKind::Horse);
  EXPECT_EQ(h.roles, defaultHorse().roles);
  EXPECT_EQ(h.mesh.vertexCount(), defaultHorse().mesh.vertexCount());
  // Without the names the stale indices are all there is: every role on joint 0.
  const std::optional<std::map<std::string, int>> by_index = [&] {
    tinygltf::Model old = read;
    tinygltf::Value::Object e = old.nodes[std::size_t(horse.mesh_node)].extras.Get<tinygltf::Value::Object>();
    e.erase("stirrup_role_joints");
    old.nodes[std::size_t(horse.mesh_node)].extras = tinygltf::Value(e);
    bool named = true;
    auto table = gltfRoleTable(old, "two.glb", 1, CharacterKind::Horse, &named);
    EXPECT_FALSE(named);
    return table;
  }();
  ASSERT_TRUE(by_index);
  EXPECT_EQ(by_index->at("lfHoof"), 0);
  // A table by the joints' names alone (the Blender add-on's shot writes its mappings' so) is read only
  // where the reader asks for it: it says nothing of the file's units and axes (rig/io/gltf_shot.h does).
  tinygltf::Model named_only = read;
  tinygltf::Value::Object e = named_only.nodes[std::size_t(horse.mesh_node)].extras.Get<tinygltf::Value::Object>();
  e.erase("stirrup_roles");
  named_only.nodes[std::size_t(horse.mesh_node)].extras = tinygltf::Value(e);
  EXPECT_FALSE(gltfRoleTable(named_only, "two.glb", 1, CharacterKind::Horse));
  bool named = false;
  const std::optional<std::map<std::string, int>> by_name = gltfRoleTable(named_only, "two.glb", 1, CharacterKind::Horse, &named, true);
  ASSERT_TRUE(by_name);
  EXPECT_TRUE(named);
  for (const char* tack : {"saddle", "lStirrup", "rStirrup", "lRein", "rRein"})
    EXPECT_EQ(read.nodes.at(std::size_t(read.skins.at(1).joints.at(std::size_t(by_name->at(tack))))).name, tack);
  e["stirrup_role_joints"] = tinygltf::Value(std::string("saddle"));
  named_only.nodes[std::size_t(horse.mesh_node)].extras = tinygltf::Value(e);
  EXPECT_EQ(stirrup::test::errorOf([&] { gltfRoleTable(named_only, "two.glb", 1, CharacterKind::Horse, nullptr, true); }),
            "two.glb: the file's role table (extras.stirrup_role_joints) is not an object (expected role -> joint name)");
}

TEST(GltfCharacter, UnknownJointNamesTheRoleTheJointAndTheFile) {
  const fs::path dir = tempDir("unknown_joint");
  nlohmann::json j = nlohmann::json::parse(std::ifstream(kCharacters / "rider-mapping.json"));
  j["roles"]["lHand"] = "LeftHandGrip";
  const fs::path m = writeJson(dir / "mapping.json", j);
  const std::string e = errorOf([&] { resolveCharacter(CharacterKind::Rider, (kCharacters / "rider.glb").string(), m.string()); });
  EXPECT_NE(e.find("roles.lHand: no joint named \"LeftHandGrip\""), std::string::npos) << e;
  EXPECT_NE(e.find("rider.glb"), std::string::npos) << e;
}

// A file without a role table is mapped by itself (rig/mapping/auto_mapping.h); one it cannot map (the
// Khronos SimpleSkin: two unnamed joints in a strip) asks for a mapping file, saying what it found.
TEST(GltfCharacter, FileWithoutRoleTableItCannotMapAsksForAMapping) {
  const fs::path simple = fs::path(STIRRUP_SHARED_DIR) / "assets" / "SimpleSkin.gltf";
  if (!fs::exists(simple)) GTEST_SKIP() << "no " << simple;
  const std::string e = errorOf([&] { loadCharacterGltf(simple, CharacterKind::Horse); });
  EXPECT_EQ(e, simple.string() + ": cannot map as a horse by topology: found 0 mirror-image limb pairs among 2 joints (expected "
                                 "two pairs of legs) (write a mapping file: docs/characters.md, \"Mapping by itself\")");
}

// The Khronos Fox as a horse: every horse role mapped onto its 24 joints (several roles share a
// joint), converted from its units and axes. It loads, keeps its joints' bind places, and posed at
// rest its hooves stay where they were built.
// A file as another tool might write it wrongly: a node naming a mesh, a primitive naming a material, a
// colour naming an accessor the file does not have. Each is one line naming where the index was.
TEST(GltfCharacter, AnIndexPastItsArrayIsOneLineNamingIt) {
  tinygltf::TinyGLTF io;
  tinygltf::Model shipped;
  std::string err, warn;
  ASSERT_TRUE(io.LoadBinaryFromFile(&shipped, &err, &warn, (kCharacters / "horse.glb").string())) << err;
  const fs::path dir = tempDir("bad_index");
  int mesh_node = -1;
  for (std::size_t n = 0; n < shipped.nodes.size(); ++n)
    if (shipped.nodes[n].mesh >= 0) mesh_node = int(n);
  ASSERT_GE(mesh_node, 0);
  const auto broken = [&](const std::string& name, auto change) {
    tinygltf::Model m = shipped;
    change(m);
    const fs::path f = dir / (name + ".glb");
    EXPECT_TRUE(io.WriteGltfSceneToFile(&m, f.string(), true, true, false, true));
    return std::make_pair(f.string(), errorOf([&] { loadCharacterGltf(f, CharacterKind::Horse); }));
  };
  {
    const auto [f, e] = broken("mesh", [&](tinygltf::Model& m) { m.nodes[std::size_t(mesh_node)].mesh = 7; });
    EXPECT_EQ(e, f + ": nodes[" + std::to_string(mesh_node) + "].mesh: 7: no such mesh (the file has 1)");
  }
  {
    const auto [f, e] = broken("material", [](tinygltf::Model& m) { m.meshes[0].primitives[1].material = 99; });
    EXPECT_EQ(e, f + ": meshes[0].primitives[1].material: 99: no such material (the file has " + std::to_string(shipped.materials.size()) + ")");
  }
  {
    const auto [f, e] = broken("weights", [](tinygltf::Model& m) { m.meshes[0].primitives[0].attributes["WEIGHTS_0"] = 12345; });
    EXPECT_EQ(e, f + ": meshes[0].primitives[0].WEIGHTS_0: accessor 12345: no such accessor (the file has " +
                     std::to_string(shipped.accessors.size()) + ")");
  }
}

TEST(GltfCharacter, FoxMapsOntoHorseRoles) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  const fs::path dir = tempDir("fox");
  nlohmann::json j = stirrup::test::foxHorseMapping();
  const fs::path m = writeJson(dir / "fox-horse.json", j);
  const Character c = resolveCharacter(CharacterKind::Horse, fox.string(), m.string());
  EXPECT_EQ(c.skeleton.size(), 24u);
  EXPECT_EQ(c.skeleton.joints[c.role("lfHoof")].name, "b_LeftHand_011");
  EXPECT_EQ(c.role("lfFetlock"), c.role("lfHoof"));
  EXPECT_GT(c.mesh.triangleCount(), 500u);  // the Fox has 576
  // Converted: the fox faces +X now; its head is ahead of its hips and above the ground.
  const glm::vec3 head = c.skeleton.restPosition(c.role("head")), hip = c.skeleton.restPosition(c.role("root"));
  EXPECT_GT(head.x, hip.x + 20.0f);
  EXPECT_GT(hip.y, 100.0f);
  const std::vector<glm::mat4> w = poseHorse(c, HorseFrame{});
  for (const char* hoof : {"lbHoof", "rbHoof"})
    EXPECT_LT(glm::length(glm::vec3(w[c.role(hoof)][3]) - c.skeleton.restPosition(c.role(hoof))), 0.5f) << hoof;

  // A required role missing, a role off its chain, the tack named in part: one line each, naming the
  // mapping file, the role and the joint.
  nlohmann::json without_hoof = j;
  without_hoof["roles"].erase("lbHoof");
  writeJson(m, without_hoof);
  EXPECT_EQ(errorOf([&] { resolveCharacter(CharacterKind::Horse, fox.string(), m.string()); }),
            m.string() + ": roles.lbHoof: missing: expected the name of the horse's lbHoof joint");
  nlohmann::json head_behind = j;
  head_behind["roles"]["head"] = "b_Spine02_03";
  writeJson(m, head_behind);
  EXPECT_EQ(errorOf([&] { resolveCharacter(CharacterKind::Horse, fox.string(), m.string()); }),
            m.string() + ": roles.head: joint \"b_Spine02_03\" is not below neck1 \"b_Neck_04\" (expected the head beyond the "
                         "neck's first joint; change it in the mapping file)");
  nlohmann::json tail_holds_body = j;
  tail_holds_body["roles"]["tail1"] = "b_Hip_01";
  tail_holds_body["roles"].erase("tail2");
  tail_holds_body["roles"].erase("tail3");
  writeJson(m, tail_holds_body);
  EXPECT_EQ(errorOf([&] { resolveCharacter(CharacterKind::Horse, fox.string(), m.string()); }),
            m.string() + ": roles.tail1: joint \"b_Hip_01\" holds root \"b_Hip_01\" (expected the tail's first joint, on a "
                         "chain of its own behind the hips; change it in the mapping file)");
  nlohmann::json part_tack = j;
  for (const char* role : {"lStirrup", "rStirrup", "lRein", "rRein"}) part_tack["roles"].erase(role);
  writeJson(m, part_tack);
  EXPECT_EQ(errorOf([&] { resolveCharacter(CharacterKind::Horse, fox.string(), m.string()); }),
            m.string() + ": roles.lStirrup: missing (the horse's saddle mapped: expected all five tack roles, saddle, lStirrup, "
                         "rStirrup, lRein and rRein, or none, and the rig adds its own tack)");
}

}  // namespace
}  // namespace stirrup::rig
