// Verdicts against the gait reference, on clips whose answer is known by construction.
#include "rig/motion/gait_reference.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/motion/clip_report.h"
#include "rig/motion/procedural_gait.h"

namespace stirrup::rig {
namespace {

TEST(GaitReference, PhaseDistanceGoesTheShortWayRound) {
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
TEST(GaitReference, TouchdownSuspensionAndBounceVerdictsCanFail) {
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
TEST(GaitReference, GallopForePairAgainstTheOneSuspensionPhasesAndTheTable) {
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

TEST(GaitReference, BuckWithoutALeapIsOutside) {
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
