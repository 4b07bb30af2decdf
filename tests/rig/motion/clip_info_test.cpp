// clip info measures what a clip does, not what its parameters say: check it on clips whose answer
// is known by construction.
#include "rig/motion/clip_info.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "rig/motion/procedural_gait.h"

namespace stirrup::rig {
namespace {

TEST(ClipInfo, MeasuresTheTrotItWasBuiltFrom) {
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

TEST(ClipInfo, ReportsSlidingAndSinkingHooves) {
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

TEST(ClipInfo, PrintsTheReferenceBesideTheNumbers) {
  const ProceduralGait trot(trotParams(), 4.0);
  const ClipInfo info = measureClip(trot);
  const auto ref = gaitReference("trot");
  ASSERT_TRUE(ref);
  const std::string text = formatClipInfo(info, &*ref);
  EXPECT_NE(text.find("stride frequency (Hz)        1.260   reference 1.24–1.28  ok"), std::string::npos) << text;
  EXPECT_EQ(text.find("OUTSIDE"), std::string::npos) << text;
  const nlohmann::json j = clipInfoJson(info, &*ref);
  EXPECT_EQ(j["footfall_order"], nlohmann::json({"lbHoof", "rfHoof", "rbHoof", "lfHoof"}));
  EXPECT_EQ(j["reference"]["suspensions_per_stride"], 2);
  EXPECT_TRUE(j["all_ok"].get<bool>());
  EXPECT_TRUE(j["verdicts"]["lfHoof.touchdown_phase"].get<bool>());
  EXPECT_TRUE(j["hooves"]["lfHoof"]["touchdown_ok"].get<bool>());
  EXPECT_NE(text.find("verdict: all 16 numbers inside the reference"), std::string::npos) << text;
  EXPECT_FALSE(gaitReference("pace"));
  EXPECT_FALSE(gaitReference("jump")->periodic);
}

TEST(ClipInfo, PhaseDistanceGoesTheShortWayRound) {
  EXPECT_NEAR(phaseDistance(0.98, 0.0), 0.02, 1e-12);
  EXPECT_NEAR(phaseDistance(0.0, 0.98), 0.02, 1e-12);
  EXPECT_NEAR(phaseDistance(0.25, 0.75), 0.5, 1e-12);
  EXPECT_NEAR(phaseDistance(0.538, 0.5), 0.038, 1e-12);
  EXPECT_NEAR(phaseDistance(0.27, Range{0.25, 0.30}), 0.0, 1e-12);
  EXPECT_NEAR(phaseDistance(0.20, Range{0.25, 0.30}), 0.05, 1e-12);
  EXPECT_NEAR(phaseDistance(0.36, Range{0.25, 0.30}), 0.06, 1e-12);
  EXPECT_NEAR(phaseDistance(0.97, Range{0.0, 0.0}), 0.03, 1e-12);
}

const Verdict& find(const std::vector<Verdict>& v, const std::string& key) {
  for (const Verdict& x : v)
    if (x.key == key) return x;
  ADD_FAILURE() << "no verdict " << key;
  static const Verdict none;
  return none;
}

// A trot whose left fore lands .10 late, whose trunk bounces once per stride and whose hooves stay
// down too long for any suspension: each is OUTSIDE, in the text and as a JSON boolean.
TEST(ClipInfo, TouchdownSuspensionAndBounceVerdictsCanFail) {
  GaitParams g = trotParams();
  g.touchdown_phase[0] = 0.638;
  g.trunk_cycles_per_stride = 1;
  g.duty_factor = {0.55, 0.55, 0.55, 0.55};
  const ClipInfo info = measureClip(ProceduralGait(g, 6.0));
  const GaitReference ref = *gaitReference("trot");
  const std::vector<Verdict> v = clipVerdicts(info, ref);
  EXPECT_FALSE(find(v, "lfHoof.touchdown_phase").ok);
  EXPECT_NEAR(find(v, "lfHoof.touchdown_phase").value, 0.638, 0.002);
  EXPECT_TRUE(find(v, "rfHoof.touchdown_phase").ok);  // .038: the 30 ms hind lead, inside ±.05
  EXPECT_FALSE(find(v, "suspensions_per_stride").ok);
  EXPECT_FALSE(find(v, "rear_pivot_cycles_per_stride").ok);
  EXPECT_FALSE(find(v, "lfHoof.duty_factor").ok);
  const std::string text = formatClipInfo(info, &ref);
  EXPECT_NE(text.find("0.50 OUTSIDE"), std::string::npos) << text;
  EXPECT_NE(text.find("suspensions per stride       0.00   reference 2  OUTSIDE"), std::string::npos) << text;
  EXPECT_NE(text.find("rear pivot cycles/stride     1.00   reference 2  OUTSIDE"), std::string::npos) << text;
  EXPECT_NE(text.find("verdict: OUTSIDE the reference"), std::string::npos) << text;
  const nlohmann::json j = clipInfoJson(info, &ref);
  EXPECT_FALSE(j["hooves"]["lfHoof"]["touchdown_ok"].get<bool>());
  EXPECT_FALSE(j["verdicts"]["suspensions_per_stride"].get<bool>());
  EXPECT_FALSE(j["verdicts"]["rear_pivot_cycles_per_stride"].get<bool>());
  EXPECT_FALSE(j["all_ok"].get<bool>());
}

// The gallop's fore pair is judged against the phases that leave one suspension with Witte's stance
// times (docs/horse-clips.md, "Gallop phases"), and the table's verdict is printed beside it: the
// generator's .36/.46 are ok against the first, OUTSIDE against the table. A gallop built on the table's
// .50/.60 shows why: two suspensions per stride, and OUTSIDE against the one-suspension phases.
TEST(ClipInfo, GallopForePairAgainstTheOneSuspensionPhasesAndTheTable) {
  const auto phases = gallopOneSuspensionForePhases(2.0);
  EXPECT_NEAR(phases[0], 0.10 + 0.143 * 2.0, 1e-12);
  EXPECT_NEAR(phases[1], 0.20 + 0.143 * 2.0, 1e-12);
  EXPECT_NEAR(gallopOneSuspensionForePhases(2.4)[0], 0.10 + 0.094 * 2.4, 1e-12);
  const GaitReference ref = *gaitReference("gallop");
  const ClipInfo ours = measureClip(ProceduralGait(gallopParams(), 6.0));
  const std::vector<Verdict> v = clipVerdicts(ours, ref);
  EXPECT_TRUE(find(v, "lfHoof.touchdown_phase").ok);
  EXPECT_NE(find(v, "lfHoof.touchdown_phase").note.find("the table's 0.50 is 0.14 away: OUTSIDE"), std::string::npos)
      << find(v, "lfHoof.touchdown_phase").note;
  const nlohmann::json j = clipInfoJson(ours, &ref);
  EXPECT_TRUE(j["hooves"]["lfHoof"]["touchdown_ok"].get<bool>());
  EXPECT_FALSE(j["hooves"]["lfHoof"]["touchdown_ok_table"].get<bool>());
  EXPECT_EQ(j["hooves"]["lfHoof"]["reference_touchdown_phase_table"], nlohmann::json({0.5, 0.5}));
  EXPECT_TRUE(j["all_ok"].get<bool>());
  const std::string text = formatClipInfo(ours, &ref);
  EXPECT_NE(text.find("0.39* ok"), std::string::npos) << text;
  EXPECT_NE(text.find("Against the table's phases they are 0.14/0.14 away: OUTSIDE"), std::string::npos) << text;

  GaitParams table = gallopParams();
  table.touchdown_phase = {0.50, 0.60, 0.0, 0.10};
  const ClipInfo muybridge = measureClip(ProceduralGait(table, 6.0));
  const std::vector<Verdict> t = clipVerdicts(muybridge, ref);
  EXPECT_NEAR(muybridge.suspensions_per_stride, 2.0, 1e-9);
  EXPECT_FALSE(find(t, "suspensions_per_stride").ok);
  EXPECT_FALSE(find(t, "lfHoof.touchdown_phase").ok);
  EXPECT_EQ(find(t, "lfHoof.touchdown_phase").note.find("OUTSIDE"), std::string::npos);  // the table's: ok
}

// Pitch dips below -10° (croup-ups) with every hoof always down: a "buck" that never leaves the ground.
class GroundedBuck final : public Clip {
 public:
  std::string name() const override { return "grounded"; }
  double duration() const override { return 3.0; }
  HorseFrame sample(double t) const override {
    HorseFrame f;
    const double s = std::sin(std::numbers::pi * t);  // three dips of -25°, one per second
    f.controls[HorseChannel::rearPivotRz] = -25.0 * s * s;
    return f;
  }
};

TEST(ClipInfo, BuckWithoutALeapIsOutside) {
  const ClipInfo info = measureClip(GroundedBuck());
  EXPECT_EQ(info.croup_ups, 3);
  EXPECT_EQ(info.airborne_phases, 0);
  const GaitReference ref = *gaitReference("buck");
  const std::vector<Verdict> v = clipVerdicts(info, ref);
  EXPECT_TRUE(find(v, "buck.croup_pitch_deg").ok);
  EXPECT_FALSE(find(v, "buck.airborne_phases").ok);
  EXPECT_NE(formatClipInfo(info, &ref).find("buck: all four hooves off    0   reference ≥ 3  OUTSIDE"), std::string::npos)
      << formatClipInfo(info, &ref);
}


}  // namespace
}  // namespace stirrup::rig
