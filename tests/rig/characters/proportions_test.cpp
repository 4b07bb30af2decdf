#include "rig/characters/proportions.h"

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// The expected values are the default parameters (rig/characters/*_character.h) times the ratios,
// worked out here by hand.
TEST(Proportions, TheDefaultSizesGiveTheDefaultParameters) {
  const HorseParams h = scaledHorse(160, 170), d;
  EXPECT_FLOAT_EQ(h.withers_height, 160.0f);
  EXPECT_EQ(h.hips, d.hips);
  EXPECT_EQ(h.muzzle, d.muzzle);
  EXPECT_EQ(h.mount.stirrup, d.mount.stirrup);
  EXPECT_EQ(h.mount.rein_grip, d.mount.rein_grip);
  const RiderParams r = scaledRider(170, 1.0), e;
  EXPECT_EQ(r.head, e.head);
  EXPECT_EQ(r.chest_radii, e.chest_radii);
  EXPECT_FLOAT_EQ(r.thigh, e.thigh);
}

TEST(Proportions, AHorseScalesWithItsWithers) {
  const HorseParams h = scaledHorse(176, 170);  // 1.1 times the default
  EXPECT_FLOAT_EQ(h.withers_height, 176.0f);
  EXPECT_FLOAT_EQ(h.hips.y, 140.8f);           // 128 × 1.1
  EXPECT_FLOAT_EQ(h.fore_hoof.x, 57.2f);       // 52 × 1.1
  EXPECT_FLOAT_EQ(h.barrel_radii.z, 27.5f);    // 25 × 1.1
  EXPECT_FLOAT_EQ(h.tail_length, 88.0f);       // 80 × 1.1
  EXPECT_FLOAT_EQ(h.mount.stirrup.z, -34.1f);  // out from the wider barrel: -31 × 1.1
  EXPECT_FLOAT_EQ(h.mount.stirrup.y, -74.0f);  // hung for the same 170 cm rider
  EXPECT_EQ(h.coat, HorseParams{}.coat);       // colours are not sizes
  EXPECT_FLOAT_EQ(h.cell, HorseParams{}.cell);
}

TEST(Proportions, TheStirrupsHangForTheRider) {
  const HorseParams h = scaledHorse(160, 187);  // a rider 1.1 times the default
  EXPECT_FLOAT_EQ(h.mount.stirrup.y, -81.4f);  // -74 × 1.1
  EXPECT_FLOAT_EQ(h.mount.stirrup.z, -31.0f);
  EXPECT_FLOAT_EQ(h.mount.rein_grip.x, 37.4f); // 34 × 1.1
}

TEST(Proportions, BuildWidensARiderWithoutMakingHerTaller) {
  const RiderParams r = scaledRider(153, 1.2);  // 0.9 times the default height
  EXPECT_FLOAT_EQ(r.head.y, 59.4f);             // 66 × 0.9
  EXPECT_FLOAT_EQ(r.thigh, 40.5f);              // 45 × 0.9
  EXPECT_FLOAT_EQ(r.chest_radii.x, 11.5f * 0.9f * 1.2f);
  EXPECT_FLOAT_EQ(r.chest_radii.y, 11.5f * 0.9f);  // height: not the build's
  EXPECT_FLOAT_EQ(r.chest_radii.z, 16.0f * 0.9f * 1.2f);
  EXPECT_FLOAT_EQ(r.waist_radius, 13.5f * 0.9f * 1.2f);
  EXPECT_FLOAT_EQ(r.calf_radius, 5.6f * 0.9f * 1.2f);
  EXPECT_FLOAT_EQ(r.wrist_radius, 3.2f * 0.9f);    // bone, not girth
  EXPECT_EQ(r.coat, RiderParams{}.coat);
}

}  // namespace
}  // namespace stirrup::rig
