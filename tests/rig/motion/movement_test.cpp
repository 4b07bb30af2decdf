// Movement clips (rig/motion/movement.cpp): ramps and their integrals, eased keys, and sampling a
// footfall schedule (a hoof still in the world while down, a swing to the next footfall), with values
// worked out by hand.
#include "rig/motion/movement.h"

#include <cmath>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

Footfall footfall(double down_s, double up_s, double x_cm) {
  Footfall f;
  f.down_s = down_s;
  f.up_s = up_s;
  f.x_cm = x_cm;
  return f;
}

// 0 at 0 s rising to 100 at 2 s, then held: the integral is the triangle 100 to 2 s, then 100 a second.
TEST(Movement, RampsAreLinearWithTheirExactIntegral) {
  Ramp r;
  r.add(0.0, 0.0);
  r.add(2.0, 100.0);
  r.add(4.0, 100.0);
  EXPECT_EQ(r.at(1.0), 50.0);
  EXPECT_EQ(r.at(3.0), 100.0);
  EXPECT_EQ(r.at(9.0), 100.0);  // constant after the last key
  EXPECT_EQ(r.at(-1.0), 0.0);   // and before the first
  EXPECT_NEAR(r.integral(1.0), 25.0, 1e-12);
  EXPECT_NEAR(r.integral(2.0), 100.0, 1e-12);
  EXPECT_NEAR(r.integral(4.0), 300.0, 1e-12);
  EXPECT_NEAR(r.integral(5.0), 400.0, 1e-12);
  const Ramp constant(5.0);
  EXPECT_NEAR(constant.integral(3.0), 15.0, 1e-12);
  EXPECT_NEAR(constant.integral(-2.0), -10.0, 1e-12);  // negative before 0
}

// Smoothstep between keys: 3u² - 2u³ of the way, so half way at the middle, 0.15625 at a quarter.
TEST(Movement, KeysEaseBetweenValues) {
  Keys k;
  EXPECT_TRUE(k.empty());
  EXPECT_EQ(k.at(1.0), 0.0);
  k.add(0.0, 0.0).add(1.0, 10.0);
  EXPECT_NEAR(k.at(0.5), 5.0, 1e-12);
  EXPECT_NEAR(k.at(0.25), 1.5625, 1e-12);
  EXPECT_EQ(k.at(-1.0), 0.0);
  EXPECT_EQ(k.at(2.0), 10.0);
  // Zero slope at a key: a step either side changes the value by far less than the step times the rise.
  EXPECT_LT(std::abs(k.at(1e-4) - k.at(0.0)), 1e-6);
}

// The left fore stands at x = 50 cm from 0 to 1 s while the body travels 100 cm/s: tx = 50 - travel.
TEST(Movement, AStandingHoofStaysPutInTheWorld) {
  Movement m;
  m.name = "test";
  m.duration_s = 2.0;
  m.speed_cm_s = Ramp(100.0);
  m.hooves[0] = {footfall(0.0, 1.0, 50.0)};
  for (double t : {0.0, 0.25, 0.5, 0.9}) {
    const HorseFrame f = sampleMovement(m, t);
    EXPECT_NEAR(f.controls[HorseChannel::lfHoofTx], 50.0 - 100.0 * t, 1e-9) << t;
    EXPECT_NEAR(f.controls[HorseChannel::lfHoofTy], 0.0, 1e-12) << t;
  }
  const MovementClip clip(m);
  EXPECT_EQ(clip.name(), "test");
  EXPECT_EQ(clip.duration(), 2.0);
}

// Without travel, from x = 0 (down until 0.5 s) to x = 100 (down from 1.5 s), lift 10: the swing is
// symmetric about its middle, 1 s, where the hoof is half way along and at its peak.
TEST(Movement, ASwingRisesToItsLiftHalfWayBetweenFootfalls) {
  Movement m;
  m.duration_s = 2.0;
  Footfall first = footfall(0.0, 0.5, 0.0);
  first.swing.lift_cm = 10.0;
  m.hooves[0] = {first, footfall(1.5, 2.0, 100.0)};
  const HorseFrame mid = sampleMovement(m, 1.0);
  EXPECT_NEAR(mid.controls[HorseChannel::lfHoofTx], 50.0, 1e-9);
  EXPECT_NEAR(mid.controls[HorseChannel::lfHoofTy], 10.0, 1e-9);
  EXPECT_NEAR(sampleMovement(m, 0.5).controls[HorseChannel::lfHoofTy], 0.0, 1e-9);  // leaves the ground at lift-off
  EXPECT_NEAR(sampleMovement(m, 1.5).controls[HorseChannel::lfHoofTx], 100.0, 1e-9);
  const double early = sampleMovement(m, 0.75).controls[HorseChannel::lfHoofTy];
  EXPECT_GT(early, 0.0);
  EXPECT_LT(early, 10.0);
  EXPECT_NEAR(sampleMovement(m, 1.25).controls[HorseChannel::lfHoofTy], early, 1e-9);  // symmetric
}

// A flight from 1 to 2 s with a 50 cm apex: a parabola, 0 at both ends, 50 at 1.5 s, 37.5 at 1.25 s.
TEST(Movement, FlightIsAParabola) {
  Movement m;
  m.flight_start_s = 1.0;
  m.flight_end_s = 2.0;
  m.flight_apex_cm = 50.0;
  EXPECT_NEAR(m.flightElevationCm(1.5), 50.0, 1e-9);
  EXPECT_NEAR(m.flightElevationCm(1.25), 37.5, 1e-9);
  EXPECT_NEAR(m.flightElevationCm(1.0), 0.0, 1e-9);
  EXPECT_EQ(m.flightElevationCm(0.5), 0.0);
  EXPECT_EQ(m.flightElevationCm(2.5), 0.0);
}

}  // namespace
}  // namespace stirrup::rig
