// Measuring a clip from the clip itself: hoof heights and positions sampled over time give per-hoof
// touchdown phase, duty factor and peak height, stride frequency and length, speed, suspensions, the
// rear pivot's bounce and pitch, and any hoof that slides or sinks; for the scripted movements the
// trunk's extreme pitches, how long it is held up, airborne phases, the pitch at lift-off and how far
// a hoof slides while down. Beside each number sits the range docs/gait-reference.md gives for
// the gait or movement and a verdict (ok / OUTSIDE), so a user sees how far a clip is from a real horse.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/clip.h"

namespace stirrup::rig {

struct ClipInfoOptions {
  double sample_hz = 1000.0;    // measurement rate
  double fps = 24.0;            // frame rate for per-frame slide and continuity
  double ground_cm = 0.001;     // a hoof at or below this height (10 µm) is down
  double slide_limit_mm = 3.0;  // per frame, for a down hoof (gait-reference: "a few mm per frame")
  double start_s = 0.0;
  double end_s = -1.0;          // < 0: the clip's duration
  // The trunk pitch band whose longest continuous stay is `pitch_held_s` (gait-reference's rear: 40–70°).
  double held_pitch_lo_deg = 40.0, held_pitch_hi_deg = 70.0;
  // A croup-up counts when rearPivot.rz falls below this and ends when it rises above half of it.
  double croup_up_deg = -10.0;
  // The horse's rest hoof places in its travel frame ((x, z) cm; lf, rf, lb, rb): where a turning clip
  // swings a hoof from. Slides are measured in the world through the travel frame.
  std::array<glm::dvec2, 4> hoof_rest = kDefaultHoofRest;
  // Measure the clip mirrored left for right (mirrorLeftRight): a left-lead canter or gallop then
  // reads against gait-reference.md's right-lead footfalls.
  bool mirror = false;
};

// The frame mirrored left for right: left and right hooves swap, and sideways moves and rolls and
// yaws change sign. A left-lead canter mirrored is a right-lead canter.
HorseFrame mirrorLeftRight(const HorseFrame& f);

struct HoofInfo {
  double touchdown_phase = 0.0;  // fraction of the stride after the left hind's touchdown
  double duty_factor = 0.0;
  double peak_height_cm = 0.0;
  double lowest_cm = 0.0;        // below 0 = sinks into the ground
  double max_slide_mm = 0.0;     // largest world movement in one frame while down
  double max_slide_at_s = 0.0;
  int touchdowns = 0;
  // The stance (one run of samples with the hoof down) whose place moves furthest in the world: how
  // far (cm, from where it landed), and when it began and ended.
  double stance_slide_cm = 0.0, stance_slide_from_s = 0.0, stance_slide_to_s = 0.0;
  // The largest per-frame slide while down outside that stance (a sliding stop's hind hooves: any
  // slide besides the slide itself).
  double max_slide_outside_stance_mm = 0.0;
};

struct ClipInfo {
  std::string name;
  double duration_s = 0.0, start_s = 0.0, end_s = 0.0, fps = 24.0;
  double sample_hz = 1000.0;          // the options' measurement rate
  double slide_limit_mm = 3.0;        // the options' per-frame slide limit the problems were judged by
  std::array<HoofInfo, 4> hooves;     // lf, rf, lb, rb
  std::vector<int> footfall_order;    // hoof indices by touchdown phase, left hind first
  int strides = 0;                    // whole left-hind strides measured (0: not periodic)
  double stride_hz = 0.0, stride_length_cm = 0.0, speed_cm_s = 0.0;
  double suspensions_per_stride = 0.0, suspension_ms = 0.0;
  double pivot_ty_peak_to_peak_cm = 0.0, pivot_ty_cycles_per_stride = 0.0;
  double pitch_min_deg = 0.0, pitch_max_deg = 0.0;  // over the whole strides (the whole window if none)
  // Over the whole measured window, strides or not (the scripted movements):
  double pitch_lowest_deg = 0.0, pitch_highest_deg = 0.0;
  double pitch_held_s = 0.0;       // longest continuous time inside the held band (options, 40–70°)
  int croup_ups = 0;               // separate dips of the pitch below options.croup_up_deg
  int airborne_phases = 0;         // runs with no hoof down that begin after a hoof was down
  double longest_airborne_ms = 0.0, longest_airborne_from_s = 0.0;
  double liftoff_pitch_deg = 0.0;  // rearPivot.rz as the last hoof leaves for the longest airborne phase
  int slide_hoof = -1;             // the hoof with the largest stance slide
  int fore_touchdowns_during_slide = 0;  // fore touchdowns while that hoof slides (the stop: still stepping)
  // The largest frame-to-frame change of any channel and which one.
  double max_channel_step = 0.0;
  std::string max_step_channel;
  double max_step_at_s = 0.0;
  std::vector<std::string> problems;  // one line each: hooves that slide or sink
};

ClipInfo measureClip(const Clip& clip, const ClipInfoOptions& options = {});

// gait-reference.md ranges for one gait or movement; an unset optional means it gives no number.
struct Range {
  double lo = 0.0, hi = 0.0;
  bool contains(double v) const { return v >= lo - 1e-6 * std::abs(lo) && v <= hi + 1e-6 * std::abs(hi); }
};
// How far apart two stride phases are, the short way round the stride (0 .. 0.5).
double phaseDistance(double a, double b);
// The same from a phase to the nearest point of [r.lo, r.hi] (0 inside it).
double phaseDistance(double a, const Range& r);

// A measured touchdown phase is ok within this many strides of the reference's phase (or range): at
// the trot 40 ms, which holds the 30 ms the hind hoof of a diagonal lands before its fore.
inline constexpr double kTouchdownTolerance = 0.05;
// A measured count per stride (suspensions, rear pivot cycles) is ok within this of the reference's
// whole number: at most one stride in ten differs.
inline constexpr double kPerStrideTolerance = 0.1;

struct GaitReference {
  std::string gait;
  bool periodic = true;  // a gait measured stride by stride; false: a scripted movement
  std::array<Range, 4> touchdown_phase{};  // lf, rf, lb, rb: a phase (lo == hi) or a range
  std::optional<Range> stride_hz, stride_length_cm, speed_cm_s, duty_fore, duty_hind;
  int suspensions_per_stride = 0;
  std::optional<Range> suspension_ms, pivot_ty_peak_to_peak_cm, pitch_range_deg;
  int pivot_cycles_per_stride = 0;   // 0 = not given
  // The gallop: the table's fore touchdowns (.50/.60) with Witte's stance times give two suspensions
  // where the reference counts one; the fore pair is compared with the latest phases that leave one
  // (docs/horse-clips.md, "Gallop phases"): see gallopOneSuspensionForePhases().
  bool one_suspension_fore_phases = false;
  // Scripted movements (Kuhnel 5.1, 5.4–5.6 via gait-reference):
  std::optional<Range> rear_pitch_deg, rear_held_s;   // rear: 40–70° held 0.5–2 s
  std::optional<Range> croup_pitch_deg;               // buck: croup up −20..−35°
  bool all_four_leave_ground = false;                 // buck: a suspension in every buck
  std::optional<Range> takeoff_pitch_deg;             // jump: 21.4 ± 2.5° at the leading hind's lift-off
  std::optional<Range> slide_cm;                      // stop: up to ≈ 10 m
  int fore_steps_during_slide = 0;                    // stop: the forelegs keep stepping (at least this)
};
// The reference for "walk", "trot", "canter", "gallop" (right lead) and the scripted "stop", "jump",
// "rear", "buck"; nullopt for other clips.
std::optional<GaitReference> gaitReference(const std::string& gait);

// The gallop's fore touchdowns that leave one suspension: the left fore lands as the right hind
// (table phase .10) lifts off after Witte's hind stance at that stride frequency (143 ms at 2.0 Hz ->
// 94 ms at 2.4 Hz), the right fore the table's .10 later. {lf, rf}; at 2.0 Hz {.386, .486}.
std::array<double, 2> gallopOneSuspensionForePhases(double stride_hz);

// One number against its reference: what `clip info` prints as ok / OUTSIDE and --json as booleans.
struct Verdict {
  std::string key;        // e.g. "stride_hz", "lfHoof.touchdown_phase", "rear.held_s"
  double value = 0.0;
  Range range;            // what it was compared with
  bool ok = false;
  std::string note;       // why this reference (empty when it is the table's number)
};
std::vector<Verdict> clipVerdicts(const ClipInfo& info, const GaitReference& reference);

// Human-readable table with the reference beside each number (reference may be null).
std::string formatClipInfo(const ClipInfo& info, const GaitReference* reference);
nlohmann::json clipInfoJson(const ClipInfo& info, const GaitReference* reference);

}  // namespace stirrup::rig
