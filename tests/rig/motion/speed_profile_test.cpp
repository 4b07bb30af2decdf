#include "rig/motion/speed_profile.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

using Key = SpeedProfile::Key;
using Over = SpeedProfile::Over;

std::string errorOf(std::vector<Key> keys, Over over = Over::Time) {
  return stirrup::test::errorOf([&] { SpeedProfile p(std::move(keys), over, 10.0, "scene.json: clip"); }, "");
}

TEST(SpeedProfile, ASteadySpeedCoversSpeedTimesTime) {
  const SpeedProfile p({{0, 360}}, Over::Time, 10.0, "p");
  for (double t : {0.0, 0.5, 3.3, 10.0}) {
    EXPECT_DOUBLE_EQ(p.speedAtTime(t), 360.0);
    EXPECT_NEAR(p.distanceAtTime(t), 360.0 * t, 1e-6) << t;
  }
}

// A linear ramp from 2 to 8 m/s over 4 s: the distance is the integral, 20 m; between the keys the
// speed never leaves [2, 8] m/s (the monotone cubic does not overshoot).
TEST(SpeedProfile, ARampIntegratesAndNeverOvershoots) {
  const SpeedProfile p({{1, 200}, {5, 800}}, Over::Time, 8.0, "p");
  EXPECT_NEAR(p.distanceAtTime(1.0), 200.0, 1e-6);
  EXPECT_NEAR(p.distanceAtTime(5.0), 200.0 + 2000.0, 1e-3);
  EXPECT_NEAR(p.distanceAtTime(8.0), 2200.0 + 2400.0, 1e-3);
  const SpeedProfile q({{0, 900}, {2, 900}, {3, 200}, {6, 250}}, Over::Time, 8.0, "q");
  for (double t = 0; t <= 8.0; t += 0.01) {
    EXPECT_GE(q.speedAtTime(t), 200.0 - 1e-9) << t;
    EXPECT_LE(q.speedAtTime(t), 900.0 + 1e-9) << t;
    // The distance grows at the speed (C1 in time).
    EXPECT_NEAR((q.distanceAtTime(t + 1e-3) - q.distanceAtTime(t)) / 1e-3, q.speedAtTime(t + 5e-4), 0.5) << t;
  }
}

// Keys over distance: 3 m/s for the first 10 m, then 6 m/s: the first 10 m take 3.33 s.
TEST(SpeedProfile, KeysOverDistance) {
  const SpeedProfile p({{0, 300}, {1000, 300}, {1000.001, 600}}, Over::Distance, 10.0, "p");
  EXPECT_NEAR(p.distanceAtTime(1000.0 / 300.0), 1000.0, 0.5);
  EXPECT_NEAR(p.speedAtTime(2.0), 300.0, 1e-6);
  EXPECT_NEAR(p.speedAtTime(5.0), 600.0, 1e-6);
}

TEST(SpeedProfile, BadKeysAreOneLineErrorsNamingTheField) {
  EXPECT_EQ(errorOf({}), "scene.json: clip: speed: expected at least one key [seconds, cm/s], got none");
  EXPECT_EQ(errorOf({{0, 300}, {1, 0}}), "scene.json: clip: speed[1]: expected a speed from 1 to 5000 cm/s, got 0");
  EXPECT_EQ(errorOf({{0, -5}}), "scene.json: clip: speed[0]: expected a speed from 1 to 5000 cm/s, got -5");
  EXPECT_EQ(errorOf({{0, std::numeric_limits<double>::quiet_NaN()}}),
            "scene.json: clip: speed[0]: expected a speed from 1 to 5000 cm/s, got nan");
  EXPECT_EQ(errorOf({{0, 300}, {0, 400}}), "scene.json: clip: speed[1]: expected a time after speed[0]'s 0, got 0");
  EXPECT_EQ(errorOf({{500, 300}, {200, 400}}, Over::Distance),
            "scene.json: clip: speed[1]: expected a distance after speed[0]'s 500, got 200");
  EXPECT_EQ(errorOf({{std::numeric_limits<double>::infinity(), 300}}), "scene.json: clip: speed[0]: expected a time from -1e+07 to 1e+07 s, got inf");
  EXPECT_EQ(errorOf({{0, 1e308}}), "scene.json: clip: speed[0]: expected a speed from 1 to 5000 cm/s, got 1e+308");
}

// Walk to gallop and back: each change once, one gait at a time, up at the up thresholds and down at
// the down ones.
TEST(GaitSchedule, ChangesGaitAtTheThresholdsOnceEach) {
  const SpeedProfile up_down({{0, 150}, {8, 950}, {16, 150}}, Over::Time, 16.0, "p");
  const GaitThresholds th;
  const GaitSchedule g(up_down, th);
  ASSERT_EQ(g.changes().size(), 6u);
  const PathGait order[] = {PathGait::Trot, PathGait::Canter, PathGait::Gallop, PathGait::Canter, PathGait::Trot, PathGait::Walk};
  const double at_speed[] = {th.walk_trot_up, th.trot_canter_up, th.canter_gallop_up, th.canter_gallop_down,
                             th.trot_canter_down, th.walk_trot_down};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(g.changes()[i].to, order[i]) << i;
    EXPECT_NEAR(up_down.speedAtTime(g.changes()[i].time), at_speed[i], 2.0) << i;
  }
  EXPECT_EQ(g.gaitAt(0.0), PathGait::Walk);
  EXPECT_EQ(g.gaitAt(8.0), PathGait::Gallop);
  EXPECT_EQ(g.gaitAt(16.0), PathGait::Walk);
}

// A speed wobbling about the walk-trot threshold (2 m/s ± 0.15) inside the hysteresis band: no change.
TEST(GaitSchedule, ASpeedNearAThresholdDoesNotFlicker) {
  std::vector<Key> keys;
  for (int i = 0; i <= 20; ++i) keys.push_back({0.5 * i, i % 2 ? 215.0 : 185.0});
  const SpeedProfile wobble(keys, Over::Time, 10.0, "p");
  const GaitSchedule g(wobble);
  EXPECT_TRUE(g.changes().empty());
  EXPECT_EQ(g.gaitAt(5.0), PathGait::Walk);
}

}  // namespace
}  // namespace stirrup::rig
