// The curve of a curve spine (rig/cubic_spline.cpp) built directly from five points: centripetal knots,
// interpolation, clamped ends, arc length and its inverse, on curves whose answers are known by hand
// (a line, a half circle). The spine that builds it from its controllers is curve_spine_test.cpp.
#include "rig/cubic_spline.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Knot spacing |P[i+1] - P[i]|^0.5: chords 1, 4, 1, 14 give spacings 1, 2, 1, sqrt(14).
TEST(CubicSpline, KnotsAreCentripetal) {
  const CubicSpline c({glm::dvec3(0, 0, 0), {1, 0, 0}, {5, 0, 0}, {6, 0, 0}, {20, 0, 0}}, {1, 0, 0}, {1, 0, 0});
  EXPECT_EQ(c.knot(0), 0.0);
  EXPECT_NEAR(c.knot(1), 1.0, 1e-15);
  EXPECT_NEAR(c.knot(2), 3.0, 1e-15);
  EXPECT_NEAR(c.knot(3), 4.0, 1e-15);
  EXPECT_NEAR(c.endParameter(), 4.0 + std::sqrt(14.0), 1e-12);
}

// Five points on a line with the ends along it: the curve is the line, 40 cm long, and a point at arc
// length s is s along it.
TEST(CubicSpline, CollinearPointsAreTheirLine) {
  const CubicSpline c({glm::dvec3(0, 0, 0), {10, 0, 0}, {20, 0, 0}, {30, 0, 0}, {40, 0, 0}}, {1, 0, 0}, {1, 0, 0});
  EXPECT_NEAR(c.length(), 40.0, 1e-9);
  for (int i = 0; i < CubicSpline::kPointCount; ++i) expectNear(c.point(c.knot(i)), {10.0 * i, 0, 0}, 1e-12);
  for (double s : {0.0, 3.7, 12.5, 20.0, 33.3, 40.0}) {
    expectNear(c.pointAtArcLength(s), {s, 0, 0}, 1e-9);
    expectNear(c.tangent(c.parameterAtArcLength(s)), {1, 0, 0}, 1e-12);
  }
  // Arc lengths outside the curve clamp to its ends.
  EXPECT_EQ(c.parameterAtArcLength(-5.0), 0.0);
  EXPECT_NEAR(c.parameterAtArcLength(45.0), c.endParameter(), 1e-12);
}

// A half circle of radius 10 (points every 45°, from (-10, 0) heading +y over the top to (10, 0)
// heading -y): through the five points, leaving and arriving along the given directions, in its plane,
// and close to the circle: a cubic through points 45° apart only approximates it, so within 0.5% of the
// radius and of the length 10π.
TEST(CubicSpline, AHalfCircleIsTenPiLong) {
  const double r = 10.0, h = r * std::sqrt(0.5);
  const CubicSpline c({glm::dvec3(-r, 0, 0), {-h, h, 0}, {0, r, 0}, {h, h, 0}, {r, 0, 0}}, {0, 1, 0}, {0, -1, 0});
  EXPECT_NEAR(c.length(), glm::pi<double>() * r, 0.005 * glm::pi<double>() * r);
  expectNear(c.point(c.knot(2)), {0, r, 0}, 1e-12);
  expectNear(c.tangent(0.0), {0, 1, 0}, 1e-12);
  expectNear(c.tangent(c.endParameter()), {0, -1, 0}, 1e-12);
  expectNear(c.tangent(c.knot(2)), {1, 0, 0}, 1e-3);  // level at the top
  for (int k = 0; k <= 100; ++k) {
    const glm::dvec3 p = c.pointAtArcLength(c.length() * k / 100.0);
    EXPECT_NEAR(glm::length(p), r, 0.005 * r) << k;
    EXPECT_EQ(p.z, 0.0);
  }
  // Arc length and its inverse agree, and halfway along is the top (the curve is symmetric).
  for (double f : {0.1, 0.37, 0.5, 0.81}) {
    const double s = f * c.length();
    EXPECT_NEAR(c.arcLengthAt(c.parameterAtArcLength(s)), s, 1e-9);
  }
  expectNear(c.pointAtArcLength(0.5 * c.length()), {0, r, 0}, 1e-9);
}

}  // namespace
}  // namespace stirrup::rig
