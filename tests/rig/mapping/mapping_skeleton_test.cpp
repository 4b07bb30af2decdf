// A file's skeleton as the automatic mapping reads it: loose roots hung from the trunk (a detached pair of
// limbs from one joint), the weighted joints, and a Rigify rig's deform bones hung as Rigify means them.
// Reading one from a glTF file (names, a VRM bone table) is tests/rig/io/gltf_mapping_test.cpp.
#include "rig/mapping/mapping_skeleton.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/characters/standing_humanoid.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_humanoid.h"
#include "rig/io/gltf_mapping.h"
#include "rig/mapping/auto_mapping.h"
#include "rig/mapping/character_mapping.h"
#include "tests/rig/user_riders.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

TEST(MappingSkeleton, DetachedLimbsHangFromTheTrunkBothFromOneJoint) {
  // The Rigify layout as Blender exports its deform bones: clavicles, upper arms and thighs are roots.
  const StandingHumanoid h = test::coarseHumanoid(HumanoidNames::Rigify);
  const MappingSkeleton s = mappingSkeletonFromGltf(stirrup::test::glbModel(humanoidGlb(h)), "rigify.glb");
  for (const char* side : {".L", ".R"}) {
    for (const std::string limb : {"DEF-shoulder", "DEF-upper_arm", "DEF-thigh"}) {
      const int j = s.find(limb + side);
      ASSERT_GE(j, 0) << limb << side;
      EXPECT_TRUE(s.hung[j]) << limb << side;
      // Hung from a joint of the spine (DEF-spine...), never from another loose limb.
      EXPECT_EQ(s.names[s.parent[j]].rfind("DEF-spine", 0), 0u) << limb << side << " hangs from " << s.names[s.parent[j]];
    }
  }
  EXPECT_EQ(s.parent[s.find("DEF-thigh.L")], s.find("DEF-spine"));  // the hip joints' nearest trunk joint: the pelvis
  EXPECT_EQ(s.parent[s.find("DEF-upper_arm.L")], s.parent[s.find("DEF-upper_arm.R")]);
  EXPECT_FALSE(s.hung[s.find("DEF-forearm.L")]);  // its parent is in the file
  EXPECT_EQ(s.parent[s.find("DEF-forearm.L")], s.find("DEF-upper_arm.L.001"));
  // Weighted joints: the body's; not the unweighted ends of the chains.
  EXPECT_TRUE(s.weighted[s.find("DEF-spine.001")]);
  EXPECT_EQ(s.vertices.size(), s.vertex_joint.size());
  EXPECT_GT(s.vertices.size(), 1000u);
}

TEST(MappingSkeleton, RigifysDeformBonesHangFromTheDeformBonesOfTheirOriginalsParents) {
  // An all-bones export of a generated Rigify rig, in part: the DEF- bones' parents are ORG- copies of
  // the meta-rig (or controls above them), as Blender writes them.
  const std::vector<std::string> names = {"root",           "DEF-spine.001", "tweak_spine.005", "ORG-spine.005",  "DEF-spine.005",
                                          "ORG-shoulder.L", "DEF-shoulder.L", "DEF-upper_arm.L", "DEF-upper_arm.L.001", "ORG-head",
                                          "DEF-head",       "ORG-skull",      "DEF-skull",       "MCH-jaw_master", "DEF-jaw"};
  std::vector<int> parent = {-1, 0, 0, 2, 1, 3, 5, 5, 7, 3, 4, 9, 11, 9, 13};
  rigifyDeformParents(parent, names);
  const auto parentOf = [&](const std::string& n) {
    const int j = static_cast<int>(std::find(names.begin(), names.end(), n) - names.begin());
    return parent[j] < 0 ? std::string("-") : names[parent[j]];
  };
  EXPECT_EQ(parentOf("DEF-upper_arm.L"), "DEF-shoulder.L");      // ORG-shoulder.L's deform bone
  EXPECT_EQ(parentOf("DEF-shoulder.L"), "DEF-spine.005");        // its own original's parent's
  EXPECT_EQ(parentOf("DEF-skull"), "DEF-head");                  // past its own ORG-skull to ORG-head's
  EXPECT_EQ(parentOf("DEF-jaw"), "DEF-head");                    // past the mechanism bone
  EXPECT_EQ(parentOf("DEF-upper_arm.L.001"), "DEF-upper_arm.L");  // a deform parent is kept
  EXPECT_EQ(parentOf("DEF-spine.001"), "root");                  // no ORG- bone above: as the file has it
  EXPECT_EQ(parentOf("ORG-head"), "ORG-spine.005");               // other bones keep their parents
}

}  // namespace
}  // namespace stirrup::rig
