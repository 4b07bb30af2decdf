// clip info measures what a clip does, not what its parameters say: check it on clips whose answer
// is known by construction.
#include "rig/motion/clip_measure.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/motion/procedural_gait.h"

namespace stirrup::rig {
namespace {

TEST(ClipMeasure, MeasuresTheTrotItWasBuiltFrom) {
  const ProceduralGait trot(trotParams(), 8.0);
  const ClipInfo info = measureClip(trot);
  EXPECT_NEAR(info.stride_hz, 1.26, 1e-3);
  EXPECT_NEAR(info.speed_cm_s, 360.0, 0.5);
  EXPECT_NEAR(info.stride_length_cm, 360.0 / 1.26, 0.5);
  for (int h = 0; h < 4; ++h) EXPECT_NEAR(info.hooves[h].duty_factor, 0.40, 0.005);
  EXPECT_NEAR(info.hooves[0].touchdown_phase, 0.538, 0.002);
  EXPECT_NEAR(info.hooves[1].touchdown_phase, 0.038, 0.002);
  EXPECT_NEAR(info.hooves[3].touchdown_phase, 0.5, 0.002);
  EXPECT_NEAR(info.hooves[0].peak_height_cm, 14.0 * 1.15, 0.01);
  EXPECT_NEAR(info.suspensions_per_stride, 2.0, 1e-9);
  // Each suspension: 0.5 - 0.038 - 0.40 of the stride = 49 ms less the 10 µm ground band.
  EXPECT_NEAR(info.suspension_ms, (0.5 - 0.038 - 0.40) / 1.26 * 1000.0, 8.0);
  EXPECT_NEAR(info.pivot_ty_peak_to_peak_cm, 6.0, 0.01);
  EXPECT_NEAR(info.pivot_ty_cycles_per_stride, 2.0, 1e-9);
  EXPECT_NEAR(info.pitch_max_deg - info.pitch_min_deg, 3.0, 0.01);
  EXPECT_TRUE(info.problems.empty());
}

// A clip whose left fore is down and slides forward at 1 m/s while the body stands still, and
// whose right hind sinks 2 cm.
class BadClip final : public Clip {
 public:
  std::string name() const override { return "bad"; }
  double duration() const override { return 2.0; }
  HorseFrame sample(double t) const override {
    HorseFrame f;
    f.controls[HorseChannel::lfHoofTx] = 100.0 * t;
    f.controls[HorseChannel::rbHoofTy] = -2.0;
    return f;
  }
};

TEST(ClipMeasure, ReportsSlidingAndSinkingHooves) {
  ClipInfoOptions o;
  o.fps = 25.0;
  const ClipInfo info = measureClip(BadClip(), o);
  EXPECT_NEAR(info.hooves[0].max_slide_mm, 40.0, 1e-6);  // 100 cm/s at 25 fps = 4 cm a frame
  EXPECT_NEAR(info.hooves[3].lowest_cm, -2.0, 1e-12);
  ASSERT_EQ(info.problems.size(), 2u);
  EXPECT_NE(info.problems[0].find("lfHoof slides 40.0 mm"), std::string::npos) << info.problems[0];
  EXPECT_NE(info.problems[1].find("rbHoof sinks 2.0 cm"), std::string::npos) << info.problems[1];
  EXPECT_EQ(info.strides, 0);
}

}  // namespace
}  // namespace stirrup::rig
