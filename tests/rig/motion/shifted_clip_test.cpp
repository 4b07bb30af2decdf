#include "rig/motion/shifted_clip.h"

#include <gtest/gtest.h>

#include "rig/motion/path_clip.h"

namespace stirrup::rig {
namespace {

PathClip turningPath() {
  PathClipParams p;
  p.points = {{0, 0}, {1500, 0}, {2500, 800}};
  p.speed = {{0, 300}, {3, 500}};
  p.variation = 0.1;
  return PathClip(p, nullptr, "test");
}

// The shifted clip at t is the clip at t + offset: every field of the frame, at the start, through the
// turn and past the end; its duration is what is left from the shot's start.
TEST(ShiftedClip, IsTheClipAtItsOffset) {
  const PathClip clip = turningPath();
  constexpr double kOffsetS = 0.75;
  const ShiftedClip shifted(clip, kOffsetS);
  EXPECT_EQ(shifted.name(), clip.name());
  EXPECT_DOUBLE_EQ(shifted.duration(), clip.duration() - kOffsetS);
  for (double t : {0.0, 1.0 / 24.0, 2.5, 4.0, clip.duration()}) {
    const HorseFrame a = shifted.sample(t), b = clip.sample(t + kOffsetS);
    EXPECT_EQ(a.controls.value, b.controls.value) << t;
    EXPECT_EQ(a.travel_cm, b.travel_cm) << t;
    EXPECT_EQ(a.travel_z_cm, b.travel_z_cm) << t;
    EXPECT_EQ(a.heading_deg, b.heading_deg) << t;
    EXPECT_EQ(a.ground_y_cm, b.ground_y_cm) << t;
  }
  // And the offset is really applied: the horse has moved on (300 cm/s and more for 0.75 s).
  EXPECT_GT(shifted.sample(0.0).travel_cm, 200.0);
}

// Its travel frame alone is the clip's at the offset too.
TEST(ShiftedClip, TravelIsTheClipsAtItsOffset) {
  const PathClip clip = turningPath();
  constexpr double kOffsetS = 0.75;
  const ShiftedClip shifted(clip, kOffsetS);
  for (double t : {0.0, 1.0 / 24.0, 2.5, 4.0, clip.duration()}) {
    const HorseFrame a = shifted.sampleTravel(t), b = clip.sample(t + kOffsetS);
    EXPECT_EQ(a.travel_cm, b.travel_cm) << t;
    EXPECT_EQ(a.travel_z_cm, b.travel_z_cm) << t;
    EXPECT_EQ(a.heading_deg, b.heading_deg) << t;
    EXPECT_EQ(a.ground_y_cm, b.ground_y_cm) << t;
  }
}

}  // namespace
}  // namespace stirrup::rig
