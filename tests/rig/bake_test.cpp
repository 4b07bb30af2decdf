// The travel acceleration the bake measures for the balance stage (rig/bake.h), against motions whose
// acceleration is known by hand: the sliding stop's braking, read off its speed profile, and a turn at
// constant speed, whose acceleration is centripetal, v^2 / r toward the centre, with nothing along the
// heading.
#include "rig/bake.h"

#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rig/rig_profile.h"
#include "scene/clip_factory.h"

namespace stirrup::rig {
namespace {

constexpr double kH = kAccelerationWindowS;  // 0.2 s each side

// The sliding stop as scenes/stop.json plays it: a gallop at 900 cm/s for entry_s = 1.5 s, then the
// speed falls linearly to 0 over slide_s = 1.6 s (rig/motion/movement_clips.h, StopParams), then the
// horse stands. So the acceleration is 0, then -900 / 1.6 = -562.5 cm/s^2 from 1.5 s to 3.1 s, then 0.
// The bake's second difference averages it under a triangle 0.2 s each side (weights (h - |s - t|) /
// h^2), which is exact where the acceleration is constant for 0.2 s around t, and at a corner of the
// speed profile weighs the two sides: at 1.5 s half of each (-281.25); at 1.6 s the triangle's part
// before 1.5 s is 0.1 x 2.5 / 2 = 0.125 of it, so -562.5 x 0.875 = -492.1875.
TEST(TravelAcceleration, TheStopBrakesAtItsEntrySpeedOverItsSlide) {
  scene::ClipSpec spec;
  spec.generator = "stop";
  spec.params = {{"entry_speed_cm_s", 900}, {"entry_s", 1.5}, {"slide_s", 1.6}, {"seed", 5}};
  const auto clip = scene::makeClip(spec);
  constexpr double kBraking = -900.0 / 1.6;
  for (double t = 0.0; t <= 1.3 + 1e-9; t += 0.1) EXPECT_NEAR(travelAcceleration(*clip, t), 0.0, 1e-6) << t << " s";
  EXPECT_NEAR(travelAcceleration(*clip, 1.5), kBraking / 2.0, 1e-6);
  EXPECT_NEAR(travelAcceleration(*clip, 1.6), kBraking * 0.875, 1e-6);
  for (double t = 1.7; t <= 2.9 + 1e-9; t += 0.1) EXPECT_NEAR(travelAcceleration(*clip, t), kBraking, 1e-6) << t << " s";
  EXPECT_NEAR(travelAcceleration(*clip, 3.1), kBraking / 2.0, 1e-6);
  for (double t = 3.3; t <= clip->duration() + 1e-9; t += 0.1) EXPECT_NEAR(travelAcceleration(*clip, t), 0.0, 1e-6) << t << " s";
  // The whole of it is along the travel (+X): nothing sideways.
  EXPECT_NEAR(travelAccelerationOnGround(*clip, 2.3).x, kBraking, 1e-6);
  EXPECT_NEAR(travelAccelerationOnGround(*clip, 2.3).y, 0.0, 1e-9);
  // The bake hands the balance stage the same number.
  const BakedFrame b = bakeFrame(*clip, RigProfile::thesis(), 56, 2.3);
  EXPECT_NEAR(b.horse.travel_accel_cm_s2, kBraking, 1e-6);
}

// A horse going round a circle of radius r at speed v, turning right (toward +Z) from heading 0 at
// the origin: centre (0, r), angle w t with w = v / r.
class CircleClip : public Clip {
 public:
  CircleClip(double v, double r) : v_(v), r_(r) {}
  std::string name() const override { return "circle"; }
  double duration() const override { return 60.0; }
  HorseFrame sample(double t) const override {
    const double a = v_ / r_ * t;
    HorseFrame f;
    f.travel_cm = r_ * std::sin(a);
    f.travel_z_cm = r_ * (1.0 - std::cos(a));
    f.heading_deg = a * 180.0 / std::numbers::pi;
    return f;
  }

 private:
  double v_, r_;
};

// At 400 cm/s on a 10 m circle: v^2 / r = 160 cm/s^2 toward the centre, none along the heading. The
// second difference of a point going round a circle is exactly 2 (1 - cos(w h)) / h^2 x r toward the
// centre: v^2 / r times 1 - (w h)^2 / 12 + ..., 0.05% less at w h = 0.08 rad.
TEST(TravelAcceleration, AConstantSpeedTurnIsCentripetalAndNothingAlongTheHeading) {
  constexpr double v = 400.0, r = 1000.0;
  const CircleClip clip(v, r);
  for (double t : {0.5, 3.0, 7.7, 20.0, 41.3}) {
    const glm::dvec2 a = travelAccelerationOnGround(clip, t);
    const HorseFrame f = clip.sample(t);
    const glm::dvec2 to_centre = glm::normalize(glm::dvec2(0.0, r) - glm::dvec2(f.travel_cm, f.travel_z_cm));
    EXPECT_NEAR(glm::length(a), v * v / r, 0.001 * v * v / r) << t << " s";
    EXPECT_NEAR(glm::dot(glm::normalize(a), to_centre), 1.0, 1e-9) << t << " s";
    EXPECT_NEAR(travelAcceleration(clip, t), 0.0, 1e-6) << t << " s";
  }
}

// The bake hands the balance stage the turn's acceleration in the horse's own terms: its sideways part
// v^2 / r, + toward the horse's right in a right turn and - in a left one, and nothing along the heading.
TEST(TravelAcceleration, TheBakeHandsOnTheSidewaysPartSignedTowardTheTurn) {
  constexpr double v = 400.0, r = 1000.0;
  for (const double sense : {1.0, -1.0}) {  // right (toward +Z), then left
    const CircleClip clip(v, sense * r);
    for (double t : {0.5, 7.7, 41.3}) {
      const BakedFrame b = bakeFrame(clip, RigProfile::thesis(), 1, t);
      EXPECT_NEAR(b.horse.travel_side_accel_cm_s2, sense * v * v / r, 0.001 * v * v / r) << sense << " at " << t << " s";
      EXPECT_NEAR(b.horse.travel_accel_cm_s2, 0.0, 1e-6) << sense << " at " << t << " s";
    }
  }
  // A straight line has none.
  scene::ClipSpec spec;
  spec.generator = "canter";
  EXPECT_EQ(bakeFrame(*scene::makeClip(spec), RigProfile::thesis(), 12, 0.5).horse.travel_side_accel_cm_s2, 0.0);
}

// The same turn as a path clip draws it (rig/motion/path_clip.h), through 36 points on the 10 m circle
// at a constant 400 cm/s: the curve through the points is nearly the circle, so v^2 / r within 1%
// (measured 0.6%), toward the centre, and nothing along the heading (measured 0.07 cm/s^2).
TEST(TravelAcceleration, APathClipsCircleIsCentripetal) {
  constexpr double v = 400.0, r = 1000.0;
  nlohmann::json points = nlohmann::json::array();
  for (int i = 0; i <= 36; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 36.0;
    points.push_back({r * std::sin(a), r * (1.0 - std::cos(a))});
  }
  scene::ClipSpec spec;
  spec.generator = "path";
  spec.params = {{"points", points}, {"speed", {{0, v}, {60, v}}}};
  const auto clip = scene::makeClip(spec);
  for (double t : {3.0, 5.5, 9.0, 12.5}) {
    const glm::dvec2 a = travelAccelerationOnGround(*clip, t);
    const HorseFrame f = clip->sample(t);
    const glm::dvec2 to_centre = glm::normalize(glm::dvec2(0.0, r) - glm::dvec2(f.travel_cm, f.travel_z_cm));
    EXPECT_NEAR(glm::length(a), v * v / r, 0.01 * v * v / r) << t << " s";
    EXPECT_GT(glm::dot(glm::normalize(a), to_centre), 0.999) << t << " s";
    EXPECT_NEAR(travelAcceleration(*clip, t), 0.0, 0.5) << t << " s";
  }
}

}  // namespace
}  // namespace stirrup::rig
