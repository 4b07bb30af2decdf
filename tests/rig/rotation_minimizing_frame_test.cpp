// One step of the rotation-minimizing frame (rig/rotation_minimizing_frame.cpp, Wang et al. 2008's
// double reflection) and the shortest-arc rotation, on curves whose frames are known by hand.
#include "rig/rotation_minimizing_frame.h"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

const glm::dvec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

TEST(RotationMinimizingFrame, AStraightStepAddsNoRotation) {
  const glm::dquat rolled = glm::angleAxis(glm::radians(30.0), kX);  // tangent along x, turned about it
  const glm::dquat next = transportFrame(rolled, {0, 0, 0}, {10, 0, 0}, kX);
  EXPECT_NEAR(std::abs(glm::dot(next, rolled)), 1.0, 1e-12);  // the same rotation: no twist of its own
}

// A quarter of a circle of radius R about (0, R, 0), from the origin (heading +x) to (R, R, 0) (heading
// +y). By hand: reflecting in the plane normal to (R, R, 0) takes y to -x and x to -y; the second
// reflection, normal to t1 - (-y) = 2y, leaves -x alone. So the frame turns 90° about z, and z, the
// plane's normal, stays.
TEST(RotationMinimizingFrame, AQuarterCircleTurnsTheFrameAQuarterAboutItsNormal) {
  const double R = 25.0;
  const glm::dquat next = transportFrame(glm::dquat(1, 0, 0, 0), {0, 0, 0}, {R, R, 0}, kY);
  expectNear(next * kX, kY);
  expectNear(next * kY, -kX);
  expectNear(next * kZ, kZ);
  EXPECT_NEAR(next.w, std::cos(glm::quarter_pi<double>()), 1e-12);
  EXPECT_GE(next.w, 0.0);
}

// On any plane curve the frame's out-of-plane axis never moves, however the curvature changes sign:
// an S in the x-y plane, stepped in 40 pieces.
TEST(RotationMinimizingFrame, APlaneCurveKeepsItsNormalThroughAnS) {
  const auto point = [](double s) { return glm::dvec3(100.0 * s, 20.0 * std::sin(glm::two_pi<double>() * s), 0.0); };
  const auto tangent = [](double s) {
    return glm::normalize(glm::dvec3(100.0, 20.0 * glm::two_pi<double>() * std::cos(glm::two_pi<double>() * s), 0.0));
  };
  glm::dquat frame = shortestArc(kX, tangent(0.0));
  for (int i = 1; i <= 40; ++i) {
    const double a = (i - 1) / 40.0, b = i / 40.0;
    frame = transportFrame(frame, point(a), point(b), tangent(b));
    expectNear(frame * kX, tangent(b), 1e-12);
    expectNear(frame * kZ, kZ, 1e-9);
  }
}

TEST(RotationMinimizingFrame, ShortestArcTurnsAOntoBAboutTheirNormal) {
  const glm::dquat q = shortestArc(kX, kY);
  expectNear(q * kX, kY);
  expectNear(q * kZ, kZ);  // about the common normal
  EXPECT_NEAR(q.w, std::cos(glm::quarter_pi<double>()), 1e-12);  // half of 90°
  const glm::dquat none = shortestArc(kY, kY);
  EXPECT_NEAR(none.w, 1.0, 1e-15);
  const glm::dvec3 d = glm::normalize(glm::dvec3(1, 2, 3));
  expectNear(shortestArc(kZ, d) * kZ, d);
}

}  // namespace
}  // namespace stirrup::rig
