#include "rig/motion/procedural_gait.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

constexpr HorseChannel kTx[4] = {HorseChannel::lfHoofTx, HorseChannel::rfHoofTx, HorseChannel::lbHoofTx,
                                 HorseChannel::rbHoofTx};
constexpr HorseChannel kTy[4] = {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy, HorseChannel::lbHoofTy,
                                 HorseChannel::rbHoofTy};

// Samples one stride finely: per hoof, whether it is on the ground at each step.
struct StrideSamples {
  static constexpr int kSteps = 2000;
  std::vector<std::array<bool, 4>> down;
  std::vector<HorseFrame> frames;
};

StrideSamples sampleStride(const ProceduralGait& gait) {
  StrideSamples s;
  const double period = 1.0 / gait.params().stride_hz;
  for (int i = 0; i < StrideSamples::kSteps; ++i) {
    const HorseFrame f = gait.sample(period * i / StrideSamples::kSteps);
    std::array<bool, 4> d{};
    for (int h = 0; h < 4; ++h) d[h] = f.controls[kTy[h]] < 1e-9;
    s.down.push_back(d);
    s.frames.push_back(f);
  }
  return s;
}

TEST(ProceduralGait, TrotDutyFactorsAndSuspensionsMatchTheReference) {
  const ProceduralGait trot(trotParams());
  const StrideSamples s = sampleStride(trot);
  for (int h = 0; h < 4; ++h) {
    const double duty =
        std::count_if(s.down.begin(), s.down.end(), [h](const auto& d) { return d[h]; }) /
        double(StrideSamples::kSteps);
    EXPECT_GE(duty, 0.35) << "hoof " << h;  // gait-reference: trot duty factor 0.35–0.45
    EXPECT_LE(duty, 0.45) << "hoof " << h;
  }
  // Two suspensions per stride: runs of samples with no hoof down.
  int suspensions = 0;
  for (int i = 0; i < StrideSamples::kSteps; ++i) {
    const auto none = [&](int k) {
      const auto& d = s.down[(k + StrideSamples::kSteps) % StrideSamples::kSteps];
      return !d[0] && !d[1] && !d[2] && !d[3];
    };
    if (none(i) && !none(i - 1)) ++suspensions;
  }
  EXPECT_EQ(suspensions, 2);
}

TEST(ProceduralGait, TrotMovesInDiagonalPairs) {
  const ProceduralGait trot(trotParams());
  const StrideSamples s = sampleStride(trot);
  // Left fore with right hind and right fore with left hind share most of their stance.
  int lf_rh = 0, lf_lh = 0;
  for (const auto& d : s.down) {
    lf_rh += d[0] && d[3];
    lf_lh += d[0] && d[2];
  }
  EXPECT_GT(lf_rh, StrideSamples::kSteps / 4);
  EXPECT_EQ(lf_lh, 0);
}

TEST(ProceduralGait, StanceHoovesStayPutInTheWorld) {
  const ProceduralGait trot(trotParams());
  const double dt = 1.0 / 240.0;
  for (int i = 0; i < 480; ++i) {
    const HorseFrame a = trot.sample(i * dt), b = trot.sample((i + 1) * dt);
    for (int h = 0; h < 4; ++h) {
      EXPECT_GE(a.controls[kTy[h]], 0.0);  // never below the ground
      if (a.controls[kTy[h]] == 0.0 && b.controls[kTy[h]] == 0.0) {
        const double world_a = a.travel_cm + a.controls[kTx[h]];
        const double world_b = b.travel_cm + b.controls[kTx[h]];
        EXPECT_NEAR(world_a, world_b, 1e-6) << "hoof " << h << " slides at t=" << i * dt;
      }
    }
  }
}

TEST(ProceduralGait, ChannelsAreContinuous) {
  const ProceduralGait trot(trotParams());
  const double dt = 1.0 / 24.0;
  for (int i = 0; i < 96; ++i) {
    const HorseFrame a = trot.sample(i * dt), b = trot.sample((i + 1) * dt);
    for (std::size_t c = 0; c < kHorseChannelCount; ++c) {
      // At 3.6 m/s a hoof in swing moves at most ~2.5x the body speed: 40 cm a frame at 24 fps.
      EXPECT_LT(std::abs(a.controls.value[c] - b.controls.value[c]), 40.0) << kHorseChannelNames[c];
    }
  }
}

TEST(ProceduralGait, TrunkBouncesTwicePerStrideWithTheReferenceAmplitude) {
  const ProceduralGait trot(trotParams());
  const StrideSamples s = sampleStride(trot);
  double lo = 1e9, hi = -1e9;
  int rises = 0;
  for (int i = 0; i < StrideSamples::kSteps; ++i) {
    const double y = s.frames[i].controls[HorseChannel::rearPivotTy];
    const double prev = s.frames[(i + StrideSamples::kSteps - 1) % StrideSamples::kSteps].controls[HorseChannel::rearPivotTy];
    lo = std::min(lo, y);
    hi = std::max(hi, y);
    rises += (prev < 0.0 && y >= 0.0);
  }
  EXPECT_EQ(rises, 2);
  EXPECT_NEAR(hi - lo, 6.0, 0.01);  // within gait-reference's ≈ 5–7 cm
}

TEST(ProceduralGait, StrideLengthIsSpeedOverFrequency) {
  const ProceduralGait trot(trotParams());
  EXPECT_NEAR(trot.strideLengthCm(), 360.0 / 1.26, 1e-9);
  EXPECT_GE(trot.strideLengthCm(), 260.0);  // gait-reference: trot stride 2.6–3.0 m
  EXPECT_LE(trot.strideLengthCm(), 300.0);
}

}  // namespace
}  // namespace stirrup::rig
