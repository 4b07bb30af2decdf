#include "rig/tack_pose.h"

#include <vector>

#include <gtest/gtest.h>

#include "tests/rig/default_characters.h"
#include "tests/rig/posed_joints.h"

#include "rig/horse_pose.h"
#include "rig/rider_pose.h"

namespace stirrup::rig {
namespace {

using namespace test;  // defaultHorse, defaultRider; pos, at, finite (tests/rig/posed_joints.h)
const Character& horse() { return defaultHorse(); }
const Character& rider() { return defaultRider(); }

TEST(TackPose, StirrupsFollowTheFeet) {
  const Character& h = horse();
  std::vector<glm::mat4> hw = poseHorse(h, HorseFrame{});
  const glm::vec3 before = at(h, hw, "lStirrup");
  RiderChannels ch;
  ch[RiderChannel::lFootTx] = 2.0;
  placeStirrups(h, hw, ch, 2.54);
  EXPECT_NEAR(at(h, hw, "lStirrup").x - before.x, 5.08f, 1e-3f);
  const std::vector<glm::mat4> rw = poseRider(rider(), h, hw, ch, 2.54);
  EXPECT_LT(glm::length(at(rider(), rw, "lBall") - at(h, hw, "lStirrup")), 0.5f);
}

}  // namespace
}  // namespace stirrup::rig
