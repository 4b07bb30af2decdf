// The default rider (rig/characters/rider_character.cpp): every role its header lists, the spine's
// controllers and chain straight up from the lower back in equal bones, the balls of her feet on the
// horse's stirrup treads and her hands on the rein grips (MountParams), her limbs as long as their
// parameters, and the trunk-only rider. Values from RiderParams' and MountParams' defaults.
#include "rig/characters/rider_character.h"

#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "rig/rider_spine.h"
#include "tests/rig/default_characters.h"

namespace stirrup::rig {
namespace {

using test::defaultRider;

void expectAt(const Character& c, const std::string& role, glm::vec3 want, float tol = 1e-4f) {
  const glm::vec3 p = c.skeleton.restPosition(c.role(role));
  EXPECT_NEAR(p.x, want.x, tol) << role;
  EXPECT_NEAR(p.y, want.y, tol) << role;
  EXPECT_NEAR(p.z, want.z, tol) << role;
}
float between(const Character& c, const std::string& a, const std::string& b) {
  return glm::distance(c.skeleton.restPosition(c.role(a)), c.skeleton.restPosition(c.role(b)));
}

TEST(RiderCharacter, HasEveryRoleItsHeaderLists) {
  const Character& r = defaultRider();
  for (const char* role : {"pelvis", "lowerBack", "waist", "chest", "upperChest", "neck", "head", "braid1", "braid2",
                           "braid3", "coatTail"})
    EXPECT_NO_THROW(r.role(role)) << role;
  for (const char* side : {"l", "r"})
    for (const char* part : {"Shoulder", "Elbow", "Wrist", "Hand", "Hip", "Knee", "Ankle", "Ball"})
      EXPECT_NO_THROW(r.role(std::string(side) + part)) << side << part;
  for (int i = 0; i <= kRiderSpineSegments; ++i) EXPECT_NO_THROW(r.role("spine" + std::to_string(i))) << i;
  EXPECT_EQ(r.role("spine" + std::to_string(kRiderSpineSegments)), r.role("upperChest"));
}

// The lower back at (-4, 17, 0); the controllers straight above it at the waist's and chest's heights
// (27, 38); the chain from 17 to the upper chest's 48 cm in ten bones of 3.1 cm.
TEST(RiderCharacter, TheSpineStandsStraightUpInEqualBones) {
  const Character& r = defaultRider();
  expectAt(r, "pelvis", {-3, 10, 0});
  expectAt(r, "lowerBack", {-4, 17, 0});
  expectAt(r, "waist", {-4, 27, 0});
  expectAt(r, "chest", {-4, 38, 0});
  for (int i = 0; i <= kRiderSpineSegments; ++i) expectAt(r, "spine" + std::to_string(i), {-4, 17 + 3.1f * i, 0});
  expectAt(r, "neck", {-3.5f, 57, 0});
  expectAt(r, "head", {-2.5f, 66, 0});
  EXPECT_TRUE(riderSpine(r).laid_on_curve);  // posing lays this chain on the curve (rig/rider_spine.h)
}

// Feet: the ball on the tread (0, -74, -31), the ankle 12 cm behind and 7 cm above it. Hands: on the
// grip (34, 16, -6), the wrist at grip + (-6, 1, -1). The right side mirrored. Thigh and shin 45 cm,
// upper arm 29 cm and forearm 25 cm, the knee and elbow bent where they meet.
TEST(RiderCharacter, FeetOnTheTreadsHandsOnTheReinsLimbsTheirLength) {
  const Character& r = defaultRider();
  expectAt(r, "lBall", {0, -74, -31});
  expectAt(r, "rBall", {0, -74, 31});
  expectAt(r, "lAnkle", {-12, -67, -31});
  expectAt(r, "lHand", {34, 16, -6});
  expectAt(r, "rHand", {34, 16, 6});
  expectAt(r, "lWrist", {28, 17, -7});
  expectAt(r, "rWrist", {28, 17, 7});
  expectAt(r, "lHip", {-2, 10, -12.5f});
  expectAt(r, "lShoulder", {-4.5f, 50, -17});
  for (const char* s : {"l", "r"}) {
    const std::string n = s;
    EXPECT_NEAR(between(r, n + "Hip", n + "Knee"), 45.0f, 1e-3f) << n;
    EXPECT_NEAR(between(r, n + "Knee", n + "Ankle"), 45.0f, 1e-3f) << n;
    EXPECT_NEAR(between(r, n + "Shoulder", n + "Elbow"), 29.0f, 1e-3f) << n;
    EXPECT_NEAR(between(r, n + "Elbow", n + "Wrist"), 25.0f, 1e-3f) << n;
  }
}

TEST(RiderCharacter, TheTrunkAloneHasTheSpineAndNoMesh) {
  const Character trunk = buildRiderTrunk(RiderParams{});
  EXPECT_TRUE(trunk.mesh.positions.empty());
  expectAt(trunk, "lowerBack", {-4, 17, 0});
  expectAt(trunk, "upperChest", {-4, 48, 0});
  expectAt(trunk, "head", {-2.5f, 66, 0});
  EXPECT_THROW(trunk.role("lHand"), std::out_of_range);
}

}  // namespace
}  // namespace stirrup::rig
