// Joint names as the conventions' tables compare them, and the convention that names the most roles
// winning. The names below are each tool's own (Mixamo's rig, HumanIK, the UE mannequin, Rigify's
// deform bones, VRoid's exports), written out by hand.
#include "rig/io/skeleton_conventions.h"

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

void expectName(const char* raw, const char* key, int side, const char* tool) {
  const JointName n = normalizeJointName(raw);
  EXPECT_EQ(n.key, key) << raw;
  EXPECT_EQ(n.side, side) << raw;
  EXPECT_EQ(n.tool, tool) << raw;
}

TEST(SkeletonConventions, NormalisesEachToolsNames) {
  expectName("mixamorig:LeftForeArm", "forearm", 1, "mixamo");
  expectName("mixamorig1:RightUpLeg", "upleg", -1, "mixamo");
  expectName("mixamorig_Hips", "hips", 0, "mixamo");
  expectName("mixamorig:HeadTop_End", "headtopend", 0, "mixamo");
  expectName("Character1_LeftHand", "hand", 1, "humanik");
  expectName("LeftInHandMiddle", "inhandmiddle", 1, "");
  expectName("upperarm_twist_01_r", "upperarmtwist01", -1, "");
  expectName("neck_01", "neck01", 0, "");
  expectName("ball_l", "ball", 1, "");
  expectName("DEF-upper_arm.L.001", "upperarm001", 1, "rigify");
  expectName("DEF-spine.004", "spine004", 0, "rigify");
  expectName("DEF-palm.02.R", "palm02", -1, "rigify");
  expectName("J_Bip_C_Hips", "hips", 0, "vroid");
  expectName("J_Bip_L_UpperArm", "upperarm", 1, "vroid");
  expectName("J_Adj_R_Palm", "palm", -1, "vroid");
  expectName("leftUpperArm", "upperarm", 1, "");   // VRM's humanoid bone names
  expectName("HandRight", "hand", -1, "");         // a side at the end of a camel-case word
  expectName("Bone.012", "bone012", 0, "");
  // Words that only look like a side keep it.
  expectName("Upright", "upright", 0, "");
  expectName("Leftover", "leftover", 0, "");
  expectName("L", "l", 0, "");  // a name that is nothing but a side letter is no side
}

// A small named skeleton: positions only matter for its hierarchy here.
MappingSkeleton namedSkeleton(const std::vector<std::pair<std::string, int>>& joints) {
  MappingSkeleton s;
  s.file = "test.glb";
  for (const auto& [name, parent] : joints) {
    s.names.push_back(name);
    s.parent.push_back(parent);
    s.position.emplace_back(0.0, static_cast<double>(s.names.size()), 0.0);
    s.weighted.push_back(1);
    s.hung.push_back(0);
  }
  s.finish();
  return s;
}

TEST(SkeletonConventions, TheConventionNamingTheMostRolesWins) {
  // HumanIK's names, bare: humanik names every rider role; mixamo none (no prefix); VRM only those it
  // shares (hips, neck, head, hand, foot).
  const MappingSkeleton s = namedSkeleton({{"Hips", -1},         {"Spine", 0},          {"Spine1", 1},        {"Neck", 2},
                                           {"Head", 3},          {"LeftShoulder", 2},   {"LeftArm", 5},       {"LeftForeArm", 6},
                                           {"LeftHand", 7},      {"RightShoulder", 2},  {"RightArm", 9},      {"RightForeArm", 10},
                                           {"RightHand", 11},    {"LeftUpLeg", 0},      {"LeftLeg", 13},      {"LeftFoot", 14},
                                           {"LeftToeBase", 15},  {"RightUpLeg", 0},     {"RightLeg", 17},     {"RightFoot", 18},
                                           {"RightToeBase", 19}});
  const std::vector<NamedRoles> found = rolesByNames(s, CharacterKind::Rider);
  ASSERT_FALSE(found.empty());
  EXPECT_EQ(found[0].convention, "humanik");
  EXPECT_TRUE(found[0].missing.empty());
  EXPECT_EQ(found[0].roles.at("lShoulder"), 6);  // LeftArm: the upper arm's root, not the clavicle
  EXPECT_EQ(found[0].roles.at("rBall"), 20);
  EXPECT_EQ(found[0].score, 17);  // the 15 required roles and both balls (no grip: no palm joint)
  for (const NamedRoles& r : found) EXPECT_NE(r.convention, "mixamo");
}

TEST(SkeletonConventions, RigifysNeckIsTwoJointsBelowItsHead) {
  const MappingSkeleton s = namedSkeleton({{"DEF-spine", -1},     {"DEF-spine.001", 0}, {"DEF-spine.002", 1}, {"DEF-spine.003", 2},
                                           {"DEF-spine.004", 3},  {"DEF-spine.005", 4}, {"DEF-spine.006", 5}, {"DEF-spine.006_end", 6}});
  const std::vector<NamedRoles> found = rolesByNames(s, CharacterKind::Rider);
  const auto rigify = std::find_if(found.begin(), found.end(), [](const NamedRoles& r) { return r.convention == "rigify"; });
  ASSERT_NE(rigify, found.end());
  EXPECT_EQ(rigify->roles.at("pelvis"), 0);
  EXPECT_EQ(rigify->roles.at("head"), 6);
  EXPECT_EQ(rigify->roles.at("neck"), 4);
}

TEST(SkeletonConventions, StirrupsOwnRoleNamesAreAConvention) {
  const MappingSkeleton s = namedSkeleton({{"root", -1}, {"backMid", 0}, {"saddle", 1}, {"lStirrup", 2}, {"Tail", 0}, {"Stirrup.R", 2}});
  const std::vector<NamedRoles> found = rolesByNames(s, CharacterKind::Horse);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].convention, "stirrup");
  EXPECT_EQ(found[0].roles, (std::map<std::string, int>{{"root", 0}, {"backMid", 1}, {"saddle", 2}, {"lStirrup", 3}}));
  // Found by its key: a side of its own ("Stirrup.R"), not stirrup's "l" prefix.
  EXPECT_EQ(jointByKey(s, "stirrup", -1), 5);
  EXPECT_EQ(jointByKey(s, "stirrup", 1), -1);
}

}  // namespace
}  // namespace stirrup::rig
