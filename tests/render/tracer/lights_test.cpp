// The sun's and the sky's sampling, and the polynomial sine, cosine and power the SIMD lanes share:
// against the C library in double precision, and by the distributions they must draw.
#include "render/tracer/lights.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Lights, TheQuarterSineAndCosineAreWithinTwoUlpOfTheLibrary) {
  double worst_sin = 0.0, worst_cos = 0.0;
  for (int i = -20000; i <= 20000; ++i) {
    const float x = float(kPi / 4.0 * i / 20000.0);
    float s, c;
    sinCosQuarterPi(x, s, c);
    worst_sin = std::max(worst_sin, std::abs(double(s) - std::sin(double(x))));
    worst_cos = std::max(worst_cos, std::abs(double(c) - std::cos(double(x))));
  }
  // Two float ulps at 0.7 and at 1 (1.2e-7); the samples' directions need no better.
  EXPECT_LT(worst_sin, 1.2e-7);
  EXPECT_LT(worst_cos, 1.2e-7);
}

TEST(Lights, TheUnitCircleGoesRoundOnceAndStaysUnit) {
  double worst = 0.0, worst_length = 0.0;
  for (int i = 0; i < 40000; ++i) {
    const float u = float(i) / 40000.0f;
    const glm::vec2 p = unitCircle(u);
    const double a = 2.0 * kPi * double(u);
    worst = std::max({worst, std::abs(double(p.x) - std::cos(a)), std::abs(double(p.y) - std::sin(a))});
    worst_length = std::max(worst_length, std::abs(double(glm::length(p)) - 1.0));
  }
  EXPECT_LT(worst, 3e-7);
  EXPECT_LT(worst_length, 3e-7);
  // The quarter turns are exact.
  EXPECT_EQ(unitCircle(0.0f), glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(unitCircle(0.25f), glm::vec2(-0.0f, 1.0f));
  EXPECT_EQ(unitCircle(0.5f), glm::vec2(-1.0f, -0.0f));
  EXPECT_EQ(unitCircle(0.75f), glm::vec2(0.0f, -1.0f));
}

TEST(Lights, AWholePowerIsTheLibrarysPower) {
  EXPECT_EQ(powWhole(2.0f, 10), 1024.0f);
  EXPECT_EQ(powWhole(0.5f, 0), 1.0f);
  EXPECT_EQ(powWhole(0.0f, 48), 0.0f);
  for (float x = 0.0f; x <= 1.0f; x += 1.0f / 1024.0f) {
    const double expected = std::pow(double(x), 48.0);
    EXPECT_NEAR(powWhole(x, 48), expected, 2e-6 * expected + 1e-30) << x;
  }
}

// A stratified grid of n x n points in [0, 1)^2, for the distributions below.
template <typename F>
void overGrid(int n, F&& f) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) f(glm::vec2((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n)));
}

TEST(Lights, TheSunsConeIsUniformInSolidAngle) {
  const Frame axis = Frame::around(glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f)));
  const float cos_max = std::cos(float(4.0 * kPi / 180.0));
  double mean_cos = 0.0;
  glm::dvec3 mean(0.0);
  int count = 0;
  overGrid(64, [&](glm::vec2 u) {
    const glm::vec3 d = sampleCone(axis, cos_max, u);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
    EXPECT_GE(glm::dot(d, axis.z), cos_max - 1e-6f);
    mean_cos += glm::dot(d, axis.z);
    mean += glm::dvec3(d);
    ++count;
  });
  // Uniform in solid angle: cos is uniform on [cos_max, 1], and the directions are symmetric about
  // the axis (their mean lies along it).
  EXPECT_NEAR(mean_cos / count, (1.0 + cos_max) / 2.0, 1e-6);
  const glm::dvec3 m = mean / double(count);
  EXPECT_NEAR(glm::length(m - glm::dot(m, glm::dvec3(axis.z)) * glm::dvec3(axis.z)), 0.0, 1e-6);
}

TEST(Lights, TheSkysRaysAreCosineWeighted) {
  const Frame around = Frame::around(glm::normalize(glm::vec3(-0.2f, 0.9f, 0.3f)));
  double mean_cos = 0.0, mean_cos2 = 0.0;
  int count = 0;
  overGrid(128, [&](glm::vec2 u) {
    const glm::vec3 d = sampleCosineHemisphere(around, u);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
    const double c = glm::dot(d, around.z);
    EXPECT_GE(c, 0.0);
    mean_cos += c, mean_cos2 += c * c;
    ++count;
  });
  // With pdf cos / pi: E[cos] = 2/3 and E[cos^2] = 1/2 (uniform over the hemisphere would give 1/2
  // and 1/3). The grid's quadrature error is about 4e-4: cos has an infinite slope at the disc's rim.
  EXPECT_NEAR(mean_cos / count, 2.0 / 3.0, 1e-3);
  EXPECT_NEAR(mean_cos2 / count, 0.5, 1e-3);
}

}  // namespace
}  // namespace stirrup::render
