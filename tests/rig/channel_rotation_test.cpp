// The contract's rotation channels as a rotation and back (rig/channel_rotation.h): each channel alone
// turns about the axis its meaning says (docs/channels.md), and angles come back as they went in.
#include "rig/channel_rotation.h"

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

glm::dvec3 turned(const glm::dquat& q, glm::dvec3 v) { return q * v; }

TEST(ChannelRotation, EachChannelTurnsAboutItsAxisByItsMeaning) {
  // rz + pitches the front (+X) up.
  EXPECT_GT(turned(rotationFromChannels(0, 0, 30), {1, 0, 0}).y, 0.49);
  // rx + rolls toward the right: the top (+Y) goes toward the right (+Z).
  EXPECT_GT(turned(rotationFromChannels(30, 0, 0), {0, 1, 0}).z, 0.49);
  // ry + yaws right: the front (+X) turns toward the right (+Z).
  EXPECT_GT(turned(rotationFromChannels(0, 30, 0), {1, 0, 0}).z, 0.49);
}

TEST(ChannelRotation, AnglesComeBackAsTheyWentIn) {
  for (const glm::dvec3 a : {glm::dvec3(10, -20, 35), glm::dvec3(-5, 40, -60), glm::dvec3(0, 0, 0), glm::dvec3(80, 3, -1)}) {
    const auto back = channelsFromRotation(rotationFromChannels(a.x, a.y, a.z));
    EXPECT_NEAR(back[0], a.x, 1e-9);
    EXPECT_NEAR(back[1], a.y, 1e-9);
    EXPECT_NEAR(back[2], a.z, 1e-9);
  }
}

}  // namespace
}  // namespace stirrup::rig
