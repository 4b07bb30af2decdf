#include "rig/motion/ground_path.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string errorOf(std::vector<glm::dvec2> points) {
  return stirrup::test::errorOf([&] { GroundPath path(std::move(points), "scene.json: clip.path"); }, "");
}

TEST(GroundPath, AStraightLineIsItself) {
  const GroundPath path({{0, 0}, {300, 0}, {1000, 0}}, "p");
  EXPECT_NEAR(path.length(), 1000.0, 1e-6);
  for (double s : {0.0, 150.0, 299.0, 700.0, 1000.0}) {
    const GroundPath::Sample p = path.at(s);
    EXPECT_NEAR(p.position.x, s, 1e-6) << s;
    EXPECT_NEAR(p.position.y, 0.0, 1e-9) << s;
    EXPECT_NEAR(p.heading_deg, 0.0, 1e-9) << s;
    EXPECT_NEAR(p.curvature, 0.0, 1e-12) << s;
  }
  // Beyond the ends the horse stands at the end, heading along the path.
  EXPECT_NEAR(path.at(-50).position.x, 0.0, 1e-9);
  EXPECT_NEAR(path.at(5000).position.x, 1000.0, 1e-6);
}

// Through every point, by arc length: one unit of s is one cm along the curve, and the curve passes
// through each point it was given.
TEST(GroundPath, PassesThroughItsPointsAtUnitSpeed) {
  const std::vector<glm::dvec2> pts = {{0, 0}, {400, 50}, {600, 400}, {500, 900}, {900, 1000}};
  const GroundPath path(pts, "p");
  std::size_t next = 1;
  double previous_distance = 1e9;
  const double ds = 0.5;
  for (double s = 0; s <= path.length(); s += ds) {
    const GroundPath::Sample a = path.at(s), b = path.at(std::min(s + ds, path.length()));
    if (s + ds <= path.length()) {
      EXPECT_NEAR(glm::length(b.position - a.position), ds, 1e-4 * ds) << s;
    }
    if (next < pts.size()) {
      const double d = glm::length(a.position - pts[next]);
      if (d > previous_distance && previous_distance < 1.0) {
        EXPECT_LT(previous_distance, 0.3) << "point " << next;
        ++next;
        previous_distance = 1e9;
      } else {
        previous_distance = d;
      }
    }
  }
  EXPECT_NEAR(glm::length(path.at(path.length()).position - pts.back()), 0.0, 1e-6);
  EXPECT_GE(next, pts.size() - 1) << "the curve passed close to every inner point";
}

// C1: the tangent turns smoothly through every point (no kink where two segments meet), and the
// heading follows the tangent.
TEST(GroundPath, TheTangentIsContinuousAcrossItsPoints) {
  const GroundPath path({{0, 0}, {100, 0}, {800, 300}, {820, 900}}, "p");
  double worst = 0;
  for (double s = 0.25; s < path.length(); s += 0.25) {
    const GroundPath::Sample a = path.at(s - 0.25), b = path.at(s);
    worst = std::max(worst, std::acos(std::clamp(glm::dot(a.tangent, b.tangent), -1.0, 1.0)) * 180 / kPi);
    EXPECT_NEAR(b.heading_deg, std::atan2(b.tangent.y, b.tangent.x) * 180 / kPi, 1e-9);
  }
  EXPECT_LT(worst, 0.5) << "degrees the tangent turns in 0.25 cm";
}

// Points on a circle of radius 10 m: the curve stays on it, and its curvature is 1/R, + turning right
// (from +X toward +Z, the horse's right).
TEST(GroundPath, ACircleHasTheCurvatureOfItsRadius) {
  const double r = 1000.0;
  std::vector<glm::dvec2> pts;
  for (int i = 0; i <= 12; ++i) {
    const double a = -kPi / 2 + i * kPi / 12;  // a half circle, turning right
    pts.push_back({r * std::cos(a), r + r * std::sin(a)});
  }
  const GroundPath path(pts, "p");
  EXPECT_NEAR(path.length(), kPi * r, 0.002 * kPi * r);
  for (double s = 0.2 * path.length(); s < 0.8 * path.length(); s += 50) {
    const GroundPath::Sample p = path.at(s);
    EXPECT_NEAR(glm::length(p.position - glm::dvec2(0, r)), r, 0.5) << s;
    // A cubic through points 15° apart: its curvature ripples about 1/R by under 6%.
    EXPECT_NEAR(p.curvature, 1.0 / r, 0.06 / r) << s;
  }
  EXPECT_NEAR(path.at(0.5 * path.length()).heading_deg, 90.0, 0.5);
}

// Centripetal: unevenly spaced points (20 m legs around a 1 m jog) make no loop: the curve never runs
// backward along x (Yuksel et al. show a uniform Catmull-Rom can loop on such spacing).
TEST(GroundPath, UnevenPointsMakeNoLoop) {
  const GroundPath path({{0, 0}, {2000, 0}, {2050, 60}, {2100, 60}, {4000, 60}}, "p");
  double x = -1;
  for (double s = 0; s <= path.length(); s += 1) {
    const GroundPath::Sample p = path.at(s);
    EXPECT_GE(p.position.x, x - 1e-9) << s;
    x = p.position.x;
  }
}

TEST(GroundPath, BadPointsAreOneLineErrorsNamingTheField) {
  EXPECT_EQ(errorOf({{0, 0}}), "scene.json: clip.path: points: expected at least two points [x, z] (cm), got 1");
  EXPECT_EQ(errorOf({{0, 0}, {0, 0}}),
            "scene.json: clip.path: points[1]: expected a point at least 1 cm from points[0] (a zero-length segment "
            "has no heading), got one 0 cm away");
  EXPECT_EQ(errorOf({{0, 0}, {100, 0}, {100.5, 0}}),
            "scene.json: clip.path: points[2]: expected a point at least 1 cm from points[1] (a zero-length "
            "segment has no heading), got one 0.5 cm away");
  EXPECT_EQ(errorOf({{0, 0}, {std::nan(""), 0}}), "scene.json: clip.path: points[1]: expected coordinates from -1e+07 to 1e+07 cm, got [nan, 0]");
  EXPECT_EQ(errorOf({{0, 0}, {std::numeric_limits<double>::infinity(), 0}}),
            "scene.json: clip.path: points[1]: expected coordinates from -1e+07 to 1e+07 cm, got [inf, 0]");
  EXPECT_EQ(errorOf({{0, 0}, {1e308, 0}}), "scene.json: clip.path: points[1]: expected coordinates from -1e+07 to 1e+07 cm, got [1e+308, 0]");
  EXPECT_EQ(errorOf({{0, 0}, {100, 0}}), "");
}

}  // namespace
}  // namespace stirrup::rig
