// Measuring a clip from the clip itself: hoof heights and positions sampled over time give per-hoof
// touchdown phase, duty factor and peak height, stride frequency and length, speed, suspensions, the
// rear pivot's bounce and pitch, and any hoof that slides or sinks; for the scripted movements the
// trunk's extreme pitches, how long it is held up, airborne phases, the pitch at lift-off and how far
// a hoof slides while down. rig/motion/gait_reference.h judges the numbers against a real horse's,
// rig/motion/clip_report.h prints them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rig/clip.h"

namespace stirrup::rig {

// The hooves as ClipInfo::hooves holds them (lf, rf, lb, rb), by their names in reports.
inline constexpr std::array<const char*, 4> kHoofNames = {"lfHoof", "rfHoof", "lbHoof", "rbHoof"};
// A stance whose place moves at least this far (cm) is a sliding stance (float noise is far less).
inline constexpr double kSlidingStanceCm = 1.0;

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

}  // namespace stirrup::rig
