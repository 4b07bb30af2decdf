#include "rig/motion/crowd_middle_clip.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// A horse standing still at one place and heading, with its controls off rest (so the middle's rest
// controls show that it does not average them).
class StandingClip : public Clip {
 public:
  StandingClip(double x, double z, double y, double heading_deg) {
    frame_.travel_cm = x, frame_.travel_z_cm = z, frame_.ground_y_cm = y, frame_.heading_deg = heading_deg;
    frame_.controls[HorseChannel::rearPivotTy] = 7.0;
  }
  std::string name() const override { return "standing"; }
  double duration() const override { return duration_s_; }
  HorseFrame sample(double) const override { return frame_; }
  double duration_s_ = 2.0;

 private:
  HorseFrame frame_;
};

// The middle stands at the mean place and ground height of the pairs, at rest.
TEST(CrowdMiddleClip, StandsAtThePairsMeanPlace) {
  StandingClip a(100, -300, 10, 0), b(500, 300, 30, 0), c(300, 900, 50, 0);
  c.duration_s_ = 5.0;
  const CrowdMiddleClip middle({&a, &b, &c});
  const HorseFrame m = middle.sample(1.0);
  EXPECT_NEAR(m.travel_cm, 300.0, 1e-12);
  EXPECT_NEAR(m.travel_z_cm, 300.0, 1e-12);
  EXPECT_NEAR(m.ground_y_cm, 30.0, 1e-12);
  EXPECT_EQ(m.heading_deg, 0.0);
  EXPECT_EQ(m.controls[HorseChannel::rearPivotTy], 0.0);
  EXPECT_EQ(middle.duration(), 5.0);  // while any pair rides
}

// Headings average as directions: 170 and -170 degrees give 180 (not 0); 30 and 90 give 60; two that
// cancel give 0.
TEST(CrowdMiddleClip, AveragesHeadingsAsDirections) {
  StandingClip a(0, 0, 0, 170), b(0, 0, 0, -170), c(0, 0, 0, 30), d(0, 0, 0, 90), e(0, 0, 0, -90);
  EXPECT_NEAR(std::abs(CrowdMiddleClip({&a, &b}).sample(0).heading_deg), 180.0, 1e-9);
  EXPECT_NEAR(CrowdMiddleClip({&c, &d}).sample(0).heading_deg, 60.0, 1e-9);
  EXPECT_NEAR(CrowdMiddleClip({&d, &e}).sample(0).heading_deg, 0.0, 1e-9);
}

// A horse galloping round a circle of 50 m at 10 m/s, its ground rising and falling 1 m every 2 s.
class CircleClip : public Clip {
 public:
  explicit CircleClip(double phase) : phase_(phase) {}
  std::string name() const override { return "circle"; }
  double duration() const override { return 10.0; }
  HorseFrame sample(double t) const override {
    const double a = phase_ + 1000.0 / 5000.0 * t;  // radians: speed over radius
    HorseFrame f;
    f.travel_cm = 5000.0 * std::sin(a), f.travel_z_cm = 5000.0 * (1.0 - std::cos(a));
    f.heading_deg = std::remainder(a * 180.0 / 3.14159265358979323846, 360.0);
    f.ground_y_cm = 100.0 * std::sin(3.14159265358979323846 * t);
    return f;
  }

 private:
  double phase_;
};

// Sampled between its table's points (the table is every 1/240 s), the middle is the pairs' average
// to a hundredth of a centimetre and degree: the table only saves time.
TEST(CrowdMiddleClip, TheTableIsTheAverageBetweenItsPoints) {
  const CircleClip a(0.0), b(0.4), c(3.0);
  const CrowdMiddleClip middle({&a, &b, &c});
  for (double t = 0.0013; t < 10.5; t += 0.0937) {
    HorseFrame exact;
    double cs = 0, sn = 0;
    for (const Clip* clip : {(const Clip*)&a, (const Clip*)&b, (const Clip*)&c}) {
      const HorseFrame f = clip->sample(t);
      exact.travel_cm += f.travel_cm / 3, exact.travel_z_cm += f.travel_z_cm / 3, exact.ground_y_cm += f.ground_y_cm / 3;
      cs += std::cos(f.heading_deg * 3.14159265358979323846 / 180.0), sn += std::sin(f.heading_deg * 3.14159265358979323846 / 180.0);
    }
    const HorseFrame m = middle.sample(t);
    EXPECT_NEAR(m.travel_cm, exact.travel_cm, 0.01) << t;
    EXPECT_NEAR(m.travel_z_cm, exact.travel_z_cm, 0.01) << t;
    EXPECT_NEAR(m.ground_y_cm, exact.ground_y_cm, 0.01) << t;
    EXPECT_NEAR(std::remainder(m.heading_deg - std::atan2(sn, cs) * 180.0 / 3.14159265358979323846, 360.0), 0.0, 0.01) << t;
  }
}

TEST(CrowdMiddleClip, NeedsAPair) {
  EXPECT_THROW(CrowdMiddleClip({}), std::invalid_argument);
  EXPECT_THROW(CrowdMiddleClip({nullptr}), std::invalid_argument);
}

}  // namespace
}  // namespace stirrup::rig
