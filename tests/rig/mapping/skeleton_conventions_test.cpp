// Joint names as the conventions' tables compare them, and the convention that names the most roles
// winning. The names below are each tool's own (Mixamo's rig, HumanIK, the UE mannequin, Rigify's
// deform bones, VRoid's exports, Rigify's horse meta-rig, 3ds Max's Biped), written out by hand; the
// horses are the stick horse (tests/rig/io/stick_horse.h) under those names, whose roles its anatomy
// gives.
#include "rig/mapping/skeleton_conventions.h"

#include <gtest/gtest.h>

#include "tests/rig/io/stick_horse.h"

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
  // Rigify's horse: a rear leg's "r_" is no side; the last side token is.
  expectName("r_toe.L", "rtoe", 1, "");
  expectName("DEF-r_hoof.R", "rhoof", -1, "rigify");
  expectName("DEF-forefoot.L.001", "forefoot001", 1, "rigify");
  expectName("spine.006", "spine006", 0, "");
  // Rigify's ORG- and MCH- bones are helpers: never a role.
  expectName("ORG-forearm.L", "forearm", 1, "rigify");
  EXPECT_TRUE(normalizeJointName("ORG-forearm.L").helper);
  EXPECT_TRUE(normalizeJointName("MCH-thigh_parent.L").helper);
  EXPECT_FALSE(normalizeJointName("DEF-forearm.L").helper);
  // 3ds Max Biped: the root name goes.
  expectName("Bip01 L HorseLink", "horselink", 1, "biped");
  expectName("Bip001 Spine1", "spine1", 0, "biped");
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

// ---- Horses.

// The stick horse under other names (`names`: its joint -> the new name), with `extra` joints added
// beside it: {name, the stick joint whose place and parent it takes}.
MappingSkeleton renamedHorse(const std::map<std::string, std::string>& names,
                             const std::vector<std::pair<std::string, std::string>>& extra = {}) {
  MappingSkeleton s = test::stickHorse();
  for (std::string& n : s.names)
    if (const auto it = names.find(n); it != names.end()) n = it->second;
  for (const auto& [name, beside] : extra) {
    const int j = s.find(names.count(beside) ? names.at(beside) : beside);
    s.names.push_back(name);
    s.parent.push_back(s.parent[j]);
    s.position.push_back(s.position[j]);
    s.weighted.push_back(0);
    s.hung.push_back(0);
  }
  s.finish();
  return s;
}

// Role -> joint name, through `names`.
std::map<std::string, std::string> renamedRoles(std::map<std::string, std::string> roles, const std::map<std::string, std::string>& names) {
  for (auto& [role, joint] : roles) joint = names.at(joint);
  return roles;
}

std::map<std::string, std::string> namedRoles(const MappingSkeleton& s, const NamedRoles& r) {
  std::map<std::string, std::string> out;
  for (const auto& [role, j] : r.roles) out[role] = s.names[j];
  return out;
}

// Blender's Rigify horse meta-rig's names for the stick horse's joints (rigify/metarigs/Animals/horse.py),
// with `prefix` ("DEF-" for the generated rig's deform bones).
std::map<std::string, std::string> rigifyHorseNames(const std::string& prefix) {
  std::map<std::string, std::string> n = {{"head", "head"}, {"jaw", "jaw"}, {"jawTip", "jaw.001"}, {"mane2", "mane_base.02"},
                                          {"mane2Top", "mane_top.02"}, {"mane3", "mane_base.03"}, {"mane3Top", "mane_top.03"}};
  for (int i = 1; i <= 6; ++i) n["spine" + std::to_string(i)] = "spine.00" + std::to_string(i);
  for (int i = 1; i <= 3; ++i) n["neck" + std::to_string(i)] = "neck.00" + std::to_string(i), n["tail" + std::to_string(i)] = "tail.00" + std::to_string(i);
  for (const std::string side : {"L", "R"})
    for (const auto& [stick, rigify] : std::vector<std::pair<std::string, std::string>>{
             {"scapula", "shoulder"}, {"shoulder", "upper_arm"}, {"elbow", "forearm"}, {"knee", "forefoot"}, {"foreFetlock", "f_toe"},
             {"foreHoof", "f_hoof"}, {"pelvis", "pelvis"}, {"thigh", "thigh"}, {"stifle", "lower_leg"}, {"hock", "hind_foot"},
             {"hindFetlock", "r_toe"}, {"hindHoof", "r_hoof"}, {"ear", "ear"}, {"earTip", "ear.001"}, {"nostril", "nose"}, {"breast", "breast"}})
      n[stick + side] = rigify == "ear.001" ? "ear." + side + ".001" : rigify + "." + side;
  for (auto& [stick, name] : n) name = prefix + name;
  n["saddle"] = "saddle";
  return n;
}

TEST(SkeletonConventions, RigifysHorseMapsByItsMetarigNames) {
  const std::map<std::string, std::string> names = rigifyHorseNames("");
  const MappingSkeleton s = renamedHorse(names);
  const std::vector<NamedRoles> found = rolesByNames(s, CharacterKind::Horse);
  ASSERT_FALSE(found.empty());
  EXPECT_EQ(found[0].convention, "rigify horse");
  EXPECT_EQ(found[0].form, "metarig names");
  EXPECT_TRUE(found[0].missing.empty());
  std::map<std::string, std::string> expected = renamedRoles(test::stickHorseRoles(), names);
  expected["withers"] = "spine.006";  // the back's joint nearest the scapulae's pivots
  EXPECT_EQ(namedRoles(s, found[0]), expected);
}

TEST(SkeletonConventions, RigifysGeneratedRigMapsByItsDeformBonesNeverItsHelpersOrControls) {
  // An all-bones export: beside each DEF- bone its ORG- copy and a control at the same place; the
  // controls "head", "shoulder.L" and "thigh_ik.L" carry no prefix, the mechanism bones MCH-.
  const std::map<std::string, std::string> names = rigifyHorseNames("DEF-");
  std::vector<std::pair<std::string, std::string>> extra;
  for (const auto& [stick, def] : names)
    if (def.rfind("DEF-", 0) == 0) extra.push_back({"ORG-" + def.substr(4), stick});
  for (const auto& [control, beside] : std::vector<std::pair<std::string, std::string>>{
           {"head", "head"}, {"shoulder.L", "scapulaL"}, {"shoulder.R", "scapulaR"}, {"thigh_ik.L", "thighL"}, {"MCH-forearm.L", "elbowL"}})
    extra.push_back({control, beside});
  const MappingSkeleton s = renamedHorse(names, extra);
  const std::vector<NamedRoles> found = rolesByNames(s, CharacterKind::Horse);
  ASSERT_FALSE(found.empty());
  EXPECT_EQ(found[0].convention, "rigify horse");
  EXPECT_EQ(found[0].form, "deform bones");
  std::map<std::string, std::string> expected = renamedRoles(test::stickHorseRoles(), names);
  expected["withers"] = "DEF-spine.006";
  EXPECT_EQ(namedRoles(s, found[0]), expected);
}

TEST(SkeletonConventions, ABipedHorseMapsByBipedsNames) {
  // 3ds Max Biped with four leg links: Pelvis, Spine.., Neck.., Head, Tail.., the arms as fore legs
  // (Clavicle the scapula, Hand the cannon), the legs' HorseLink the hind cannon.
  std::map<std::string, std::string> names = {{"spine1", "Bip01 Pelvis"}, {"spine2", "Bip01 Spine"}, {"spine3", "Bip01 Spine1"},
                                               {"spine4", "Bip01 Spine2"}, {"spine5", "Bip01 Spine3"}, {"spine6", "Bip01 Spine4"},
                                               {"neck1", "Bip01 Neck"},    {"neck2", "Bip01 Neck1"},   {"neck3", "Bip01 Neck2"},
                                               {"head", "Bip01 Head"},     {"tail1", "Bip01 Tail"},    {"tail2", "Bip01 Tail1"},
                                               {"tail3", "Bip01 Tail2"}};
  for (const std::string side : {"L", "R"})
    for (const auto& [stick, biped] : std::vector<std::pair<std::string, std::string>>{
             {"scapula", "Clavicle"}, {"shoulder", "UpperArm"}, {"elbow", "Forearm"}, {"knee", "Hand"}, {"foreFetlock", "Finger0"},
             {"foreHoof", "Finger01"}, {"thigh", "Thigh"}, {"stifle", "Calf"}, {"hock", "HorseLink"}, {"hindFetlock", "Foot"},
             {"hindHoof", "Toe0"}})
      names[stick + side] = "Bip01 " + side + " " + biped;
  const MappingSkeleton s = renamedHorse(names);
  const std::vector<NamedRoles> found = rolesByNames(s, CharacterKind::Horse);
  ASSERT_FALSE(found.empty());
  EXPECT_EQ(found[0].convention, "3ds max biped");
  std::map<std::string, std::string> expected = renamedRoles(test::stickHorseRoles(), names);
  expected["withers"] = "Bip01 Spine4";
  EXPECT_EQ(namedRoles(s, found[0]), expected);
}

}  // namespace
}  // namespace stirrup::rig
