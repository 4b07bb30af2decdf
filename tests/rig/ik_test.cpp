#include "rig/ik.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TwoBoneIkInput leg(glm::vec3 target) {
  TwoBoneIkInput in;
  in.root = {0, 100, 0};
  in.upper_length = 45;
  in.lower_length = 40;
  in.target = target;
  in.pole = {100, 50, 0};  // knee forward
  return in;
}

TEST(TwoBoneIk, ReachesReachableTargetsWithinOneMillimetre) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int tried = 0;
  while (tried < 500) {
    glm::vec3 dir(u(rng), u(rng), u(rng));
    if (glm::length(dir) < 0.1f) continue;
    dir = glm::normalize(dir);
    // Between just past the fold limit and full reach (85 cm).
    const float dist = 6.0f + (84.9f - 6.0f) * (0.5f + 0.5f * u(rng));
    TwoBoneIkInput in = leg(glm::vec3(0, 100, 0) + dir * dist);
    const TwoBoneIkResult r = solveTwoBoneIk(in);
    ASSERT_TRUE(finite(r.middle) && finite(r.end));
    EXPECT_LT(glm::length(r.end - in.target), 0.1f) << "target " << dist;  // 1 mm
    EXPECT_TRUE(r.reached);
    EXPECT_NEAR(glm::length(r.middle - in.root), in.upper_length, 1e-3f);
    EXPECT_NEAR(glm::length(r.end - r.middle), in.lower_length, 1e-3f);
    ++tried;
  }
}

TEST(TwoBoneIk, HonoursTheBendDirection) {
  for (glm::vec3 pole : {glm::vec3(100, 50, 0), glm::vec3(-100, 50, 0), glm::vec3(0, 50, 100)}) {
    TwoBoneIkInput in = leg({10, 30, 0});
    in.pole = pole;
    const TwoBoneIkResult r = solveTwoBoneIk(in);
    const glm::vec3 axis = glm::normalize(in.target - in.root);
    const glm::vec3 foot = in.root + axis * glm::dot(r.middle - in.root, axis);
    const glm::vec3 to_pole = pole - in.root - axis * glm::dot(pole - in.root, axis);
    EXPECT_GT(glm::dot(r.middle - foot, glm::normalize(to_pole)), 5.0f);  // knee on the pole side
  }
}

TEST(TwoBoneIk, ClampsMonotonicallyWithoutNaNWhenOutOfReach) {
  for (float soften : {0.0f, 2.0f}) {
    float last = 0.0f;
    glm::vec3 last_end(0.0f);
    for (float d = 60.0f; d < 200.0f; d += 0.25f) {
      TwoBoneIkInput in = leg(glm::vec3(0, 100, 0) + glm::normalize(glm::vec3(0.3f, -1, 0.1f)) * d);
      in.soften = soften;
      const TwoBoneIkResult r = solveTwoBoneIk(in);
      ASSERT_TRUE(finite(r.middle) && finite(r.end)) << d;
      const float reach = glm::length(r.end - in.root);
      EXPECT_GE(reach, last - 1e-4f) << d;        // monotone
      EXPECT_LE(reach, 85.0f + 1e-3f) << d;       // never longer than the limb
      EXPECT_LT(glm::length(r.end - last_end), last_end == glm::vec3(0.0f) ? 1e9f : 0.3f) << d;  // continuous
      EXPECT_NEAR(glm::length(r.middle - in.root), 45.0f, 1e-3f);
      last = reach;
      last_end = r.end;
    }
    EXPECT_NEAR(last, 85.0f, 1e-2f);
  }
}

TEST(TwoBoneIk, DegenerateInputsStayFinite) {
  TwoBoneIkInput in = leg({0, 100, 0});  // target on the root
  TwoBoneIkResult r = solveTwoBoneIk(in);
  EXPECT_TRUE(finite(r.middle) && finite(r.end));
  in = leg({0, 30, 0});
  in.pole = in.target;  // pole on the reach line
  r = solveTwoBoneIk(in);
  EXPECT_TRUE(finite(r.middle) && finite(r.end));
  EXPECT_LT(glm::length(r.end - in.target), 0.1f);
}

TEST(BoneRotation, MapsRestFrameToPosedFrame) {
  const glm::vec3 rest_dir(0, -1, 0), rest_n(0, 0, 1);
  const glm::vec3 dir = glm::normalize(glm::vec3(1, -1, 0)), n(0, 0, 1);
  const glm::mat3 R = boneRotation(rest_dir, rest_n, dir, n);
  const glm::vec3 mapped = R * rest_dir;
  EXPECT_NEAR(glm::length(mapped - dir), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(R * rest_n - n), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::determinant(R), 1.0f, 1e-5f);
}

}  // namespace
}  // namespace stirrup::rig
