// The movement generators against docs/gait-reference.md, measured from the clips themselves
// (rig/motion/clip_measure.h, gait_reference.h), and the rider's response per Kuhnel 2003 sections 5 and 9.
#include "rig/motion/movement_clips.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <ostream>

#include <gtest/gtest.h>

#include "rig/characters/horse_character.h"
#include "rig/error.h"
#include "rig/motion/clip_report.h"
#include "rig/rider_rig.h"
#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "scene/scene.h"

namespace stirrup::rig {
namespace {

constexpr int kLF = 0, kRF = 1, kLH = 2, kRH = 3;

std::unique_ptr<Clip> generator(const std::string& name, nlohmann::json params = nlohmann::json::object()) {
  params["generator"] = name;
  JsonObjectReader r("test", "clip", params);
  return scene::makeClip(scene::parseClipSpec(r, "."));
}

// A stretch of time in which the two hind hooves of a sliding stop may move while down: from the
// slide's start to its end, taken from the clip's own parameters.
struct SlideWindow {
  double from_s = 0.0, to_s = 0.0;
};

// Every clip: no hoof below the ground, no down hoof moving more than a few mm a frame (except the
// hind hooves of a sliding stop inside its slide window), and every channel continuous.
void expectSound(const Clip& clip, std::optional<SlideWindow> hind_slide = std::nullopt) {
  ClipInfoOptions o;
  o.fps = 24.0;
  const ClipInfo info = measureClip(clip, o);
  for (int h = 0; h < 4; ++h) {
    EXPECT_GE(info.hooves[h].lowest_cm, 0.0) << clip.name() << " hoof " << h;
    if (hind_slide && h >= 2) continue;  // checked frame by frame below
    EXPECT_LE(info.hooves[h].max_slide_mm, 3.0) << clip.name() << " hoof " << h << " at " << info.hooves[h].max_slide_at_s;
  }
  if (hind_slide) {
    // Hind hooves frame by frame, as clip info measures them: a frame that overlaps the slide window is
    // exempt, every other frame with the hoof down at both ends moves it at most 3 mm in the world.
    const std::array<std::pair<HorseChannel, HorseChannel>, 2> hind = {
        {{HorseChannel::lbHoofTx, HorseChannel::lbHoofTy}, {HorseChannel::rbHoofTx, HorseChannel::rbHoofTy}}};
    const double dt = 1.0 / o.fps;
    int exempt = 0, checked = 0;
    for (int k = 0; (k + 1) * dt <= clip.duration(); ++k) {
      const double t = k * dt;
      const HorseFrame a = clip.sample(t), b = clip.sample(t + dt);
      for (const auto& [tx, ty] : hind) {
        if (a.controls[ty] > o.ground_cm || b.controls[ty] > o.ground_cm) continue;
        if (t < hind_slide->to_s && t + dt > hind_slide->from_s) {
          ++exempt;
          continue;
        }
        ++checked;
        EXPECT_LE(10.0 * std::abs((b.travel_cm + b.controls[tx]) - (a.travel_cm + a.controls[tx])), 3.0)
            << clip.name() << " " << name(tx) << " slides outside the slide window at " << t << " s";
      }
    }
    EXPECT_GT(exempt, 0) << clip.name() << ": the slide window holds no sliding frame";
    EXPECT_GT(checked, 0) << clip.name() << ": no hind stance outside the slide window was checked";
  }
  // Continuity: sampled at 1 kHz no channel changes faster than a galloping hoof swings (a pop would
  // show as a step of centimetres in one millisecond, i.e. > 10000 /s).
  EXPECT_LT(info.max_channel_step, 2500.0) << clip.name() << ": " << info.max_step_channel << " at " << info.max_step_at_s;
  // And the body follow-through too.
  for (double t = 0.0; t + 0.001 < clip.duration(); t += 0.001) {
    const HorseFrame a = clip.sample(t), b = clip.sample(t + 0.001);
    ASSERT_LT(std::abs(a.neck_rz - b.neck_rz) + std::abs(a.head_rz - b.head_rz) + std::abs(a.tail_rz - b.tail_rz) +
                  std::abs(a.tail_ry - b.tail_ry),
              1.0)
        << clip.name() << " at " << t;
    ASSERT_LT(std::abs(a.travel_cm - b.travel_cm), 2.0) << clip.name() << " at " << t;
  }
}

struct GaitCase {
  std::string name;
  std::vector<int> order;  // footfall order, left hind first
  int suspensions;
  int bounce_cycles;
};

// gtest prints a parameter it cannot print as its bytes, and CTest names the test after that: name it.
void PrintTo(const GaitCase& c, std::ostream* os) { *os << c.name; }

class SteadyGait : public ::testing::TestWithParam<GaitCase> {};

TEST_P(SteadyGait, MeasuresInsideTheReference) {
  const GaitCase& c = GetParam();
  for (const double variation : {0.0, 0.3}) {
    const auto clip = generator(c.name, {{"variation", variation}, {"seed", 11}, {"duration_s", 8.0}});
    const ClipInfo info = measureClip(*clip);
    const GaitReference ref = *gaitReference(c.name);
    SCOPED_TRACE(c.name + " variation " + std::to_string(variation));
    ASSERT_GE(info.strides, 4);
    EXPECT_EQ(info.footfall_order, c.order);
    for (int h = 0; h < 4; ++h) {
      const auto& duty = h < 2 ? ref.duty_fore : ref.duty_hind;
      if (duty) {
        EXPECT_TRUE(duty->contains(info.hooves[h].duty_factor)) << h << ": " << info.hooves[h].duty_factor;
      }
    }
    EXPECT_NEAR(info.suspensions_per_stride, c.suspensions, 1e-9);
    EXPECT_TRUE(ref.stride_hz->contains(info.stride_hz)) << info.stride_hz;
    EXPECT_TRUE(ref.stride_length_cm->contains(info.stride_length_cm)) << info.stride_length_cm;
    EXPECT_TRUE(ref.speed_cm_s->contains(info.speed_cm_s)) << info.speed_cm_s;
    EXPECT_NEAR(info.pivot_ty_cycles_per_stride, c.bounce_cycles, 1e-9);
    if (ref.pivot_ty_peak_to_peak_cm) {
      EXPECT_TRUE(ref.pivot_ty_peak_to_peak_cm->contains(info.pivot_ty_peak_to_peak_cm)) << info.pivot_ty_peak_to_peak_cm;
    }
    if (ref.suspension_ms) {
      EXPECT_TRUE(ref.suspension_ms->contains(info.suspension_ms)) << info.suspension_ms;
    }
    const double pitch = info.pitch_max_deg - info.pitch_min_deg;
    EXPECT_TRUE(ref.pitch_range_deg->contains(pitch)) << pitch;
    expectSound(*clip);
  }
}

INSTANTIATE_TEST_SUITE_P(GaitReference, SteadyGait,
                         ::testing::Values(GaitCase{"walk", {kLH, kLF, kRH, kRF}, 0, 2},
                                           GaitCase{"trot", {kLH, kRF, kRH, kLF}, 2, 2},
                                           GaitCase{"canter", {kLH, kRH, kLF, kRF}, 1, 1},
                                           GaitCase{"gallop", {kLH, kRH, kLF, kRF}, 1, 1}),
                         [](const auto& info) { return info.param.name; });

TEST(SteadyGait, LeftLeadMirrorsTheFootfalls) {
  const auto clip = generator("canter", {{"lead", "left"}, {"duration_s", 6.0}});
  const ClipInfo info = measureClip(*clip);
  // Left lead: right hind trails, then LH with RF, then the leading LF.
  EXPECT_NEAR(info.hooves[kRH].touchdown_phase, 0.73, 0.02);
  EXPECT_GT(info.hooves[kLF].touchdown_phase, info.hooves[kRF].touchdown_phase);
}

TEST(SteadyGait, VariationIsDeterministicPerSeed) {
  const auto a = generator("gallop", {{"variation", 0.5}, {"seed", 3}});
  const auto b = generator("gallop", {{"variation", 0.5}, {"seed", 3}});
  const auto c = generator("gallop", {{"variation", 0.5}, {"seed", 4}});
  double same = 0.0, differ = 0.0;
  for (double t = 0.0; t < 4.0; t += 0.05) {
    same += std::abs(a->sample(t).controls[HorseChannel::lfHoofTy] - b->sample(t).controls[HorseChannel::lfHoofTy]);
    differ += std::abs(a->sample(t).controls[HorseChannel::lfHoofTy] - c->sample(t).controls[HorseChannel::lfHoofTy]);
  }
  EXPECT_EQ(same, 0.0);
  EXPECT_GT(differ, 1.0);
}

// gait-reference: one suspension per stride from 9 to 17 m/s. The fore pair lands before the right
// hind lifts off at every speed (its stance shortens from 143 to 94 ms), not only at 9 m/s.
TEST(SteadyGait, GallopKeepsOneSuspensionAtEverySpeed) {
  const GaitReference ref = *gaitReference("gallop");
  for (const double speed : {900.0, 1300.0, 1700.0}) {
    for (const double variation : {0.0, 0.3}) {
      const auto clip = generator("gallop", {{"speed_cm_s", speed}, {"variation", variation}, {"duration_s", 6.0}});
      const ClipInfo info = measureClip(*clip);
      SCOPED_TRACE(std::to_string(speed) + " cm/s, variation " + std::to_string(variation));
      EXPECT_NEAR(info.suspensions_per_stride, 1.0, 1e-9);
      for (const Verdict& v : clipVerdicts(info, ref)) EXPECT_TRUE(v.ok) << v.key << " = " << v.value;
    }
  }
}

TEST(GaitSequence, WalkTrotCanterGallopStopBlendsWithoutPops) {
  const auto clip = generator("sequence", {{"gaits", "walk,trot,canter,gallop"}, {"end_with_stop", true}});
  // The stop starts after the four 3 s segments (the sequence's defaults) and slides for slide_s.
  const StopParams stop;
  expectSound(*clip, SlideWindow{4 * 3.0, 4 * 3.0 + stop.slide_s});
  // Speed ends at zero after the stop and the travel never goes backwards.
  const HorseFrame end = clip->sample(clip->duration());
  EXPECT_NEAR(end.travel_cm, clip->sample(clip->duration() - 0.5).travel_cm, 1e-6);
  for (double t = 0.0; t < clip->duration(); t += 0.01)
    EXPECT_GE(clip->sample(t + 0.01).travel_cm, clip->sample(t).travel_cm - 1e-9);
}

TEST(GaitSequence, EachSegmentPlaysItsGait) {
  const Movement m = makeGaitSequence({walkParams(), trotParams(), canterParams(), gallopParams()}, 4.0, 1.0, {0.0, 1});
  const MovementClip clip(m);
  const std::array<std::string, 4> names = {"walk", "trot", "canter", "gallop"};
  for (int i = 0; i < 4; ++i) {
    ClipInfoOptions o;
    o.start_s = 4.0 * i + 0.6;  // past the blend
    o.end_s = 4.0 * i + 3.4;
    const ClipInfo info = measureClip(clip, o);
    const GaitReference ref = *gaitReference(names[i]);
    EXPECT_TRUE(ref.stride_hz->contains(info.stride_hz)) << names[i] << " " << info.stride_hz;
    EXPECT_TRUE(ref.speed_cm_s->contains(info.speed_cm_s)) << names[i] << " " << info.speed_cm_s;
  }
}

// ---- the scripted movements ----

TEST(Stop, HindHoovesSlideUnderTheBodyWhileForelegsStep) {
  const StopParams p;
  const MovementClip clip(makeStop(p));
  expectSound(clip, SlideWindow{p.entry_s, p.entry_s + p.slide_s});
  const double mid = p.entry_s + 0.5 * p.slide_s;
  const HorseFrame f = clip.sample(mid);
  // Hind hooves drawn forward under the body, down, and moving in the world with it (the slide).
  for (HorseChannel tx : {HorseChannel::lbHoofTx, HorseChannel::rbHoofTx}) EXPECT_GT(f.controls[tx], 30.0);
  EXPECT_EQ(f.controls[HorseChannel::lbHoofTy], 0.0);
  EXPECT_GT(clip.sample(mid + 0.1).travel_cm - f.travel_cm, 10.0);
  // Croup lowered, front up.
  EXPECT_LT(f.controls[HorseChannel::rearPivotTy], -20.0);
  EXPECT_GT(f.controls[HorseChannel::rearPivotRz], 4.0);
  // The forelegs keep stepping during the slide.
  int fore_lifts = 0;
  bool was_down = true;
  for (double t = p.entry_s + 0.2; t < p.entry_s + p.slide_s; t += 0.005) {
    const bool down = clip.sample(t).controls[HorseChannel::lfHoofTy] == 0.0;
    fore_lifts += was_down && !down;
    was_down = down;
  }
  EXPECT_GE(fore_lifts, 2);
  // Slide length: gait-reference, up to ≈ 10 m.
  const double slide = clip.sample(p.entry_s + p.slide_s).travel_cm - clip.sample(p.entry_s).travel_cm;
  EXPECT_GT(slide, 300.0);
  EXPECT_LT(slide, 1000.0);
}

TEST(Jump, TakeOffFlightAndLanding) {
  const JumpParams p;
  const MovementClip clip(makeJump(p));
  expectSound(clip);
  const JumpTimes jt = jumpTimes(p);
  // Take-off pitch (gait-reference: 21.4 ± 2.5°), body on a parabola, forelegs tucked, landing pitch -.
  EXPECT_NEAR(clip.sample(jt.takeoff_s).controls[HorseChannel::rearPivotRz], 21.4, 2.5);
  const double mid = 0.5 * (jt.takeoff_s + jt.landing_s);
  const HorseFrame apex = clip.sample(mid);
  EXPECT_NEAR(apex.controls[HorseChannel::rearPivotTy], jt.apex_cm, 1.0);
  for (HorseChannel ty : {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy, HorseChannel::lbHoofTy, HorseChannel::rbHoofTy})
    EXPECT_GT(apex.controls[ty], p.fence_height_cm) << "hooves clear the fence";
  EXPECT_LT(clip.sample(jt.landing_s).controls[HorseChannel::rearPivotRz], -10.0);
  // Ballistic: the flight lasts sqrt(8 h / g).
  EXPECT_NEAR(jt.landing_s - jt.takeoff_s, std::sqrt(8.0 * jt.apex_cm / 981.0), 1e-9);
  // A higher fence flies higher and longer.
  JumpParams high = p;
  high.fence_height_cm = 130.0;
  EXPECT_GT(jumpTimes(high).apex_cm, jt.apex_cm);
}

// The fence in the world: wherever a hoof passes over the fence's rails (the default horse's rest hoof
// places, plus the hoof's radius), its sole is above the top rail — at the default and a high fence.
TEST(Jump, EveryHoofClearsTheFenceWhereverItCrossesIt) {
  const HorseParams horse;
  const std::array<std::pair<HorseChannel, HorseChannel>, 4> hooves = {{
      {HorseChannel::lfHoofTx, HorseChannel::lfHoofTy}, {HorseChannel::rfHoofTx, HorseChannel::rfHoofTy},
      {HorseChannel::lbHoofTx, HorseChannel::lbHoofTy}, {HorseChannel::rbHoofTx, HorseChannel::rbHoofTy}}};
  const std::array<double, 4> rest_x = {horse.fore_hoof.x, horse.fore_hoof.x, horse.hind_hoof.x, horse.hind_hoof.x};
  for (double height : {90.0, 130.0}) {
    JumpParams p;
    p.fence_height_cm = height;
    const MovementClip clip(makeJump(p));
    const std::vector<Obstacle> fences = clip.obstacles();
    ASSERT_EQ(fences.size(), 1u);
    EXPECT_EQ(fences[0].height_cm, height);
    const double fence_x = fences[0].travel_cm + 0.5 * (horse.fore_hoof.x + horse.hind_hoof.x);
    const double reach = 0.5 * fences[0].depth_cm + horse.hoof_radius;
    std::array<int, 4> crossings{};
    double margin = 1e9;
    for (double t = 0.0; t < clip.duration(); t += 0.001) {
      const HorseFrame f = clip.sample(t);
      for (int h = 0; h < 4; ++h) {
        const double x = f.travel_cm + f.controls[hooves[h].first] + rest_x[h];
        if (std::abs(x - fence_x) > reach) continue;
        ++crossings[h];
        margin = std::min(margin, f.controls[hooves[h].second] - height);
        EXPECT_GT(f.controls[hooves[h].second], height) << "hoof " << h << " at " << t << " s, fence " << height;
      }
    }
    for (int h = 0; h < 4; ++h) EXPECT_GT(crossings[h], 0) << "hoof " << h << " never passes the fence";
    std::printf("[ fence ] %.0f cm: lowest hoof over the rails %.1f cm above the top rail\n", height, margin);
  }
}

TEST(Rear, PitchHeldOnTheHindLegsWithForelegsUp) {
  const RearParams p;
  const MovementClip clip(makeRear(p));
  expectSound(clip);
  const RearTimes rt = rearTimes(p);
  for (double t = rt.hold_start_s; t <= rt.hold_end_s; t += 0.05) {
    const HorseFrame f = clip.sample(t);
    EXPECT_GE(f.controls[HorseChannel::rearPivotRz], 40.0);  // gait-reference: 40–70°
    EXPECT_LE(f.controls[HorseChannel::rearPivotRz], 70.0);
    EXPECT_GT(f.controls[HorseChannel::lfHoofTy], 80.0);
    EXPECT_LT(f.controls[HorseChannel::lfHoofTx], -20.0);  // folded back
    EXPECT_EQ(f.controls[HorseChannel::lbHoofTy], 0.0);
    EXPECT_GT(f.controls[HorseChannel::lbHoofTx], 10.0);   // under the body
  }
  EXPECT_GE(rt.hold_end_s - rt.hold_start_s, 0.5);
  EXPECT_LE(rt.hold_end_s - rt.hold_start_s, 2.0);
}

// Kuhnel 5.4: while up, the horse uses "a kicking motion to aid balance": each foreleg strikes out and
// pulls back paw_strokes times, the two legs half a stroke apart, and is still when paw_strokes = 0.
TEST(Rear, ForelegsPawTheAirWhileUp) {
  const auto strokes = [](const RearParams& p, HorseChannel tx) {
    const MovementClip clip(makeRear(p));
    const RearTimes rt = rearTimes(p);
    int turns = 0;
    double last = 0.0, prev = clip.sample(rt.hold_start_s).controls[tx];
    for (double t = rt.hold_start_s + 0.01; t <= rt.hold_end_s; t += 0.01) {
      const double x = clip.sample(t).controls[tx], d = x - prev;
      if (std::abs(d) > 1e-3) {
        if (last != 0.0 && (d > 0) != (last > 0)) ++turns;
        last = d;
      }
      prev = x;
    }
    return turns;
  };
  RearParams p;
  // Two strokes: out-back-out-back, at least three reversals of each hoof's fore-aft motion.
  EXPECT_GE(strokes(p, HorseChannel::lfHoofTx), 3);
  EXPECT_GE(strokes(p, HorseChannel::rfHoofTx), 3);
  const MovementClip clip(makeRear(p));
  const RearTimes rt = rearTimes(p);
  const HorseFrame mid = clip.sample(0.5 * (rt.hold_start_s + rt.hold_end_s));
  EXPECT_GT(std::abs(mid.controls[HorseChannel::lfHoofTx] - mid.controls[HorseChannel::rfHoofTx]), 5.0);  // out of step
  p.paw_strokes = 0;
  EXPECT_LE(strokes(p, HorseChannel::lfHoofTx), 1);
}

TEST(Buck, CroupUpHindKickFrontPlantedWithTwist) {
  const BuckParams p;
  const MovementClip clip(makeBuck(p));
  expectSound(clip);
  double min_rz = 0.0, max_hind = 0.0, max_twist = 0.0;
  for (double t = 0.0; t < clip.duration(); t += 0.005) {
    const HorseFrame f = clip.sample(t);
    min_rz = std::min(min_rz, f.controls[HorseChannel::rearPivotRz]);
    max_twist = std::max(max_twist, std::abs(f.controls[HorseChannel::rearPivotRx]));
    if (f.controls[HorseChannel::rearPivotRz] < -15.0) {
      EXPECT_EQ(f.controls[HorseChannel::lfHoofTy], 0.0) << t;  // front planted while the croup is up
      max_hind = std::max(max_hind, f.controls[HorseChannel::lbHoofTy]);
    }
  }
  EXPECT_LE(min_rz, -20.0);  // gait-reference: −20..−35°
  EXPECT_GE(min_rz, -35.0);
  EXPECT_GT(max_hind, 30.0);
  EXPECT_GT(max_twist, 4.0);
}

// gait-reference: "all four legs leave the ground" — in every buck, for a while, no hoof is down.
TEST(Buck, AllFourHoovesLeaveTheGroundInEveryBuck) {
  const BuckParams p;
  const MovementClip clip(makeBuck(p));
  constexpr double kStep = 0.002;
  for (int b = 0; b < p.bucks; ++b) {
    const BuckTimes bt = buckTimes(p, b);
    double airborne = 0.0, lowest = 1e9;
    for (double t = bt.start_s; t < bt.start_s + p.period_s; t += kStep) {
      const HorseFrame f = clip.sample(t);
      const double low = std::min({f.controls[HorseChannel::lfHoofTy], f.controls[HorseChannel::rfHoofTy],
                                   f.controls[HorseChannel::lbHoofTy], f.controls[HorseChannel::rbHoofTy]});
      if (low > 1.0) airborne += kStep;  // every hoof more than a centimetre up
      if (t > bt.hind_off_s + 0.04 && t < bt.fore_land_s - 0.04) lowest = std::min(lowest, low);
    }
    EXPECT_GE(airborne, 0.05) << "buck " << b;  // at least 50 ms with all four in the air
    EXPECT_GT(lowest, 1.0) << "buck " << b;
  }
  // Measured the way `stirrup clip info` measures it (buck to buck, left hind touchdown to left hind
  // touchdown): one suspension per buck.
  const ClipInfo info = measureClip(clip);
  EXPECT_GE(info.strides, 1);
  EXPECT_NEAR(info.suspensions_per_stride, 1.0, 1e-9);
  EXPECT_GE(info.suspension_ms, 50.0);
}

// ---- clip info's verdicts on the shipped scenes and on the scripted movements ----

// What `stirrup clip info GENERATOR` prints for every movement scene: every number inside its reference
// (the gallop's fore pair against the one-suspension phases, see gait_reference_test).
TEST(ClipInfoVerdicts, EveryDefaultSceneClipIsInsideTheReference) {
  for (const char* scene : {"walk", "trot", "canter", "gallop", "stop", "jump", "rear", "buck"}) {
    const scene::SceneSpec spec = scene::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + scene + ".json");
    const auto clip = scene::makeClip(spec.clip);
    const ClipInfo info = measureClip(*clip);
    const auto ref = gaitReference(spec.clip.generator);
    ASSERT_TRUE(ref) << scene;
    const std::vector<Verdict> verdicts = clipVerdicts(info, *ref);
    EXPECT_GE(verdicts.size(), ref->periodic ? 10u : 1u) << scene;
    for (const Verdict& v : verdicts) EXPECT_TRUE(v.ok) << scene << ": " << v.key << " = " << v.value;
    EXPECT_NE(formatClipInfo(info, &*ref).find("verdict: all"), std::string::npos) << scene;
  }
}

// Each scripted check measures the clip, so a parameter outside the reference shows as OUTSIDE.
TEST(ClipInfoVerdicts, ScriptedMovementsOutsideTheReferenceAreOutside) {
  const auto judged = [](const std::string& gen, const nlohmann::json& params, const std::string& key) {
    const auto clip = generator(gen, params);
    const std::vector<Verdict> v = clipVerdicts(measureClip(*clip), *gaitReference(gen));
    for (const Verdict& x : v)
      if (x.key == key) return x;
    ADD_FAILURE() << gen << ": no verdict " << key;
    return Verdict{};
  };
  // Rear: 55° held 1.2 s is inside; 75° is too steep, a 3 s hold too long.
  const Verdict rear = judged("rear", nlohmann::json::object(), "rear.peak_pitch_deg");
  EXPECT_TRUE(rear.ok);
  EXPECT_NEAR(rear.value, 55.0, 0.6);  // seeded ±1 %
  const Verdict held = judged("rear", nlohmann::json::object(), "rear.held_s");
  EXPECT_TRUE(held.ok);
  EXPECT_GT(held.value, 1.2);  // the hold plus the parts of the rise and descent above 40°
  EXPECT_FALSE(judged("rear", {{"angle_deg", 75}}, "rear.peak_pitch_deg").ok);
  EXPECT_FALSE(judged("rear", {{"hold_s", 3.0}}, "rear.held_s").ok);
  // Buck: −28° croup-up; −15° is not a buck's.
  EXPECT_TRUE(judged("buck", nlohmann::json::object(), "buck.croup_pitch_deg").ok);
  EXPECT_FALSE(judged("buck", {{"croup_deg", -15}}, "buck.croup_pitch_deg").ok);
  const Verdict leaps = judged("buck", {{"bucks", 4}}, "buck.airborne_phases");
  EXPECT_TRUE(leaps.ok);
  EXPECT_EQ(leaps.value, 4.0);
  // Jump: the pitch as the leading hind leaves, 21.4 ± 2.5°.
  const Verdict takeoff = judged("jump", nlohmann::json::object(), "jump.takeoff_pitch_deg");
  EXPECT_TRUE(takeoff.ok);
  EXPECT_NEAR(takeoff.value, 21.4, 0.3);
  EXPECT_FALSE(judged("jump", {{"takeoff_pitch_deg", 30}}, "jump.takeoff_pitch_deg").ok);
  // Stop: 9 m/s over 1.6 s slides 7.2 m; 17 m/s over 3 s would slide 25 m.
  const Verdict slide = judged("stop", nlohmann::json::object(), "stop.slide_cm");
  EXPECT_TRUE(slide.ok);
  EXPECT_NEAR(slide.value, 900.0 * 1.6 / 2.0, 5.0);
  EXPECT_FALSE(judged("stop", {{"entry_speed_cm_s", 1700}, {"slide_s", 3.0}}, "stop.slide_cm").ok);
  EXPECT_TRUE(judged("stop", nlohmann::json::object(), "stop.fore_steps_during_slide").ok);
}

// ---- the rider (Kuhnel 2003 sections 5 and 9) ----

double meanLowerBack(const Clip& clip, double a, double b) {
  double sum = 0.0;
  int n = 0;
  for (double t = a; t <= b; t += 0.01, ++n)
    sum += evaluateRider(clip.sample(t).controls, RigProfile::thesis())[RiderChannel::lowerBackRz];
  return sum / n;
}

TEST(RiderResponse, LeansForwardOverTheFence) {
  const JumpParams p;
  const MovementClip clip(makeJump(p));
  const JumpTimes jt = jumpTimes(p);
  const double mid = 0.5 * (jt.takeoff_s + jt.landing_s);
  EXPECT_GT(meanLowerBack(clip, jt.takeoff_s, jt.landing_s), 1.0);
  EXPECT_GT(meanLowerBack(clip, mid - 0.05, mid + 0.05), 0.0);
}

TEST(RiderResponse, LeansBackAtTheStop) {
  const StopParams p;
  const MovementClip clip(makeStop(p));
  EXPECT_LT(meanLowerBack(clip, p.entry_s + 0.3, p.entry_s + p.slide_s), 0.0);
}

TEST(RiderResponse, LeansForwardAndLiftsAtTheRear) {
  const RearParams p;
  const MovementClip clip(makeRear(p));
  const RearTimes rt = rearTimes(p);
  EXPECT_GT(meanLowerBack(clip, rt.hold_start_s, rt.hold_end_s), 1.0);
  const RiderChannels r = evaluateRider(clip.sample(0.5 * (rt.hold_start_s + rt.hold_end_s)).controls, RigProfile::thesis());
  EXPECT_GT(r[RiderChannel::cogTy], 0.0);
  const RiderChannels still = evaluateRider(clip.sample(0.0).controls, RigProfile::thesis());
  EXPECT_GT(r[RiderChannel::cogTy], still[RiderChannel::cogTy]);
}

TEST(RiderResponse, LeansForwardAsTheForehandRisesAndBackAsTheCroupRises) {
  const BuckParams p;
  const MovementClip clip(makeBuck(p));
  const BuckTimes first = buckTimes(p, 0);
  const double s = first.start_s;
  EXPECT_GT(meanLowerBack(clip, s + 0.17, s + 0.27), 0.0);
  const double croup = first.croup_peak_s;
  EXPECT_LT(meanLowerBack(clip, croup - 0.05, croup + 0.05), 0.0);
}

// ---- the rider in the steady gaits (Kuhnel 2003 section 9; docs/rider-rig.md) ----
//
// Each default gait clip (as scenes/*.json play them) sampled at 1 kHz over whole strides, the thesis
// rider evaluated on every sample.
struct Ride {
  double stride_s = 0.0;
  int strides = 0;
  std::vector<double> t;
  std::vector<HorseFrame> horse;
  std::vector<RiderChannels> rider;
  std::vector<double> series(RiderChannel c) const {
    std::vector<double> v;
    for (const RiderChannels& r : rider) v.push_back(r[c]);
    return v;
  }
  std::vector<double> series(HorseChannel c) const {
    std::vector<double> v;
    for (const HorseFrame& f : horse) v.push_back(f.controls[c]);
    return v;
  }
  // Fore-aft spread of the limbs: the fore pair's mean reach minus the hind pair's (out = +).
  std::vector<double> limbSpread() const {
    std::vector<double> v;
    for (const HorseFrame& f : horse) {
      const HorseChannels& c = f.controls;
      v.push_back(0.5 * (c[HorseChannel::lfHoofTx] + c[HorseChannel::rfHoofTx]) -
                  0.5 * (c[HorseChannel::lbHoofTx] + c[HorseChannel::rbHoofTx]));
    }
    return v;
  }
  bool airborne(std::size_t i) const {
    const HorseChannels& c = horse[i].controls;
    return c[HorseChannel::lfHoofTy] > 0.0 && c[HorseChannel::rfHoofTy] > 0.0 && c[HorseChannel::lbHoofTy] > 0.0 &&
           c[HorseChannel::rbHoofTy] > 0.0;
  }
};

Ride ride(const std::string& gait, int strides = 6) {
  const GaitParams g = *gaitParamsByName(gait);
  const auto clip = generator(gait, {{"duration_s", (strides + 1) / g.stride_hz}});
  Ride r;
  r.stride_s = 1.0 / g.stride_hz;
  r.strides = strides;
  const RigProfile thesis = RigProfile::thesis();
  for (int i = 0; i <= static_cast<int>(std::lround(strides * r.stride_s * 1000.0)); ++i) {
    const double t = i * 0.001;
    r.t.push_back(t);
    r.horse.push_back(clip->sample(t));
    r.rider.push_back(evaluateRider(r.horse.back().controls, thesis));
  }
  return r;
}

// How many times per stride a series rises through its middle (hysteresis: a quarter of its range),
// as clip info counts the rear pivot's bounce.
double risesPerStride(const std::vector<double>& y, int strides) {
  const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
  const double mid = 0.5 * (*lo + *hi), band = 0.125 * (*hi - *lo);
  int rises = 0;
  bool low = y.front() < mid;
  for (double v : y) {
    if (low && v > mid + band) ++rises, low = false;
    else if (!low && v < mid - band) low = true;
  }
  return double(rises) / strides;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

// The index of the largest value of y in samples [from, to).
std::size_t argmax(const std::vector<double>& y, std::size_t from, std::size_t to) {
  return static_cast<std::size_t>(std::max_element(y.begin() + from, y.begin() + to) - y.begin());
}

// Touchdown times of a hoof (up at one sample, down at the next).
std::vector<double> touchdowns(const Ride& r, HorseChannel ty) {
  std::vector<double> out;
  for (std::size_t i = 1; i < r.t.size(); ++i)
    if (r.horse[i].controls[ty] <= 0.0 && r.horse[i - 1].controls[ty] > 0.0) out.push_back(r.t[i]);
  return out;
}

// 9.2: "when the distance between each set of the horse's feet is the greatest the rider will bounce up
// and as they pass by each other the rider sinks back down": the lift (Eq 7) twice per stride, highest
// at the widest spread of the pairs, lowest as they pass.
TEST(RiderResponse, TrotLiftsTwicePerStrideWhereThePairsSpreadWidest) {
  const Ride r = ride("trot");
  const std::vector<double> lift = r.series(RiderChannel::cogTy);
  EXPECT_NEAR(risesPerStride(lift, r.strides), 2.0, 1e-9);
  std::vector<double> spread;
  for (const HorseFrame& f : r.horse) {
    const HorseChannels& c = f.controls;
    spread.push_back(std::abs(c[HorseChannel::lfHoofTx] - c[HorseChannel::rfHoofTx]) +
                     std::abs(c[HorseChannel::lbHoofTx] - c[HorseChannel::rbHoofTx]));
  }
  std::vector<double> neg_lift, neg_spread;
  for (std::size_t i = 0; i < lift.size(); ++i) neg_lift.push_back(-lift[i]), neg_spread.push_back(-spread[i]);
  const std::size_t half = static_cast<std::size_t>(std::lround(500.0 * r.stride_s));
  for (int k = 0; k < 2 * r.strides; ++k) {
    const std::size_t a = k * half, b = std::min(a + half, lift.size());
    // Highest lift within 0.05 stride of the widest spread, lowest within 0.05 of the narrowest.
    EXPECT_NEAR(r.t[argmax(lift, a, b)], r.t[argmax(spread, a, b)], 0.05 * r.stride_s) << "half stride " << k;
    EXPECT_NEAR(r.t[argmax(neg_lift, a, b)], r.t[argmax(neg_spread, a, b)], 0.05 * r.stride_s) << "half stride " << k;
  }
}

// Eq 1 (section 8.1): the lower back leans with the horse's pitch. At the trot the diagonal pairs' reach
// terms nearly cancel, so the lean follows the pitch (measured correlation 0.94).
TEST(RiderResponse, TrotLowerBackLeansWithThePitch) {
  const Ride r = ride("trot");
  EXPECT_GT(correlation(r.series(RiderChannel::lowerBackRz), r.series(HorseChannel::rearPivotRz)), 0.8);
  EXPECT_NEAR(risesPerStride(r.series(RiderChannel::lowerBackRz), r.strides), 1.0, 1e-9);
}

// 9.3: "The rider leans slightly back when the average position of each set of the horse's limbs move
// towards the center ... As the horse's limbs move out ... the rider leans forward", "when all of the
// horse's limbs are towards the center of the horse and the horse's feet are off the ground the rider
// lifts into the air", and "the seat slides back as the rider leans forward".
TEST(RiderResponse, GallopLeansWithTheLimbsAndLiftsInTheSuspension) {
  const Ride r = ride("gallop");
  const std::vector<double> lean = r.series(RiderChannel::lowerBackRz), lift = r.series(RiderChannel::cogTy);
  EXPECT_GT(correlation(lean, r.limbSpread()), 0.9);  // measured 0.98
  EXPECT_NEAR(risesPerStride(lean, r.strides), 1.0, 1e-9);
  EXPECT_NEAR(risesPerStride(lift, r.strides), 1.0, 1e-9);
  const std::size_t stride = static_cast<std::size_t>(std::lround(1000.0 * r.stride_s));
  for (int k = 0; k < r.strides; ++k) {
    const std::size_t top = argmax(lift, k * stride, std::min((k + 1) * stride, lift.size()));
    EXPECT_TRUE(r.airborne(top)) << "stride " << k << ": highest lift at " << r.t[top] << " s with a hoof down";
  }
  // The seat slides against the lean only weakly (measured −0.19): Eq 8's seat shift is
  // (2 × pitch − lean) × 0.1, and at the gallop the horse's pitch term is the larger.
  EXPECT_LT(correlation(r.series(RiderChannel::cogTx), lean), 0.0);
}

// The canter is not in section 9; gait-reference (Viry 2013): the body rises and falls once per stride
// at the canter, and the same expressions as the gallop apply: the lift once per stride, highest in the
// suspension, the lean following the limbs.
TEST(RiderResponse, CanterLiftsOncePerStrideAndLeansWithTheLimbs) {
  const Ride r = ride("canter");
  const std::vector<double> lean = r.series(RiderChannel::lowerBackRz), lift = r.series(RiderChannel::cogTy);
  EXPECT_NEAR(risesPerStride(lift, r.strides), 1.0, 1e-9);
  EXPECT_NEAR(risesPerStride(lean, r.strides), 1.0, 1e-9);
  EXPECT_GT(correlation(lean, r.limbSpread()), 0.9);  // measured 0.997
  const std::size_t stride = static_cast<std::size_t>(std::lround(1000.0 * r.stride_s));
  for (int k = 0; k < r.strides; ++k) {
    const std::size_t top = argmax(lift, k * stride, std::min((k + 1) * stride, lift.size()));
    EXPECT_TRUE(r.airborne(top)) << "stride " << k << ": highest lift at " << r.t[top] << " s with a hoof down";
  }
}

// 9.6: "the rider will lean forward as one of the horse's front legs is lifted and set on the ground in
// front of him. As each leg is lifted and placed in front of him a repetitive rolling motion of the
// rider is created": the lean peaks twice per stride, just before each fore hoof lands (at most 0.1
// stride before it), and the lower back rolls once per stride against the horse's roll (Eq 2).
TEST(RiderResponse, WalkLeansForwardAsEachForeHoofIsSetDownAndRolls) {
  const Ride r = ride("walk");
  const std::vector<double> lean = r.series(RiderChannel::lowerBackRz);
  EXPECT_NEAR(risesPerStride(lean, r.strides), 2.0, 1e-9);
  int checked = 0;
  for (HorseChannel ty : {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy})
    for (double land : touchdowns(r, ty)) {
      const double window = 0.25 * r.stride_s;
      if (land - window < 0.0 || land + window > r.t.back()) continue;
      const std::size_t a = static_cast<std::size_t>(std::lround((land - window) * 1000.0));
      const std::size_t b = static_cast<std::size_t>(std::lround((land + window) * 1000.0));
      const double peak = r.t[argmax(lean, a, b)];
      EXPECT_LE(peak, land) << name(ty) << " lands at " << land;
      EXPECT_GE(peak, land - 0.1 * r.stride_s) << name(ty) << " lands at " << land;
      ++checked;
    }
  EXPECT_GE(checked, 2 * (r.strides - 1));
  const std::vector<double> roll = r.series(RiderChannel::lowerBackRy);
  EXPECT_NEAR(risesPerStride(roll, r.strides), 1.0, 1e-9);
  EXPECT_LT(correlation(roll, r.series(HorseChannel::rearPivotRx)), -0.99);
}

}  // namespace
}  // namespace stirrup::rig
