#include "rig/characters/torso_weights.h"

#include <array>
#include <vector>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// Vertices at the given heights, each 0.6 on the chain's bottom joint (1) and 0.4 on joint 9 off it.
SkinnedMesh torsoAt(const std::vector<float>& heights) {
  SkinnedMesh m;
  for (float y : heights) {
    m.positions.push_back({0.0f, y, 0.0f});
    m.joints.push_back({1, 9, 0, 0});
    m.weights.push_back({0.6f, 0.4f, 0.0f, 0.0f});
  }
  return m;
}

constexpr std::array<int, 3> kChain = {1, 2, 3};

// Evenly spaced (bones 10 cm from 0: middles at 5, 15, 25): at a middle the joint takes the chain's whole
// share and the joint above is listed with none; halfway between two middles they share it; the weight
// off the chain stays; above the top middle the tip joint takes it all.
TEST(SpreadTorsoWeights, EvenlySpacedBonesShareBetweenTheMiddlesAround) {
  SkinnedMesh m = torsoAt({5.0f, 10.0f, 40.0f});
  TorsoChain chain;
  chain.joints = kChain;
  chain.bone = 10.0f;
  spreadTorsoWeights(m, chain);
  EXPECT_EQ(m.joints[0], glm::u16vec4(1, 9, 2, 0));
  EXPECT_FLOAT_EQ(m.weights[0].x, 0.6f);
  EXPECT_FLOAT_EQ(m.weights[0].y, 0.4f);
  EXPECT_EQ(m.weights[0].z, 0.0f);
  EXPECT_EQ(m.joints[1], glm::u16vec4(9, 1, 2, 0));
  EXPECT_FLOAT_EQ(m.weights[1].x, 0.4f);
  EXPECT_FLOAT_EQ(m.weights[1].y, 0.3f);
  EXPECT_FLOAT_EQ(m.weights[1].z, 0.3f);
  EXPECT_EQ(m.joints[2], glm::u16vec4(3, 9, 2, 0));
  EXPECT_FLOAT_EQ(m.weights[2].x, 0.6f);
  EXPECT_EQ(m.weights[2].z, 0.0f);
}

// By listed middles: the same shares, and a joint with no share is not listed.
TEST(SpreadTorsoWeights, ListedMiddlesShareTheSameWayWithoutEmptyShares) {
  const std::array<float, 3> middles = {5.0f, 15.0f, 25.0f};
  SkinnedMesh m = torsoAt({0.0f, 10.0f, 40.0f});
  TorsoChain chain;
  chain.joints = kChain;
  chain.middles = middles;
  spreadTorsoWeights(m, chain);
  EXPECT_EQ(m.joints[0], glm::u16vec4(1, 9, 0, 0));
  EXPECT_FLOAT_EQ(m.weights[0].x, 0.6f);
  EXPECT_EQ(m.joints[1], glm::u16vec4(9, 1, 2, 0));
  EXPECT_FLOAT_EQ(m.weights[1].y, 0.3f);
  EXPECT_FLOAT_EQ(m.weights[1].z, 0.3f);
  EXPECT_EQ(m.joints[2], glm::u16vec4(3, 9, 0, 0));
  EXPECT_FLOAT_EQ(m.weights[2].x + m.weights[2].y, 1.0f);
}

}  // namespace
}  // namespace stirrup::rig
