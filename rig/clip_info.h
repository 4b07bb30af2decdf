// Measuring a clip from the clip itself: hoof heights and positions sampled over time give per-hoof
// touchdown phase, duty factor and peak height, stride frequency and length, speed, suspensions, the
// rear pivot's bounce and pitch, and any hoof that slides or sinks. Beside each number sits the range
// ../shared/gait-reference.md gives for the gait, so a user sees how far a clip is from a real horse.
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
};

struct HoofInfo {
  double touchdown_phase = 0.0;  // fraction of the stride after the left hind's touchdown
  double duty_factor = 0.0;
  double peak_height_cm = 0.0;
  double lowest_cm = 0.0;        // below 0 = sinks into the ground
  double max_slide_mm = 0.0;     // largest world movement in one frame while down
  double max_slide_at_s = 0.0;
  int touchdowns = 0;
};

struct ClipInfo {
  std::string name;
  double duration_s = 0.0, start_s = 0.0, end_s = 0.0, fps = 24.0;
  std::array<HoofInfo, 4> hooves;     // lf, rf, lb, rb
  std::vector<int> footfall_order;    // hoof indices by touchdown phase, left hind first
  int strides = 0;                    // whole left-hind strides measured (0: not periodic)
  double stride_hz = 0.0, stride_length_cm = 0.0, speed_cm_s = 0.0;
  double suspensions_per_stride = 0.0, suspension_ms = 0.0;
  double pivot_ty_peak_to_peak_cm = 0.0, pivot_ty_cycles_per_stride = 0.0;
  double pitch_min_deg = 0.0, pitch_max_deg = 0.0;
  // The largest frame-to-frame change of any channel and which one.
  double max_channel_step = 0.0;
  std::string max_step_channel;
  double max_step_at_s = 0.0;
  std::vector<std::string> problems;  // one line each: hooves that slide or sink
};

ClipInfo measureClip(const Clip& clip, const ClipInfoOptions& options = {});

// gait-reference.md ranges for one gait; an unset optional means the reference gives no number.
struct Range {
  double lo = 0.0, hi = 0.0;
  bool contains(double v) const { return v >= lo - 1e-6 * std::abs(lo) && v <= hi + 1e-6 * std::abs(hi); }
};
struct GaitReference {
  std::string gait;
  std::array<double, 4> touchdown_phase{};  // lf, rf, lb, rb
  std::optional<Range> stride_hz, stride_length_cm, speed_cm_s, duty_fore, duty_hind;
  int suspensions_per_stride = 0;
  std::optional<Range> suspension_ms, pivot_ty_peak_to_peak_cm, pitch_range_deg;
  int pivot_cycles_per_stride = 0;   // 0 = not given
};
// The reference for "walk", "trot", "canter", "gallop" (right lead); nullopt for other clips.
std::optional<GaitReference> gaitReference(const std::string& gait);

// Human-readable table with the reference beside each number (reference may be null).
std::string formatClipInfo(const ClipInfo& info, const GaitReference* reference);
nlohmann::json clipInfoJson(const ClipInfo& info, const GaitReference* reference);

}  // namespace stirrup::rig
