// A glTF file's skin as the mapping reads it: the importer's joint names (unnamed and repeated names made
// "jointN", and the importer takes a mapping file naming them so), and a VRM file's own humanoid bone
// table in its 1.0 and 0.x forms.
#include "rig/io/gltf_mapping.h"

#include "rig/io/character_mapping_json.h"
#include "rig/mapping/mapping_skeleton.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/characters/standing_humanoid.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_humanoid.h"
#include "rig/mapping/auto_mapping.h"
#include "rig/mapping/character_mapping.h"
#include "tests/rig/user_riders.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

TEST(GltfMapping, UnnamedAndRepeatedJointsAreNamedByTheirIndexAsTheImporterNamesThem) {
  tinygltf::Model m = stirrup::test::glbModel(humanoidGlb(test::coarseHumanoid(HumanoidNames::Mixamo)));
  const std::vector<int>& joints = m.skins.at(0).joints;
  m.nodes.at(joints[4]).name = "";                               // the neck, unnamed
  m.nodes.at(joints[8]).name = m.nodes.at(joints[7]).name;       // the left arm named like the clavicle
  const std::vector<std::string> names = gltfJointNames(m);
  EXPECT_EQ(names[4], "joint4");
  EXPECT_EQ(names[7], "mixamorig:LeftShoulder");
  EXPECT_EQ(names[8], "joint8");
  // The mapping made by itself names them so, and the importer finds them by those names.
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_mapping_skeleton";
  fs::create_directories(dir);
  const fs::path file = dir / "unnamed.glb";
  tinygltf::TinyGLTF gltf;
  ASSERT_TRUE(gltf.WriteGltfSceneToFile(&m, file.string(), true, true, false, true));
  const AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider);
  EXPECT_EQ(a.report.method, "topology");  // the names no longer give every role
  EXPECT_EQ(a.mapping.roles.at("neck"), "joint4");
  EXPECT_EQ(a.mapping.roles.at("lShoulder"), "joint8");
  std::ofstream(dir / "unnamed.json") << autoMappingJson(a).dump(2);
  const CharacterMapping mapping = loadCharacterMapping(dir / "unnamed.json", CharacterKind::Rider);
  const Character c = loadCharacterGltf(file, CharacterKind::Rider, &mapping);
  EXPECT_EQ(c.skeleton.joints[c.role("neck")].name, "joint4");
  EXPECT_EQ(c.skeleton.joints[c.role("lShoulder")].name, "joint8");
}

TEST(GltfMapping, ReadsAVrmFilesOwnHumanoidBoneTableInBothVersions) {
  const StandingHumanoid h = test::coarseHumanoid(HumanoidNames::Vrm);
  tinygltf::Model m = stirrup::test::glbModel(humanoidGlb(h));
  {
    const MappingSkeleton s = mappingSkeletonFromGltf(m, "vrm1.glb");
    EXPECT_EQ(s.vrm_table, "VRMC_vrm");
    EXPECT_EQ(s.vrm_bones.at("leftUpperArm"), s.find("J_Bip_L_UpperArm"));
    EXPECT_EQ(s.vrm_bones.at("hips"), s.find("J_Bip_C_Hips"));
  }
  // VRM 0.x: humanBones an array of {"bone", "node"}; one entry naming a node that is no joint is left out.
  tinygltf::Value::Array bones;
  const auto entry = [](const std::string& bone, int node) {
    tinygltf::Value::Object o;
    o["bone"] = tinygltf::Value(bone);
    o["node"] = tinygltf::Value(node);
    return tinygltf::Value(o);
  };
  const std::vector<int>& joints = m.skins.at(0).joints;
  const int mesh_node = static_cast<int>(m.nodes.size()) - 1;  // the body's node: no joint
  bones.push_back(entry("hips", joints.at(static_cast<std::size_t>(h.character.skeleton.find("J_Bip_C_Hips")))));
  bones.push_back(entry("leftFoot", joints.at(static_cast<std::size_t>(h.character.skeleton.find("J_Bip_L_Foot")))));
  bones.push_back(entry("head", mesh_node));
  tinygltf::Value::Object humanoid_object;
  humanoid_object["humanBones"] = tinygltf::Value(bones);
  tinygltf::Value::Object vrm;
  vrm["humanoid"] = tinygltf::Value(humanoid_object);
  m.extensions.erase("VRMC_vrm");
  m.extensions["VRM"] = tinygltf::Value(vrm);
  const MappingSkeleton s = mappingSkeletonFromGltf(m, "vrm0.glb");
  EXPECT_EQ(s.vrm_table, "VRM");
  EXPECT_EQ(s.vrm_bones, (std::map<std::string, int>{{"hips", s.find("J_Bip_C_Hips")}, {"leftFoot", s.find("J_Bip_L_Foot")}}));
}


}  // namespace
}  // namespace stirrup::rig
