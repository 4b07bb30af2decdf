#include "rig/pose.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/rig/default_characters.h"

namespace stirrup::rig {
namespace {

using namespace test;  // defaultHorse, defaultRider
const Character& horse() { return defaultHorse(); }
const Character& rider() { return defaultRider(); }

// The reins run from the bit to the rider's hands: wherever the wrist channels move the hands, the
// horse's rein ends (lRein, rRein) are where the hands close on the reins (lHand, rHand).
TEST(PoseMounted, ReinsEndInTheRidersHands) {
  const Character& h = horse();
  const Character& r = rider();
  HorseFrame f;
  f.controls[HorseChannel::rearPivotRz] = 10.0;
  RiderChannels ch;
  ch[RiderChannel::lWristTx] = 1.5;
  ch[RiderChannel::rWristTy] = -1.0;
  const MountedPose p = poseMounted(h, r, f, ch, RigProfile::thesis());
  for (const char* side : {"l", "r"}) {
    const glm::vec3 rein = glm::vec3(p.horse[h.role(std::string(side) + "Rein")][3]);
    const glm::vec3 hand = glm::vec3(p.rider[r.role(std::string(side) + "Hand")][3]);
    EXPECT_LT(glm::length(rein - hand), 1e-4f) << side;
    EXPECT_GT(glm::length(rein - h.skeleton.restPosition(h.role(std::string(side) + "Rein"))), 5.0f) << side;
  }
}

}  // namespace
}  // namespace stirrup::rig
