// rig/motion/placed_clip.h: a clip moved rigidly on the ground. The default trot travels along +X from the
// origin; carried to (50, 200) and turned a quarter to the right it travels along +Z from there, its
// heading 90 degrees, its controls (relative to its travel frame) untouched.
#include "rig/motion/placed_clip.h"

#include <memory>

#include <gtest/gtest.h>

#include "scene/clip_factory.h"

namespace stirrup::rig {
namespace {

TEST(PlacedClip, CarriesAndTurnsTheTravelAndKeepsTheControls) {
  const std::shared_ptr<const Clip> trot = scene::makeClip(scene::ClipSpec{});
  const HorseFrame start = trot->sample(0.0);
  const PlacedClip placed(trot, {start.travel_cm, start.travel_z_cm}, {50.0, 200.0}, 90.0);
  for (const double t : {0.0, 0.5, 1.25}) {
    const HorseFrame a = trot->sample(t), b = placed.sample(t);
    const double along = a.travel_cm - start.travel_cm, side = a.travel_z_cm - start.travel_z_cm;
    EXPECT_NEAR(b.travel_cm, 50.0 - side, 1e-9) << t;
    EXPECT_NEAR(b.travel_z_cm, 200.0 + along, 1e-9) << t;
    EXPECT_NEAR(b.heading_deg, a.heading_deg + 90.0, 1e-12) << t;
    EXPECT_EQ(b.controls.value, a.controls.value) << t;
    EXPECT_EQ(placed.sampleTravel(t).travel_z_cm, b.travel_z_cm) << t;
  }
  EXPECT_GT(trot->sample(1.25).travel_cm - start.travel_cm, 400.0);  // it did travel (360 cm/s)
  EXPECT_EQ(placed.duration(), trot->duration());
  EXPECT_EQ(placed.name(), trot->name());
}

}  // namespace
}  // namespace stirrup::rig
