// The lights behind their one interface: the sun's radiance on a surface facing it and turned away,
// its cone and its shadow-ray test; the sky's colour at the zenith, the horizon and below, its
// cosine-weighted sampling and its occlusion test; and what each hands the lanes.
#include "render/tracer/light.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/tracer/material.h"

namespace stirrup::render {
namespace {

const OccluderBox kBox{{-50.0f, 0.0f, -30.0f}, {50.0f, 180.0f, 30.0f}};
const glm::vec3 kSunRadiance(1.8f, 1.728f, 1.584f);

Sun overhead(const OccluderBox& box = kBox) { return Sun({0.0, 1.0, 0.0}, 2.0, kSunRadiance, box, 0.0f); }

TEST(Light, TheSunLightsASurfaceFacingItAndNotOneTurnedAway) {
  const Sun sun({0.45, 0.75, 0.5}, 2.0, kSunRadiance, kBox, 0.0f);
  const glm::vec3 axis = sun.frame().z;
  EXPECT_NEAR(glm::length(axis), 1.0f, 1e-6f);
  EXPECT_EQ(sun.radiance(axis), kSunRadiance);
  EXPECT_EQ(sun.radiance(-axis), glm::vec3(0.0f));
  const Brdf matte;  // specular 0: albedo times cosine
  const glm::vec3 albedo(0.5f, 0.4f, 0.3f), wo(0.0f, 1.0f, 0.0f);
  const glm::vec3 facing = matte.reflected(albedo, axis, axis, wo, axis) * sun.radiance(axis);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(facing[c], albedo[c] * kSunRadiance[c], 1e-6f);
  const glm::vec3 away = matte.reflected(albedo, -axis, -axis, wo, axis) * sun.radiance(axis);
  EXPECT_EQ(away, glm::vec3(0.0f));
  // Half lit at 60 degrees from the axis.
  const glm::vec3 tilted = glm::normalize(axis + std::sqrt(3.0f) * sun.frame().x);
  const glm::vec3 side = matte.reflected(albedo, tilted, tilted, wo, axis) * sun.radiance(axis);
  EXPECT_NEAR(side.x, 0.5f * albedo.x * kSunRadiance.x, 1e-5f);
}

TEST(Light, TheSunsSamplesStayInItsConeAndCarryItsRadiance) {
  const Sun sun({0.2, 0.9, -0.3}, 3.0, kSunRadiance, kBox, 0.0f);
  float widest = 1.0f;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      const glm::vec3 wi = sun.sampleDirection({0.0f, 1.0f, 0.0f}, {(i + 0.5f) / 64.0f, (j + 0.5f) / 64.0f});
      EXPECT_NEAR(glm::length(wi), 1.0f, 1e-5f);
      widest = std::min(widest, glm::dot(wi, sun.frame().z));
    }
  }
  EXPECT_GE(widest, sun.cosMax() - 1e-6f);
  EXPECT_LT(widest, 1.0f - 0.9f * (1.0f - sun.cosMax()));  // the samples reach the disc's edge
}

TEST(Light, TheSunNeedsShadowRaysOnlyWhereTheCharactersMayBlockIt) {
  const Sun sun = overhead();
  EXPECT_TRUE(sun.mayBeBlocked({0.0f, 0.0f, 0.0f}));        // under the characters
  EXPECT_FALSE(sun.mayBeBlocked({500.0f, 0.0f, 0.0f}));     // beside them
  EXPECT_FALSE(sun.mayBeBlocked({0.0f, 300.0f, 0.0f}));     // above them
  EXPECT_TRUE(sun.groundMayBeBlocked({0.0f, 0.0f, 0.0f}));
  EXPECT_FALSE(sun.groundMayBeBlocked({500.0f, 0.0f, 0.0f}));
  EXPECT_TRUE(sun.groundRegionExcludes({5000.0f, 0.0f, 0.0f}));
  EXPECT_FALSE(sun.groundRegionExcludes({0.0f, 0.0f, 0.0f}));
  const Sun alone = overhead(OccluderBox{{1.0f, 1.0f, 1.0f}, {-1.0f, -1.0f, -1.0f}});  // no characters
  EXPECT_FALSE(alone.mayBeBlocked({0.0f, 0.0f, 0.0f}));
}

TEST(Light, TheSkyIsItsZenithColourOverheadAndItsHorizonColourLevel) {
  SkyGradient gradient;
  gradient.below = {0.1f, 0.2f, 0.3f};
  const Sky sky(gradient, 300.0f, kBox, glm::vec3(0.2f));
  EXPECT_EQ(sky.radiance({0.0f, 1.0f, 0.0f}), gradient.zenith);
  EXPECT_EQ(sky.radiance({1.0f, 0.0f, 0.0f}), gradient.horizon);
  EXPECT_EQ(sky.radiance({0.0f, -1.0f, 0.0f}), gradient.below);
  // Halfway where the sine of the elevation is a quarter (the square root keeps the low sky pale), and
  // bluer the higher.
  const glm::vec3 quarter = sky.radiance(glm::normalize(glm::vec3(std::sqrt(15.0f), 1.0f, 0.0f)));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(quarter[c], 0.5f * (gradient.horizon[c] + gradient.zenith[c]), 1e-6f);
  const glm::vec3 higher = sky.radiance(glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
  EXPECT_LT(higher.x, quarter.x);
  EXPECT_GT(higher.z - higher.x, quarter.z - quarter.x);
}

TEST(Light, TheSkysCosineWeightedSamplesAverageToItsIrradiance) {
  const Sky sky(SkyGradient{}, 300.0f, kBox, glm::vec3(0.2f));
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  glm::dvec3 sum(0.0);
  constexpr int kSide = 256;
  for (int i = 0; i < kSide; ++i) {
    for (int j = 0; j < kSide; ++j) {
      const glm::vec3 wi = sky.sampleDirection(up, {(i + 0.5f) / kSide, (j + 0.5f) / kSide});
      ASSERT_GE(wi.y, 0.0f);
      sum += glm::dvec3(sky.radiance(wi));
    }
  }
  const glm::vec3 mean(sum / double(kSide * kSide)), expected = sky.upwardIrradianceOverPi();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], expected[c], 2e-3f);
}

TEST(Light, TheSkyNeedsRaysOnlyNearTheCharacters) {
  const Sky sky(SkyGradient{}, 300.0f, kBox, glm::vec3(0.2f));
  EXPECT_TRUE(sky.mayBeBlocked({100.0f, 0.0f, 0.0f}));   // 50 cm from the box
  EXPECT_FALSE(sky.mayBeBlocked({400.0f, 0.0f, 0.0f}));  // 350 cm
  const Sky open(SkyGradient{}, 300.0f, OccluderBox{{1.0f, 1.0f, 1.0f}, {-1.0f, -1.0f, -1.0f}}, glm::vec3(0.2f));
  EXPECT_FALSE(open.mayBeBlocked({0.0f, 0.0f, 0.0f}));
}

TEST(Light, EachLightHandsTheLanesItsNumbers) {
  const Sun sun({0.45, 0.75, 0.5}, 2.0, kSunRadiance, kBox, 0.0f);
  const Sky sky(SkyGradient{}, 250.0f, kBox, glm::vec3(0.25f, 0.2f, 0.15f));
  LaneConstants k;
  sun.toLanes(k);
  sky.toLanes(k);
  EXPECT_EQ(k.sun_axis, sun.frame().z);
  EXPECT_EQ(k.sun_y, sun.frame().z.y);
  EXPECT_EQ(k.sun_radiance, kSunRadiance);
  EXPECT_EQ(k.sun_cos_max, sun.cosMax());
  EXPECT_TRUE(k.sun_region);
  EXPECT_LT(k.sun_lower_x, kBox.lower.x);
  EXPECT_GT(k.sun_upper_z, kBox.upper.z);
  EXPECT_EQ(k.zenith, SkyGradient{}.zenith);
  EXPECT_EQ(k.sky_irradiance, sky.upwardIrradianceOverPi());
  EXPECT_EQ(k.ao_distance, 250.0f);
  EXPECT_EQ(k.ground_bounce, glm::vec3(0.25f, 0.2f, 0.15f));
  // The light interface, as the integrator holds either.
  const Light& light = sun;
  EXPECT_EQ(light.radiance(sun.frame().z), kSunRadiance);
}

}  // namespace
}  // namespace stirrup::render
