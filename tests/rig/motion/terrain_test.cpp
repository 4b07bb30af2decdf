#include "rig/motion/terrain.h"

#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

std::string errorOf(HillsParams p) {
  return stirrup::test::errorOf([&] { (void)Terrain::hills(p, "scene.json"); }, "");
}

TEST(Terrain, FlatIsZeroEverywhere) {
  const Terrain flat;
  EXPECT_TRUE(flat.flat());
  EXPECT_EQ(flat.height(123, -456), 0.0);
  EXPECT_EQ(flat.normal(5, 5), glm::dvec3(0, 1, 0));
}

// Within ±amplitude, using most of it over a few kilometres, and the same heights every time.
TEST(Terrain, HillsStayWithinTheirAmplitudeAndRepeat) {
  HillsParams p;
  p.seed = 7;
  p.amplitude_cm = 150;
  p.wavelength_cm = 3000;
  p.octaves = 3;
  const Terrain a = Terrain::hills(p, "s"), b = Terrain::hills(p, "s");
  double lo = 1e9, hi = -1e9;
  for (double x = -100000; x <= 100000; x += 997)
    for (double z = -20000; z <= 20000; z += 1013) {
      const double h = a.height(x, z);
      EXPECT_EQ(h, b.height(x, z));
      lo = std::min(lo, h), hi = std::max(hi, h);
    }
  EXPECT_GE(lo, -150.0);
  EXPECT_LE(hi, 150.0);
  EXPECT_GT(hi - lo, 150.0) << "the hills use their amplitude";
  p.seed = 8;
  EXPECT_NE(Terrain::hills(p, "s").height(1234, 567), a.height(1234, 567)) << "another seed, other hills";
}

// The analytic slope matches the heights' finite differences, and is continuous across the lattice
// lines (the quintic fade): a horse's pitch over the ground never jumps.
TEST(Terrain, SlopeIsTheHeightsDerivativeAndContinuous) {
  HillsParams p;
  p.amplitude_cm = 200;
  p.wavelength_cm = 2500;
  const Terrain t = Terrain::hills(p, "s");
  for (double x = -5000; x <= 5000; x += 311.7) {
    const double z = 0.37 * x + 120;
    double gx = 0, gz = 0;
    t.gradient(x, z, gx, gz);
    const double e = 0.01;
    EXPECT_NEAR(gx, (t.height(x + e, z) - t.height(x - e, z)) / (2 * e), 1e-6) << x;
    EXPECT_NEAR(gz, (t.height(x, z + e) - t.height(x, z - e)) / (2 * e), 1e-6) << x;
    const glm::dvec3 n = t.normal(x, z);
    EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
    EXPECT_GT(n.y, 0.0);
  }
  // Across the lattice line x = 2500 (the first octave's): the slope on either side agrees.
  double a = 0, b = 0, dz = 0;
  t.gradient(2500 - 1e-6, 400, a, dz);
  t.gradient(2500 + 1e-6, 400, b, dz);
  EXPECT_NEAR(a, b, 1e-6);
}

TEST(Terrain, BadParametersAreOneLineErrorsNamingTheField) {
  HillsParams p;
  p.amplitude_cm = -1;
  EXPECT_EQ(errorOf(p), "scene.json: terrain.hills.amplitude_cm: expected a height from 0 to 5000 cm, got -1");
  p = {};
  p.amplitude_cm = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(errorOf(p), "scene.json: terrain.hills.amplitude_cm: expected a height from 0 to 5000 cm, got nan");
  p = {};
  p.wavelength_cm = 10;
  EXPECT_EQ(errorOf(p), "scene.json: terrain.hills.wavelength_cm: expected a length from 100 to 1000000 cm, got 10");
  p = {};
  p.octaves = 0;
  EXPECT_EQ(errorOf(p), "scene.json: terrain.hills.octaves: expected a whole number from 1 to 6, got 0");
  EXPECT_EQ(errorOf(HillsParams{}), "");
}

}  // namespace
}  // namespace stirrup::rig
