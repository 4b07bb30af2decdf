// The gait reference: docs/gait-reference.md's ranges for each gait and scripted movement, and the
// verdict (ok / OUTSIDE) a measured clip (rig/motion/clip_measure.h) gets against them, so a user sees
// how far a clip is from a real horse.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "rig/motion/clip_measure.h"

namespace stirrup::rig {

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

}  // namespace stirrup::rig
