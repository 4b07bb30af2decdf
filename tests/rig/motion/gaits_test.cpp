// Gait timelines (rig/motion/gaits.cpp): speed and stride frequency over the segments and their blends,
// and the footfalls a steady gait gives, checked against the gait's own definition (stride length =
// speed / stride frequency, stance = duty factor of a stride, hooves still while down).
#include "rig/motion/gaits.h"

#include <cmath>

#include <gtest/gtest.h>

#include "rig/motion/movement.h"
#include "rig/motion/procedural_gait.h"

namespace stirrup::rig {
namespace {

TEST(GaitTimeline, OneSegmentIsItsGaitThroughout) {
  Movement m;
  const GaitParams trot = trotParams();
  EXPECT_EQ(applyGaitTimeline({{{trot, 4.0}}, 1.0, 0.0, 0}, m), 4.0);
  for (double t : {0.0, 1.3, 3.9}) {
    EXPECT_NEAR(m.speed_cm_s.at(t), trot.speed_cm_s, 1e-12) << t;
    EXPECT_NEAR(m.stride_hz.at(t), trot.stride_hz, 1e-12) << t;
  }
  // The phase is the integral of the frequency: 1.26 strides a second.
  EXPECT_NEAR(m.stridePhase(2.0) - m.stridePhase(1.0), trot.stride_hz, 1e-9);
}

// Walk 3 s then trot 3 s with a 1 s blend centred on 3 s: walk until 2.5 s, trot from 3.5 s, half way
// between at 3 s (a linear ramp).
TEST(GaitTimeline, ABlendRampsLinearlyAcrossItsWindow) {
  Movement m;
  const GaitParams walk = walkParams(), trot = trotParams();
  EXPECT_EQ(applyGaitTimeline({{{walk, 3.0}, {trot, 3.0}}, 1.0, 0.0, 0}, m), 6.0);
  EXPECT_NEAR(m.speed_cm_s.at(2.4), walk.speed_cm_s, 1e-9);
  EXPECT_NEAR(m.speed_cm_s.at(3.0), 0.5 * (walk.speed_cm_s + trot.speed_cm_s), 1e-9);
  EXPECT_NEAR(m.speed_cm_s.at(3.25), 0.25 * walk.speed_cm_s + 0.75 * trot.speed_cm_s, 1e-9);
  EXPECT_NEAR(m.speed_cm_s.at(3.6), trot.speed_cm_s, 1e-9);
  EXPECT_NEAR(m.stride_hz.at(3.0), 0.5 * (walk.stride_hz + trot.stride_hz), 1e-9);
}

TEST(GaitTimeline, ASteadyGaitsFootfallsAreAStrideApartAndStill) {
  Movement m;
  GaitParams trot = trotParams();
  const GaitTimeline timeline{{{trot, 6.0}}, 1.0, 0.0, 0};
  applyGaitTimeline(timeline, m);
  const double stride_s = 1.0 / trot.stride_hz, stride_cm = trot.speed_cm_s / trot.stride_hz;  // 0.794 s, 285.7 cm
  for (int hoof = 0; hoof < 4; ++hoof) {
    const HoofSchedule s = scanFootfalls(m, timeline, hoof, 0.0, 6.0, 1e9);
    ASSERT_GE(s.size(), 6u) << hoof;  // 6 s at 1.26 strides a second: 7 or 8 touchdowns
    for (std::size_t i = 0; i < s.size(); ++i) {
      EXPECT_GE(s[i].down_s, 0.0);
      EXPECT_LT(s[i].down_s, 6.0);
      EXPECT_NEAR(s[i].up_s - s[i].down_s, trot.duty_factor[std::size_t(hoof)] * stride_s, 1e-6) << hoof << " " << i;
      if (i == 0) continue;
      EXPECT_NEAR(s[i].down_s - s[i - 1].down_s, stride_s, 1e-6) << hoof << " " << i;
      EXPECT_NEAR(s[i].x_cm - s[i - 1].x_cm, stride_cm, 1e-3) << hoof << " " << i;
    }
    // A hoof lands at its touchdown phase of the stride: left hind (2) at whole strides.
    if (hoof == 2) {
      const double phase = m.stridePhase(s[1].down_s);
      EXPECT_NEAR(phase, std::round(phase), 1e-6);
    }
    // Touchdowns whose stance would end after lift_by_s are left for a scripted movement to take.
    for (const Footfall& f : scanFootfalls(m, timeline, hoof, 0.0, 6.0, 3.0)) EXPECT_LE(f.up_s, 3.0);
  }
}

}  // namespace
}  // namespace stirrup::rig
