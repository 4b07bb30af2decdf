// Character mappings (rig/mapping/character_mapping.cpp): the roles each kind needs and may name, the order
// roles must keep on the skeleton, and the file's space to stirrup's, worked out by hand. Reading a mapping
// file is tests/rig/io/character_mapping_json_test.cpp.
#include "rig/mapping/character_mapping.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// The header's lists: the horse's root, neck1, head and 4 legs x (Upper, Middle, Fetlock, Hoof) = 19;
// the rider's pelvis, neck, head and 2 sides x (Shoulder, Elbow, Wrist, Hip, Knee, Ankle) = 15.
TEST(CharacterMapping, TheRolesEachKindNeeds) {
  EXPECT_EQ(requiredRoles(CharacterKind::Horse).size(), 19u);
  EXPECT_EQ(requiredRoles(CharacterKind::Horse).front(), "root");
  EXPECT_EQ(requiredRoles(CharacterKind::Rider).size(), 15u);
  EXPECT_EQ(requiredRoles(CharacterKind::Rider)[3], "lShoulder");
  const std::vector<std::string>& horse = optionalRoles(CharacterKind::Horse);
  EXPECT_NE(std::find(horse.begin(), horse.end(), "lRein"), horse.end());
  const std::vector<std::string>& rider = optionalRoles(CharacterKind::Rider);
  EXPECT_NE(std::find(rider.begin(), rider.end(), "spine10"), rider.end());
  EXPECT_NE(std::find(rider.begin(), rider.end(), "rBall"), rider.end());
  EXPECT_EQ(characterKindName(CharacterKind::Horse), "horse");
}

// A rider: pelvis 0 -> spine 1 -> neck 2 -> head 3; shoulder 4 on the spine, elbow 5, wrist 6.
TEST(CharacterMapping, RolesKeepTheirOrderOnTheSkeleton) {
  const std::vector<int> parent = {-1, 0, 1, 2, 1, 4, 5};
  const std::vector<std::string> names = {"Hips", "Spine", "Neck", "Head", "LeftArm", "LeftForeArm", "LeftHand"};
  std::map<std::string, int> roles = {{"pelvis", 0}, {"neck", 2}, {"head", 3}, {"lShoulder", 4}, {"lElbow", 5}, {"lWrist", 6}};
  EXPECT_EQ(roleChainProblem(CharacterKind::Rider, roles, parent, names), "");
  roles["lElbow"] = 6, roles["lWrist"] = 5;  // swapped: the elbow is still below the shoulder, the wrist is not below it
  EXPECT_EQ(roleChainProblem(CharacterKind::Rider, roles, parent, names),
            "roles.lWrist: joint \"LeftForeArm\" is not below lElbow \"LeftHand\" (expected the wrist on the arm's chain "
            "below the elbow)");
  roles = {{"pelvis", 0}, {"neck", 1}};  // no spine joint between
  EXPECT_EQ(roleChainProblem(CharacterKind::Rider, roles, parent, names, "see docs/characters.md"),
            "roles.neck: joint \"Spine\" is not above pelvis \"Hips\" with a spine joint between them (expected the neck "
            "on the chain that runs up from the pelvis; see docs/characters.md)");
  // A horse's tail must not hold the body.
  EXPECT_EQ(roleChainProblem(CharacterKind::Horse, {{"tail1", 0}, {"root", 1}}, {-1, 0}, {"Tail", "Hips"}),
            "roles.tail1: joint \"Tail\" holds root \"Hips\" (expected the tail's first joint, on a chain of its own "
            "behind the hips)");
}

// The file's axes are the rows: x_rig = fw . p, y_rig = up . p, z_rig = (fw x up) . p, times 100 cm a
// unit, then the offset. Here forward is the file's +Z, up its +Y, and the offset 90 cm down.
TEST(CharacterMapping, TheFilesSpaceToStirrups) {
  CharacterMapping m;
  m.scale_cm = 100.0;
  m.forward = {0, 0, 1};
  m.offset_cm = {0, -90, 0};
  const glm::dmat4 to_rig = mappingToRig(m);
  const auto apply = [&](glm::dvec3 p) { return glm::dvec3(to_rig * glm::dvec4(p, 1.0)); };
  // The file's forward (0, 0, 1), 1 m: stirrup's +X, 100 cm; its up 1 m: 100 cm up less the offset's 90.
  const glm::dvec3 ahead = apply({0, 0, 1}), above = apply({0, 1, 0}), side = apply({1, 0, 0});
  EXPECT_NEAR(ahead.x, 100.0, 1e-12);
  EXPECT_NEAR(ahead.y, -90.0, 1e-12);
  EXPECT_NEAR(above.y, 10.0, 1e-12);
  // fw x up = (0, 0, 1) x (0, 1, 0) = (-1, 0, 0): the file's +X is stirrup's -Z (its left).
  EXPECT_NEAR(side.z, -100.0, 1e-12);
  EXPECT_NEAR(side.x, 0.0, 1e-12);
  EXPECT_EQ(mappingToRig(CharacterMapping{}), glm::dmat4(1.0));  // the defaults change nothing
}

}  // namespace
}  // namespace stirrup::rig
