// The rider's spine as posing reads it (rig/rider_spine.cpp), from small hand-made skeletons: the chain
// from the pelvis toward the neck, its rest points and arc lengths, where the three FK bones split it,
// and one-line errors for roles that make no spine. The generator's rider (laid on the curve) is
// covered by the posing tests (rider_pose_test.cpp, balance_test.cpp).
#include "rig/rider_spine.h"

#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

glm::mat4 up(float cm) { return glm::translate(glm::mat4(1.0f), {0.0f, cm, 0.0f}); }

// pelvis at 100 cm; spine joints s1.. straight up by `bones` (cm) each from the one below; the neck
// `neck_cm` above the last. Roles pelvis and neck, and `roles` (role -> joint name).
Character rider(const std::vector<float>& bones, float neck_cm, const std::map<std::string, std::string>& roles = {}) {
  Character c;
  c.name = "test rider";
  int parent = c.skeleton.addJoint("pelvis", -1, up(100.0f));
  for (std::size_t i = 0; i < bones.size(); ++i) {
    std::string name = "s";
    name += std::to_string(i + 1);
    parent = c.skeleton.addJoint(name, parent, up(bones[i]));
  }
  c.skeleton.addJoint("neck", parent, up(neck_cm));
  c.roles = {{"pelvis", c.skeleton.find("pelvis")}, {"neck", c.skeleton.find("neck")}};
  for (const auto& [role, joint] : roles) c.roles[role] = c.skeleton.find(joint);
  return c;
}

std::string errorOf(const Character& c) {
  try {
    riderSpine(c);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

// Chain s1 s2 s3 (the neck hangs from s3, the chain's top): points 10, 20 and 32 cm above the pelvis,
// arc 0, 10, 22; without controller roles the three FK bones are thirds of 22 cm.
TEST(RiderSpine, TheChainRunsFromThePelvisToTheJointTheNeckHangsFrom) {
  const Character c = rider({10, 10, 12}, 6);
  const RiderSpine sp = riderSpine(c);
  EXPECT_EQ(sp.chain, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(sp.pelvis, 0);
  EXPECT_EQ(sp.neck, 4);
  EXPECT_FALSE(sp.ends_at_neck);
  ASSERT_EQ(sp.points.size(), 3u);
  EXPECT_NEAR(sp.points[2].y, 32.0, 1e-5);
  EXPECT_EQ(sp.points[2].x, 0.0);
  ASSERT_EQ(sp.arc.size(), 3u);
  EXPECT_NEAR(sp.arc[1], 10.0, 1e-5);
  EXPECT_NEAR(sp.arc[2], 22.0, 1e-5);
  for (double l : sp.fk_lengths) EXPECT_NEAR(l, 22.0 / 3.0, 1e-5);
  EXPECT_NEAR(sp.root.y, 10.0f, 1e-5f);
  EXPECT_EQ(sp.controllers, (std::array<int, 3>{-1, -1, -1}));
  EXPECT_FALSE(sp.laid_on_curve);
}

// Controller roles on the chain split it where they are: at arc 0, 10 and 22 of 30 cm: bones 10, 12, 8.
TEST(RiderSpine, ControllersOnTheChainSplitItWhereTheyAre) {
  const Character c = rider({10, 10, 12, 8}, 6, {{"lowerBack", "s1"}, {"waist", "s2"}, {"chest", "s3"}});
  const RiderSpine sp = riderSpine(c);
  EXPECT_NEAR(sp.fk_lengths[0], 10.0, 1e-5);
  EXPECT_NEAR(sp.fk_lengths[1], 12.0, 1e-5);
  EXPECT_NEAR(sp.fk_lengths[2], 8.0, 1e-5);
  EXPECT_EQ(sp.controllers, (std::array<int, 3>{-1, -1, -1}));  // on the chain: not posed as joints of their own
  // Out of order (waist above chest) they say nothing: thirds of 30.
  const RiderSpine swapped = riderSpine(rider({10, 10, 12, 8}, 6, {{"lowerBack", "s1"}, {"waist", "s3"}, {"chest", "s2"}}));
  for (double l : swapped.fk_lengths) EXPECT_NEAR(l, 10.0, 1e-5);
}

TEST(RiderSpine, UpperChestEndsTheChainAndOneJointBendsToTheNeck) {
  const RiderSpine chest = riderSpine(rider({10, 10, 12, 8}, 6, {{"upperChest", "s2"}}));
  EXPECT_EQ(chest.chain, (std::vector<int>{1, 2}));
  EXPECT_NEAR(chest.arc.back(), 10.0, 1e-5);
  // One spine joint: its curve runs on to the neck, 14 cm above it.
  const RiderSpine one = riderSpine(rider({10}, 14));
  EXPECT_EQ(one.chain, (std::vector<int>{1}));
  EXPECT_TRUE(one.ends_at_neck);
  ASSERT_EQ(one.points.size(), 2u);
  EXPECT_NEAR(one.points[1].y, 24.0, 1e-5);
  EXPECT_NEAR(one.arc[1], 14.0, 1e-5);
}

TEST(RiderSpine, RolesThatMakeNoSpineAreOneLineErrors) {
  EXPECT_EQ(errorOf(rider({}, 20)),
            "roles.neck: joint \"neck\" is not below the pelvis joint \"pelvis\" with at least one spine joint between "
            "them (map the neck to a joint of the chain that runs up from the pelvis)");
  Character side = rider({10, 10}, 6);
  side.skeleton.addJoint("arm", 1, up(5.0f));
  side.roles["upperChest"] = side.skeleton.find("arm");
  EXPECT_EQ(errorOf(side),
            "roles.upperChest: joint \"arm\" is not between the pelvis \"pelvis\" and the neck \"neck\" (map it to the "
            "spine joint the shoulders hang from, or leave it out)");
  EXPECT_EQ(errorOf(rider({0}, 0)), "roles.neck: the spine from \"pelvis\" to \"neck\" has no length at rest");
}

}  // namespace
}  // namespace stirrup::rig
