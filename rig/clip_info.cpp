#include "rig/clip_info.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "rig/error.h"

namespace stirrup::rig {
namespace {

constexpr std::array<HorseChannel, 4> kTx = {HorseChannel::lfHoofTx, HorseChannel::rfHoofTx, HorseChannel::lbHoofTx,
                                             HorseChannel::rbHoofTx};
constexpr std::array<HorseChannel, 4> kTy = {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy, HorseChannel::lbHoofTy,
                                             HorseChannel::rbHoofTy};
constexpr std::array<HorseChannel, 4> kTz = {HorseChannel::lfHoofTz, HorseChannel::rfHoofTz, HorseChannel::lbHoofTz,
                                             HorseChannel::rbHoofTz};
constexpr std::array<const char*, 4> kHoofNames = {"lfHoof", "rfHoof", "lbHoof", "rbHoof"};
constexpr int kLeftHind = 2;

std::string fmt(const char* f, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}

}  // namespace

ClipInfo measureClip(const Clip& clip, const ClipInfoOptions& o) {
  ClipInfo info;
  info.name = clip.name();
  info.duration_s = clip.duration();
  info.fps = o.fps;
  info.start_s = o.start_s;
  info.end_s = o.end_s < 0.0 ? clip.duration() : o.end_s;
  if (!(info.end_s > info.start_s) || !(o.sample_hz > 0.0) || !(o.fps > 0.0))
    throw InputError("clip info: expected end > start and positive rates");
  const double dt = 1.0 / o.sample_hz;
  const int n = static_cast<int>(std::floor((info.end_s - info.start_s) * o.sample_hz)) + 1;
  std::vector<HorseFrame> frames(n);
  std::vector<std::array<bool, 4>> down(n);
  for (int i = 0; i < n; ++i) {
    frames[i] = clip.sample(info.start_s + i * dt);
    for (int h = 0; h < 4; ++h) down[i][h] = frames[i].controls[kTy[h]] <= o.ground_cm;
  }
  const auto time = [&](int i) { return info.start_s + i * dt; };

  // Touchdowns per hoof (an up sample followed by a down sample).
  std::array<std::vector<double>, 4> touchdowns;
  for (int i = 1; i < n; ++i)
    for (int h = 0; h < 4; ++h)
      if (down[i][h] && !down[i - 1][h]) touchdowns[h].push_back(time(i));
  for (int h = 0; h < 4; ++h) {
    HoofInfo& hi = info.hooves[h];
    hi.touchdowns = static_cast<int>(touchdowns[h].size());
    hi.peak_height_cm = -1e300;
    hi.lowest_cm = 1e300;
    for (const HorseFrame& f : frames) {
      hi.peak_height_cm = std::max(hi.peak_height_cm, f.controls[kTy[h]]);
      hi.lowest_cm = std::min(hi.lowest_cm, f.controls[kTy[h]]);
    }
  }

  // Strides: from one left-hind touchdown to the next. Measure over whole strides only.
  const std::vector<double>& lh = touchdowns[kLeftHind];
  info.strides = lh.size() >= 2 ? static_cast<int>(lh.size()) - 1 : 0;
  const auto index = [&](double t) { return std::clamp(static_cast<int>(std::lround((t - info.start_s) / dt)), 0, n - 1); };
  int i0 = 0, i1 = n - 1;
  if (info.strides > 0) {
    i0 = index(lh.front());
    i1 = index(lh.back());
    const double period = (lh.back() - lh.front()) / info.strides;
    info.stride_hz = 1.0 / period;
    for (int h = 0; h < 4; ++h) {
      // Circular mean of each touchdown's phase within its left-hind stride.
      double sx = 0.0, sy = 0.0;
      for (double t : touchdowns[h]) {
        auto it = std::upper_bound(lh.begin(), lh.end(), t);
        if (it == lh.begin() || it == lh.end()) continue;
        const double a = *std::prev(it), b = *it;
        const double phase = (t - a) / (b - a);
        sx += std::cos(2 * std::numbers::pi * phase);
        sy += std::sin(2 * std::numbers::pi * phase);
      }
      double phase = std::atan2(sy, sx) / (2 * std::numbers::pi);
      if (phase < -1e-9) phase += 1.0;
      info.hooves[h].touchdown_phase = std::abs(phase) < 1e-9 ? 0.0 : phase;
      // Sample intervals with the hoof down at both ends: a stance of N ms counts N, not N + 1.
      int d = 0;
      for (int i = i0; i < i1; ++i) d += down[i][h] && down[i + 1][h];
      info.hooves[h].duty_factor = double(d) / std::max(1, i1 - i0);
    }
    info.footfall_order = {0, 1, 2, 3};
    std::sort(info.footfall_order.begin(), info.footfall_order.end(), [&](int a, int b) {
      const auto key = [&](int h) { return h == kLeftHind ? -1.0 : info.hooves[h].touchdown_phase; };
      return key(a) < key(b);
    });
    // Suspensions: runs with no hoof down.
    int runs = 0, airborne = 0;
    for (int i = i0; i < i1; ++i) {
      const bool none = !down[i][0] && !down[i][1] && !down[i][2] && !down[i][3];
      const bool none_before = i > i0 && !down[i - 1][0] && !down[i - 1][1] && !down[i - 1][2] && !down[i - 1][3];
      airborne += none;
      runs += none && !none_before;
    }
    info.suspensions_per_stride = double(runs) / info.strides;
    info.suspension_ms = runs ? 1000.0 * airborne * dt / runs : 0.0;
  }
  const int s0 = info.strides > 0 ? i0 : 0, s1 = info.strides > 0 ? i1 : n - 1;
  info.speed_cm_s = (frames[s1].travel_cm - frames[s0].travel_cm) / std::max(dt, (s1 - s0) * dt);
  if (info.stride_hz > 0.0) info.stride_length_cm = info.speed_cm_s / info.stride_hz;

  // Rear pivot: height peak to peak, and how many times per stride it rises through its middle.
  double lo = 1e300, hi = -1e300, pitch_lo = 1e300, pitch_hi = -1e300;
  for (int i = s0; i <= s1; ++i) {
    const double y = frames[i].controls[HorseChannel::rearPivotTy];
    lo = std::min(lo, y);
    hi = std::max(hi, y);
    pitch_lo = std::min(pitch_lo, frames[i].controls[HorseChannel::rearPivotRz]);
    pitch_hi = std::max(pitch_hi, frames[i].controls[HorseChannel::rearPivotRz]);
  }
  info.pivot_ty_peak_to_peak_cm = hi - lo;
  info.pitch_min_deg = pitch_lo;
  info.pitch_max_deg = pitch_hi;
  if (info.strides > 0 && hi - lo > 1e-6) {
    // Rises through the middle, with a hysteresis of a quarter of the range so noise does not count.
    const double mid = 0.5 * (lo + hi), band = 0.25 * (hi - lo);
    int rises = 0;
    bool low = frames[s0].controls[HorseChannel::rearPivotTy] < mid;
    for (int i = s0; i < s1; ++i) {
      const double y = frames[i].controls[HorseChannel::rearPivotTy];
      if (low && y > mid + 0.5 * band) {
        ++rises;
        low = false;
      } else if (!low && y < mid - 0.5 * band) {
        low = true;
      }
    }
    info.pivot_ty_cycles_per_stride = double(rises) / info.strides;
  }

  // Per frame: down hooves that move in the world, and the largest channel step.
  const double frame_dt = 1.0 / o.fps;
  const int frame_count = static_cast<int>(std::floor((info.end_s - info.start_s) * o.fps));
  for (int k = 0; k < frame_count; ++k) {
    const double t = info.start_s + k * frame_dt;
    const HorseFrame a = clip.sample(t), b = clip.sample(t + frame_dt);
    for (int h = 0; h < 4; ++h) {
      if (a.controls[kTy[h]] > o.ground_cm || b.controls[kTy[h]] > o.ground_cm) continue;
      const double dx = (b.travel_cm + b.controls[kTx[h]]) - (a.travel_cm + a.controls[kTx[h]]);
      const double dz = b.controls[kTz[h]] - a.controls[kTz[h]];
      const double mm = 10.0 * std::hypot(dx, dz);
      if (mm > info.hooves[h].max_slide_mm) {
        info.hooves[h].max_slide_mm = mm;
        info.hooves[h].max_slide_at_s = t;
      }
    }
  }
  for (int i = 1; i < n; ++i)
    for (std::size_t c = 0; c < kHorseChannelCount; ++c) {
      const double step = std::abs(frames[i].controls.value[c] - frames[i - 1].controls.value[c]) * o.sample_hz;
      if (step > info.max_channel_step) {
        info.max_channel_step = step;
        info.max_step_channel = std::string(kHorseChannelNames[c]);
        info.max_step_at_s = time(i);
      }
    }
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi2 = info.hooves[h];
    if (hi2.max_slide_mm > o.slide_limit_mm)
      info.problems.push_back(std::string(kHoofNames[h]) + " slides " + fmt("%.1f", hi2.max_slide_mm) +
                              " mm in one frame while down (at " + fmt("%.2f", hi2.max_slide_at_s) + " s)");
    if (hi2.lowest_cm < -0.01)
      info.problems.push_back(std::string(kHoofNames[h]) + " sinks " + fmt("%.1f", -hi2.lowest_cm) +
                              " cm below the ground");
  }
  return info;
}

std::optional<GaitReference> gaitReference(const std::string& gait) {
  // Every number from ../shared/gait-reference.md; ≈ ranges are its engineering estimates.
  GaitReference r;
  r.gait = gait;
  if (gait == "walk") {
    r.touchdown_phase = {0.25, 0.75, 0.0, 0.5};
    r.stride_hz = Range{1.0 / 1.1, 1.0};          // stride ≈ 1.0–1.1 s
    r.stride_length_cm = Range{160, 190};         // ≈ 1.6–1.9 m
    r.speed_cm_s = Range{180, 190};               // 1.8–1.9 m/s
    r.duty_fore = r.duty_hind = Range{0.60, 0.70};
    r.suspensions_per_stride = 0;
    r.pitch_range_deg = Range{0, 20};             // head, neck, trunk within ≈ 20° (Dunbar 2008)
    return r;
  }
  if (gait == "trot") {
    r.touchdown_phase = {0.5, 0.0, 0.0, 0.5};
    r.stride_hz = Range{1.0 / 0.808, 1.0 / 0.780};  // 794 ± 14 ms (Holmström)
    r.stride_length_cm = Range{260, 300};
    r.speed_cm_s = Range{350, 370};               // 3.6 ± 0.1 m/s (Gómez Álvarez 2009)
    r.duty_fore = r.duty_hind = Range{0.35, 0.45};
    r.suspensions_per_stride = 2;
    r.suspension_ms = Range{40, 90};
    r.pivot_ty_peak_to_peak_cm = Range{5, 7};     // withers ≈ 7 cm (Buchner 2000)
    r.pivot_cycles_per_stride = 2;
    r.pitch_range_deg = Range{2, 4};
    return r;
  }
  if (gait == "canter") {
    r.touchdown_phase = {0.275, 0.525, 0.0, 0.275};
    r.stride_hz = Range{1.0 / 0.65, 1.0 / 0.55};  // stride ≈ 0.55–0.65 s
    r.stride_length_cm = Range{300, 400};
    r.speed_cm_s = Range{500, 700};
    r.suspensions_per_stride = 1;
    r.pivot_cycles_per_stride = 1;                // Viry 2013
    r.pitch_range_deg = Range{5, 10};
    return r;
  }
  if (gait == "gallop") {
    r.touchdown_phase = {0.50, 0.60, 0.0, 0.10};
    r.stride_hz = Range{2.0, 2.4};                // Witte 2006, 9 -> 17 m/s
    r.stride_length_cm = Range{450, 710};
    r.speed_cm_s = Range{900, 1700};
    r.duty_fore = Range{0.18, 0.26};
    r.duty_hind = Range{0.094 * 2.4, 0.143 * 2.0};  // hind stance 143 -> 94 ms at those strides
    r.suspensions_per_stride = 1;
    r.pivot_cycles_per_stride = 1;
    r.pitch_range_deg = Range{5, 10};
    return r;
  }
  return std::nullopt;
}

namespace {

std::string rangeText(const std::optional<Range>& r, const char* f, double value) {
  if (!r) return "(no reference)";
  char buf[96];
  std::snprintf(buf, sizeof buf, f, r->lo, r->hi);
  return std::string(buf) + (r->contains(value) ? "  ok" : "  OUTSIDE");
}

nlohmann::json rangeJson(const std::optional<Range>& r) {
  if (!r) return nullptr;
  return nlohmann::json::array({r->lo, r->hi});
}

}  // namespace

std::string formatClipInfo(const ClipInfo& c, const GaitReference* ref) {
  std::string s;
  char line[256];
  std::snprintf(line, sizeof line, "clip %s: %.2f s, measured %.2f–%.2f s at 1 kHz, %d strides%s\n", c.name.c_str(),
                c.duration_s, c.start_s, c.end_s, c.strides,
                ref ? (" (reference: " + ref->gait + ", ../shared/gait-reference.md)").c_str() : " (no gait reference)");
  s += line;
  s += "hoof     touchdown  duty   peak cm  lowest cm  slide mm/frame   reference touchdown, duty\n";
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi = c.hooves[h];
    std::string r = "-";
    if (ref) {
      const auto& duty = h < 2 ? ref->duty_fore : ref->duty_hind;
      r = fmt("%.2f", ref->touchdown_phase[h]) + ", " + rangeText(duty, "%.2f–%.2f", hi.duty_factor);
    }
    std::snprintf(line, sizeof line, "%-8s %9.3f  %5.3f  %7.1f  %9.2f  %14.1f   %s\n", kHoofNames[h], hi.touchdown_phase,
                  hi.duty_factor, hi.peak_height_cm, hi.lowest_cm, hi.max_slide_mm, r.c_str());
    s += line;
  }
  std::string order;
  for (int h : c.footfall_order) order += std::string(order.empty() ? "" : " ") + kHoofNames[h];
  s += "footfall order: " + (order.empty() ? std::string("(no full stride)") : order) + "\n";
  const auto row = [&](const char* label, const char* vf, double v, const std::optional<Range>& r, const char* rf) {
    std::snprintf(line, sizeof line, "%-28s ", label);
    s += line + fmt(vf, v) + "   reference " + (ref ? rangeText(r, rf, v) : std::string("-")) + "\n";
  };
  row("stride frequency (Hz)", "%.3f", c.stride_hz, ref ? ref->stride_hz : std::nullopt, "%.2f–%.2f");
  row("stride length (cm)", "%.1f", c.stride_length_cm, ref ? ref->stride_length_cm : std::nullopt, "%.0f–%.0f");
  row("speed (cm/s)", "%.1f", c.speed_cm_s, ref ? ref->speed_cm_s : std::nullopt, "%.0f–%.0f");
  std::snprintf(line, sizeof line, "%-28s %.2f   reference %s\n", "suspensions per stride", c.suspensions_per_stride,
                ref ? std::to_string(ref->suspensions_per_stride).c_str() : "-");
  s += line;
  row("suspension length (ms)", "%.1f", c.suspension_ms, ref ? ref->suspension_ms : std::nullopt, "%.0f–%.0f");
  row("rear pivot ty p-p (cm)", "%.2f", c.pivot_ty_peak_to_peak_cm, ref ? ref->pivot_ty_peak_to_peak_cm : std::nullopt,
      "%.0f–%.0f");
  std::snprintf(line, sizeof line, "%-28s %.2f   reference %s\n", "rear pivot cycles/stride", c.pivot_ty_cycles_per_stride,
                ref && ref->pivot_cycles_per_stride ? std::to_string(ref->pivot_cycles_per_stride).c_str() : "-");
  s += line;
  row("pitch range (deg)", "%.2f", c.pitch_max_deg - c.pitch_min_deg, ref ? ref->pitch_range_deg : std::nullopt,
      "%.0f–%.0f");
  std::snprintf(line, sizeof line, "%-28s %.2f..%.2f\n", "pitch rearPivot.rz (deg)", c.pitch_min_deg, c.pitch_max_deg);
  s += line;
  std::snprintf(line, sizeof line, "%-28s %.0f /s (%s at %.2f s)\n", "fastest channel change", c.max_channel_step,
                c.max_step_channel.c_str(), c.max_step_at_s);
  s += line;
  if (c.problems.empty()) s += "no hoof slides or sinks\n";
  for (const std::string& p : c.problems) s += "problem: " + p + "\n";
  return s;
}

nlohmann::json clipInfoJson(const ClipInfo& c, const GaitReference* ref) {
  nlohmann::json j;
  j["name"] = c.name;
  j["duration_s"] = c.duration_s;
  j["measured_s"] = {c.start_s, c.end_s};
  j["strides"] = c.strides;
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi = c.hooves[h];
    nlohmann::json hj = {{"touchdown_phase", hi.touchdown_phase}, {"duty_factor", hi.duty_factor},
                         {"peak_height_cm", hi.peak_height_cm}, {"lowest_cm", hi.lowest_cm},
                         {"max_slide_mm_per_frame", hi.max_slide_mm}, {"touchdowns", hi.touchdowns}};
    if (ref) {
      hj["reference_touchdown_phase"] = ref->touchdown_phase[h];
      hj["reference_duty_factor"] = rangeJson(h < 2 ? ref->duty_fore : ref->duty_hind);
    }
    j["hooves"][kHoofNames[h]] = hj;
  }
  j["footfall_order"] = nlohmann::json::array();
  for (int h : c.footfall_order) j["footfall_order"].push_back(kHoofNames[h]);
  j["stride_hz"] = c.stride_hz;
  j["stride_length_cm"] = c.stride_length_cm;
  j["speed_cm_s"] = c.speed_cm_s;
  j["suspensions_per_stride"] = c.suspensions_per_stride;
  j["suspension_ms"] = c.suspension_ms;
  j["rear_pivot_ty_peak_to_peak_cm"] = c.pivot_ty_peak_to_peak_cm;
  j["rear_pivot_cycles_per_stride"] = c.pivot_ty_cycles_per_stride;
  j["pitch_deg"] = {c.pitch_min_deg, c.pitch_max_deg};
  j["fastest_channel"] = {{"channel", c.max_step_channel}, {"per_s", c.max_channel_step}, {"at_s", c.max_step_at_s}};
  j["problems"] = c.problems;
  if (ref) {
    j["reference"] = {{"gait", ref->gait},
                      {"stride_hz", rangeJson(ref->stride_hz)},
                      {"stride_length_cm", rangeJson(ref->stride_length_cm)},
                      {"speed_cm_s", rangeJson(ref->speed_cm_s)},
                      {"suspensions_per_stride", ref->suspensions_per_stride},
                      {"suspension_ms", rangeJson(ref->suspension_ms)},
                      {"rear_pivot_ty_peak_to_peak_cm", rangeJson(ref->pivot_ty_peak_to_peak_cm)},
                      {"rear_pivot_cycles_per_stride", ref->pivot_cycles_per_stride},
                      {"pitch_range_deg", rangeJson(ref->pitch_range_deg)},
                      {"source", "../shared/gait-reference.md"}};
  }
  return j;
}

}  // namespace stirrup::rig
