#include "rig/motion/clip_info.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "rig/error.h"

#include <glm/vec3.hpp>

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
// A stance whose place moves at least this far (cm) is a sliding stance (float noise is far less).
constexpr double kSlidingStanceCm = 1.0;

// A hoof's place in the world (cm): its channels about its rest place in the travel frame, carried by
// the travel frame's heading, ground height and pitch as rig::travelMatrix does (in double). On a
// straight clip over flat ground this is (travel + rest.x + tx, ty, rest.z + tz).
glm::dvec3 hoofWorld(const HorseFrame& f, int h, const std::array<glm::dvec2, 4>& rest) {
  const double x = rest[h].x + f.controls[kTx[h]], y = f.controls[kTy[h]] + f.hoof_ground_cm[h],
               z = rest[h].y + f.controls[kTz[h]];
  const double p = f.ground_pitch_deg * std::numbers::pi / 180.0, a = f.heading_deg * std::numbers::pi / 180.0;
  const double px = x * std::cos(p) - y * std::sin(p), py = x * std::sin(p) + y * std::cos(p);
  return {f.travel_cm + px * std::cos(a) - z * std::sin(a), f.ground_y_cm + py, f.travel_z_cm + px * std::sin(a) + z * std::cos(a)};
}

}  // namespace

HorseFrame mirrorLeftRight(const HorseFrame& f) {
  using C = HorseChannel;
  HorseFrame m = f;
  for (const auto& [l, r] : {std::pair{0, 1}, std::pair{2, 3}}) {
    m.controls[kTx[l]] = f.controls[kTx[r]], m.controls[kTx[r]] = f.controls[kTx[l]];
    m.controls[kTy[l]] = f.controls[kTy[r]], m.controls[kTy[r]] = f.controls[kTy[l]];
    m.controls[kTz[l]] = -f.controls[kTz[r]], m.controls[kTz[r]] = -f.controls[kTz[l]];
    m.hoof_ground_cm[l] = f.hoof_ground_cm[r], m.hoof_ground_cm[r] = f.hoof_ground_cm[l];
  }
  for (C c : {C::rearPivotTz, C::rearPivotRx, C::rearPivotRy, C::backMidRx, C::backMidRy}) m.controls[c] = -f.controls[c];
  m.travel_z_cm = -f.travel_z_cm;
  m.heading_deg = -f.heading_deg;
  return m;
}

namespace {

// The clip sampled at o.sample_hz over the window, and which hooves are down at each sample.
struct ClipSamples {
  double start_s = 0.0, dt = 0.0;
  int n = 0;
  std::vector<HorseFrame> frames;
  std::vector<std::array<bool, 4>> down;
  double time(int i) const { return start_s + i * dt; }
  bool noneDown(int i) const { return !down[i][0] && !down[i][1] && !down[i][2] && !down[i][3]; }
};

ClipSamples sampleClip(const Clip& clip, const ClipInfo& info, const ClipInfoOptions& o) {
  ClipSamples m;
  m.start_s = info.start_s;
  m.dt = 1.0 / o.sample_hz;
  m.n = static_cast<int>(std::floor((info.end_s - info.start_s) * o.sample_hz)) + 1;
  m.frames.resize(m.n);
  m.down.resize(m.n);
  for (int i = 0; i < m.n; ++i) {
    m.frames[i] = clip.sample(info.start_s + i * m.dt);
    if (o.mirror) m.frames[i] = mirrorLeftRight(m.frames[i]);
    for (int h = 0; h < 4; ++h) m.down[i][h] = m.frames[i].controls[kTy[h]] <= o.ground_cm;
  }
  return m;
}

// Touchdowns per hoof (an up sample followed by a down sample), their counts and each hoof's range.
std::array<std::vector<double>, 4> measureTouchdowns(const ClipSamples& m, ClipInfo& info) {
  std::array<std::vector<double>, 4> touchdowns;
  for (int i = 1; i < m.n; ++i)
    for (int h = 0; h < 4; ++h)
      if (m.down[i][h] && !m.down[i - 1][h]) touchdowns[h].push_back(m.time(i));
  for (int h = 0; h < 4; ++h) {
    HoofInfo& hi = info.hooves[h];
    hi.touchdowns = static_cast<int>(touchdowns[h].size());
    hi.peak_height_cm = -1e300;
    hi.lowest_cm = 1e300;
    for (const HorseFrame& f : m.frames) {
      hi.peak_height_cm = std::max(hi.peak_height_cm, f.controls[kTy[h]]);
      hi.lowest_cm = std::min(hi.lowest_cm, f.controls[kTy[h]]);
    }
  }
  return touchdowns;
}

// Strides: from one left-hind touchdown to the next: their rate, each hoof's phase and duty factor, the
// footfall order and the suspensions. Returns the samples [first, last] the whole strides span (the
// whole window without a stride).
std::pair<int, int> measureStrides(const ClipSamples& m, const std::array<std::vector<double>, 4>& touchdowns, ClipInfo& info) {
  const int n = m.n;
  const double dt = m.dt;
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
      for (int i = i0; i < i1; ++i) d += m.down[i][h] && m.down[i + 1][h];
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
      const bool none = m.noneDown(i);
      const bool none_before = i > i0 && m.noneDown(i - 1);
      airborne += none;
      runs += none && !none_before;
    }
    info.suspensions_per_stride = double(runs) / info.strides;
    info.suspension_ms = runs ? 1000.0 * airborne * dt / runs : 0.0;
  }
  return {info.strides > 0 ? i0 : 0, info.strides > 0 ? i1 : n - 1};
}

// Speed and stride length along the ground track over samples [s0, s1]; the rear pivot's bounce and pitch.
void measureTravelAndPivot(const ClipSamples& m, int s0, int s1, ClipInfo& info) {
  const double dt = m.dt;
  // Distance along the ground track (a path turns): the sum of the travel frame's steps.
  double track = 0.0;
  for (int i = s0; i < s1; ++i)
    track += std::hypot(m.frames[i + 1].travel_cm - m.frames[i].travel_cm, m.frames[i + 1].travel_z_cm - m.frames[i].travel_z_cm);
  info.speed_cm_s = track / std::max(dt, (s1 - s0) * dt);
  if (info.stride_hz > 0.0) info.stride_length_cm = info.speed_cm_s / info.stride_hz;

  // Rear pivot: height peak to peak, and how many times per stride it rises through its middle.
  double lo = 1e300, hi = -1e300, pitch_lo = 1e300, pitch_hi = -1e300;
  for (int i = s0; i <= s1; ++i) {
    const double y = m.frames[i].controls[HorseChannel::rearPivotTy];
    lo = std::min(lo, y);
    hi = std::max(hi, y);
    pitch_lo = std::min(pitch_lo, m.frames[i].controls[HorseChannel::rearPivotRz]);
    pitch_hi = std::max(pitch_hi, m.frames[i].controls[HorseChannel::rearPivotRz]);
  }
  info.pivot_ty_peak_to_peak_cm = hi - lo;
  info.pitch_min_deg = pitch_lo;
  info.pitch_max_deg = pitch_hi;
  if (info.strides > 0 && hi - lo > 1e-6) {
    // Rises through the middle, with a hysteresis of a quarter of the range so noise does not count.
    const double mid = 0.5 * (lo + hi), band = 0.25 * (hi - lo);
    int rises = 0;
    bool low = m.frames[s0].controls[HorseChannel::rearPivotTy] < mid;
    for (int i = s0; i < s1; ++i) {
      const double y = m.frames[i].controls[HorseChannel::rearPivotTy];
      if (low && y > mid + 0.5 * band) {
        ++rises;
        low = false;
      } else if (!low && y < mid - 0.5 * band) {
        low = true;
      }
    }
    info.pivot_ty_cycles_per_stride = double(rises) / info.strides;
  }

}

// Over the whole window: the trunk's extreme pitches, the longest stay in the held band, croup-ups.
void measurePitchHeld(const ClipSamples& m, const ClipInfoOptions& o, ClipInfo& info) {
  info.pitch_lowest_deg = 1e300;
  info.pitch_highest_deg = -1e300;
  int held = 0, best_held = 0;
  bool in_dip = false;
  for (int i = 0; i < m.n; ++i) {
    const double rz = m.frames[i].controls[HorseChannel::rearPivotRz];
    info.pitch_lowest_deg = std::min(info.pitch_lowest_deg, rz);
    info.pitch_highest_deg = std::max(info.pitch_highest_deg, rz);
    held = rz >= o.held_pitch_lo_deg && rz <= o.held_pitch_hi_deg ? held + 1 : 0;
    best_held = std::max(best_held, held);
    if (!in_dip && rz < o.croup_up_deg) {
      in_dip = true;
      ++info.croup_ups;
    } else if (in_dip && rz > 0.5 * o.croup_up_deg) {
      in_dip = false;
    }
  }
  info.pitch_held_s = best_held > 1 ? (best_held - 1) * m.dt : 0.0;
}

// Airborne phases: runs with no hoof down that begin after some hoof was down and end with a touchdown
// inside the window; the pitch as the last hoof leaves for the longest one.
void measureAirborne(const ClipSamples& m, ClipInfo& info) {
  bool was_down = false;
  int run = -1, longest = 0;
  for (int i = 0; i < m.n; ++i) {
    const bool none = m.noneDown(i);
    if (none) {
      if (run < 0 && was_down) run = i;
      continue;
    }
    if (run >= 0) {
      ++info.airborne_phases;
      if (i - run > longest) {
        longest = i - run;
        info.longest_airborne_from_s = m.time(run);
        info.liftoff_pitch_deg = m.frames[run - 1].controls[HorseChannel::rearPivotRz];
      }
      run = -1;
    }
    was_down = true;
  }
  info.longest_airborne_ms = 1000.0 * longest * m.dt;
}

// Stance slides: per hoof, the stance whose place moves furthest in the world from where it landed; the
// fore touchdowns during the worst.
void measureStanceSlides(const ClipSamples& m, const std::array<std::vector<double>, 4>& touchdowns,
                         const ClipInfoOptions& o, ClipInfo& info) {
  const int n = m.n;
  for (int h = 0; h < 4; ++h) {
    HoofInfo& hi = info.hooves[h];
    int run = -1;
    double x0 = 0.0, z0 = 0.0, run_max = 0.0;
    for (int i = 0; i <= n; ++i) {
      const bool d = i < n && m.down[i][h];
      if (d) {
        const glm::dvec3 w = hoofWorld(m.frames[i], h, o.hoof_rest);
        const double x = w.x, z = w.z;
        if (run < 0) run = i, x0 = x, z0 = z, run_max = 0.0;
        run_max = std::max(run_max, std::hypot(x - x0, z - z0));
      } else if (run >= 0) {
        if (run_max > hi.stance_slide_cm) {
          hi.stance_slide_cm = run_max;
          hi.stance_slide_from_s = m.time(run);
          hi.stance_slide_to_s = m.time(i - 1);
        }
        run = -1;
      }
    }
    if (hi.stance_slide_cm >= kSlidingStanceCm && (info.slide_hoof < 0 || hi.stance_slide_cm > info.hooves[info.slide_hoof].stance_slide_cm))
      info.slide_hoof = h;
  }
  if (info.slide_hoof >= 0) {
    const HoofInfo& s = info.hooves[info.slide_hoof];
    for (int h : {0, 1})
      for (double t : touchdowns[h]) info.fore_touchdowns_during_slide += t > s.stance_slide_from_s && t < s.stance_slide_to_s;
  }
}

// Per frame (at o.fps): down hooves that move in the world.
void measureFrameSlides(const Clip& clip, const ClipInfoOptions& o, ClipInfo& info) {
  const double frame_dt = 1.0 / o.fps;
  const int frame_count = static_cast<int>(std::floor((info.end_s - info.start_s) * o.fps));
  for (int k = 0; k < frame_count; ++k) {
    const double t = info.start_s + k * frame_dt;
    HorseFrame a = clip.sample(t), b = clip.sample(t + frame_dt);
    if (o.mirror) a = mirrorLeftRight(a), b = mirrorLeftRight(b);
    for (int h = 0; h < 4; ++h) {
      if (a.controls[kTy[h]] > o.ground_cm || b.controls[kTy[h]] > o.ground_cm) continue;
      const glm::dvec3 wa = hoofWorld(a, h, o.hoof_rest), wb = hoofWorld(b, h, o.hoof_rest);
      const double dx = wb.x - wa.x, dz = wb.z - wa.z;
      const double mm = 10.0 * std::hypot(dx, dz);
      HoofInfo& hi = info.hooves[h];
      if (mm > hi.max_slide_mm) {
        hi.max_slide_mm = mm;
        hi.max_slide_at_s = t;
      }
      const bool in_slide = hi.stance_slide_cm >= kSlidingStanceCm && t < hi.stance_slide_to_s && t + frame_dt > hi.stance_slide_from_s;
      if (!in_slide) hi.max_slide_outside_stance_mm = std::max(hi.max_slide_outside_stance_mm, mm);
    }
  }
}

// The largest step of any channel between samples, per second.
void measureChannelSteps(const ClipSamples& m, const ClipInfoOptions& o, ClipInfo& info) {
  for (int i = 1; i < m.n; ++i)
    for (std::size_t c = 0; c < kHorseChannelCount; ++c) {
      const double step = std::abs(m.frames[i].controls.value[c] - m.frames[i - 1].controls.value[c]) * o.sample_hz;
      if (step > info.max_channel_step) {
        info.max_channel_step = step;
        info.max_step_channel = std::string(kHorseChannelNames[c]);
        info.max_step_at_s = m.time(i);
      }
    }
}

// Problems worth a line: a hoof sliding in one frame past the limit, or below the ground.
void listProblems(const ClipInfoOptions& o, ClipInfo& info) {
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi2 = info.hooves[h];
    if (hi2.max_slide_mm > o.slide_limit_mm)
      info.problems.push_back(std::string(kHoofNames[h]) + " slides " + printfNumber("%.1f", hi2.max_slide_mm) +
                              " mm in one frame while down (at " + printfNumber("%.2f", hi2.max_slide_at_s) + " s)");
    if (hi2.lowest_cm < -0.01)
      info.problems.push_back(std::string(kHoofNames[h]) + " sinks " + printfNumber("%.1f", -hi2.lowest_cm) +
                              " cm below the ground");
  }
}

}  // namespace

ClipInfo measureClip(const Clip& clip, const ClipInfoOptions& o) {
  ClipInfo info;
  info.name = clip.name();
  info.duration_s = clip.duration();
  info.fps = o.fps;
  info.slide_limit_mm = o.slide_limit_mm;
  info.sample_hz = o.sample_hz;
  info.start_s = o.start_s;
  info.end_s = o.end_s < 0.0 ? clip.duration() : o.end_s;
  if (!(info.end_s > info.start_s) || !(o.sample_hz > 0.0) || !(o.fps > 0.0))
    throw InputError("clip info: expected end > start and positive rates");
  const ClipSamples m = sampleClip(clip, info, o);
  const std::array<std::vector<double>, 4> touchdowns = measureTouchdowns(m, info);
  const auto [s0, s1] = measureStrides(m, touchdowns, info);
  measureTravelAndPivot(m, s0, s1, info);
  measurePitchHeld(m, o, info);
  measureAirborne(m, info);
  measureStanceSlides(m, touchdowns, o, info);
  measureFrameSlides(clip, o, info);
  measureChannelSteps(m, o, info);
  listProblems(o, info);
  return info;
}

double phaseDistance(double a, double b) {
  const double d = std::abs(a - b) - std::floor(std::abs(a - b));
  return std::min(d, 1.0 - d);
}

double phaseDistance(double a, const Range& r) {
  const double lo = r.lo - std::floor(r.lo), width = r.hi - r.lo;
  const double from_lo = a - lo - std::floor(a - lo);  // 0..1 past lo, going forward
  if (from_lo <= width + 1e-12) return 0.0;
  return std::min(from_lo - width, 1.0 - from_lo);
}

std::array<double, 2> gallopOneSuspensionForePhases(double stride_hz) {
  // gait-reference (Witte 2006): hind stance 143 ms at 2.0 Hz (9 m/s) -> 94 ms at 2.4 Hz (17 m/s).
  const double u = std::clamp((stride_hz - 2.0) / 0.4, 0.0, 1.0);
  const double hind_duty = (0.143 - 0.049 * u) * stride_hz;
  const double lf = 0.10 + hind_duty;  // the right hind (table .10) lifts off: the latest one-suspension touchdown
  return {lf, lf + 0.10};              // the table's fore pair lag
}

std::optional<GaitReference> gaitReference(const std::string& gait) {
  // Every number from docs/gait-reference.md; ≈ ranges are its engineering estimates.
  GaitReference r;
  r.gait = gait;
  const auto phases = [&](double lf, double rf, double lb, double rb) {
    r.touchdown_phase = {Range{lf, lf}, Range{rf, rf}, Range{lb, lb}, Range{rb, rb}};
  };
  if (gait == "walk") {
    phases(0.25, 0.75, 0.0, 0.5);
    r.stride_hz = Range{1.0 / 1.1, 1.0};          // stride ≈ 1.0–1.1 s
    r.stride_length_cm = Range{160, 190};         // ≈ 1.6–1.9 m
    r.speed_cm_s = Range{180, 190};               // 1.8–1.9 m/s
    r.duty_fore = r.duty_hind = Range{0.60, 0.70};
    r.suspensions_per_stride = 0;
    r.pitch_range_deg = Range{0, 20};             // head, neck, trunk within ≈ 20° (Dunbar 2008)
    return r;
  }
  if (gait == "trot") {
    phases(0.5, 0.0, 0.0, 0.5);                   // the hind of a pair lands ≈ 30 ms first: inside ±.05
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
    r.touchdown_phase = {Range{0.25, 0.30}, Range{0.50, 0.55}, Range{0.0, 0.0}, Range{0.25, 0.30}};
    r.stride_hz = Range{1.0 / 0.65, 1.0 / 0.55};  // stride ≈ 0.55–0.65 s
    r.stride_length_cm = Range{300, 400};
    r.speed_cm_s = Range{500, 700};
    r.suspensions_per_stride = 1;
    r.pivot_cycles_per_stride = 1;                // Viry 2013
    r.pitch_range_deg = Range{5, 10};
    return r;
  }
  if (gait == "gallop") {
    phases(0.50, 0.60, 0.0, 0.10);                // Muybridge via Rotenberg
    r.one_suspension_fore_phases = true;          // see gallopOneSuspensionForePhases
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
  r.periodic = false;
  if (gait == "rear") {
    r.rear_pitch_deg = Range{40, 70};             // ≈ 40–70° trunk pitch held 0.5–2 s (Kuhnel 5.4)
    r.rear_held_s = Range{0.5, 2.0};
    return r;
  }
  if (gait == "buck") {
    r.croup_pitch_deg = Range{-35, -20};          // croup-up pitch ≈ −20 to −35° (Kuhnel 5.6)
    r.all_four_leave_ground = true;               // "all four legs leave the ground"
    return r;
  }
  if (gait == "jump") {
    r.takeoff_pitch_deg = Range{21.4 - 2.5, 21.4 + 2.5};  // Colborne 1995, at the leading hind's lift-off
    return r;
  }
  if (gait == "stop") {
    r.slide_cm = Range{0, 1000};                  // slides up to ≈ 10 m (Kuhnel 5.5)
    r.fore_steps_during_slide = 2;                // "the forelegs keep stepping"
    return r;
  }
  return std::nullopt;
}

namespace {

constexpr double kAtLeast = std::numeric_limits<double>::infinity();

Verdict verdict(std::string key, double value, Range range, bool ok, std::string note = {}) {
  return Verdict{std::move(key), value, range, ok, std::move(note)};
}

Verdict inRange(std::string key, double value, Range range, double slack = 0.0, std::string note = {}) {
  const bool ok = Range{range.lo - slack, range.hi + slack}.contains(value);
  return verdict(std::move(key), value, range, ok, std::move(note));
}

}  // namespace

std::vector<Verdict> clipVerdicts(const ClipInfo& c, const GaitReference& ref) {
  std::vector<Verdict> out;
  if (ref.periodic) {
    if (c.strides > 0) {
      for (int h = 0; h < 4; ++h) {
        Range r = ref.touchdown_phase[h];
        std::string note;
        if (ref.one_suspension_fore_phases && h < 2) {
          const double table = r.lo, derived = gallopOneSuspensionForePhases(c.stride_hz)[h];
          const double away = phaseDistance(c.hooves[h].touchdown_phase, table);
          r = Range{derived, derived};
          note = "one-suspension phase (right hind .10 + Witte's hind stance at this stride; docs/horse-clips.md "
                 "\"Gallop phases\"); the table's " + printfNumber("%.2f", table) + " is " + printfNumber("%.2f", away) + " away: " +
                 (away <= kTouchdownTolerance ? "ok" : "OUTSIDE");
        }
        const bool ok = phaseDistance(c.hooves[h].touchdown_phase, r) <= kTouchdownTolerance + 1e-9;
        out.push_back(verdict(std::string(kHoofNames[h]) + ".touchdown_phase", c.hooves[h].touchdown_phase, r, ok, note));
      }
        // Within the 1 kHz measurement's resolution of the range counts as inside: a stance is measured up
      // to one sample short at each end (duty ± two samples per stride), a stride up to one sample off
      // over all the strides.
      const double duty_slack = 2.0 * c.stride_hz / c.sample_hz;
      for (int h = 0; h < 4; ++h)
        if (const auto& duty = h < 2 ? ref.duty_fore : ref.duty_hind)
          out.push_back(inRange(std::string(kHoofNames[h]) + ".duty_factor", c.hooves[h].duty_factor, *duty, duty_slack));
    }
    const double hz_slack = c.strides > 0 ? c.stride_hz * c.stride_hz / (c.sample_hz * c.strides) : 0.0;
    if (ref.stride_hz) out.push_back(inRange("stride_hz", c.stride_hz, *ref.stride_hz, hz_slack));
    if (ref.stride_length_cm) out.push_back(inRange("stride_length_cm", c.stride_length_cm, *ref.stride_length_cm));
    if (ref.speed_cm_s) out.push_back(inRange("speed_cm_s", c.speed_cm_s, *ref.speed_cm_s));
    const double n = ref.suspensions_per_stride;
    out.push_back(verdict("suspensions_per_stride", c.suspensions_per_stride, Range{n, n},
                          c.strides > 0 && std::abs(c.suspensions_per_stride - n) <= kPerStrideTolerance));
    if (ref.suspension_ms) out.push_back(inRange("suspension_ms", c.suspension_ms, *ref.suspension_ms));
    if (ref.pivot_ty_peak_to_peak_cm)
      out.push_back(inRange("rear_pivot_ty_peak_to_peak_cm", c.pivot_ty_peak_to_peak_cm, *ref.pivot_ty_peak_to_peak_cm));
    if (ref.pivot_cycles_per_stride > 0) {
      const double k = ref.pivot_cycles_per_stride;
      out.push_back(verdict("rear_pivot_cycles_per_stride", c.pivot_ty_cycles_per_stride, Range{k, k},
                            c.strides > 0 && std::abs(c.pivot_ty_cycles_per_stride - k) <= kPerStrideTolerance));
    }
    if (ref.pitch_range_deg) out.push_back(inRange("pitch_range_deg", c.pitch_max_deg - c.pitch_min_deg, *ref.pitch_range_deg));
    return out;
  }
  if (ref.rear_pitch_deg) out.push_back(inRange("rear.peak_pitch_deg", c.pitch_highest_deg, *ref.rear_pitch_deg));
  if (ref.rear_held_s) out.push_back(inRange("rear.held_s", c.pitch_held_s, *ref.rear_held_s));
  if (ref.croup_pitch_deg) out.push_back(inRange("buck.croup_pitch_deg", c.pitch_lowest_deg, *ref.croup_pitch_deg));
  if (ref.all_four_leave_ground) {
    // Every buck (every croup-up) has its airborne phase: at least one in all, and no fewer than bucks.
    const double need = std::max(1, c.croup_ups);
    out.push_back(verdict("buck.airborne_phases", c.airborne_phases, Range{need, kAtLeast}, c.airborne_phases >= need,
                          std::to_string(c.croup_ups) + " croup-ups"));
  }
  if (ref.takeoff_pitch_deg) {
    if (c.airborne_phases > 0)
      out.push_back(inRange("jump.takeoff_pitch_deg", c.liftoff_pitch_deg, *ref.takeoff_pitch_deg, 0.0,
                            "at the last lift-off before the longest airborne phase"));
    else
      out.push_back(verdict("jump.takeoff_pitch_deg", 0.0, *ref.takeoff_pitch_deg, false, "no airborne phase: no take-off"));
  }
  if (ref.slide_cm) {
    const double slide = c.slide_hoof >= 0 ? c.hooves[c.slide_hoof].stance_slide_cm : 0.0;
    out.push_back(inRange("stop.slide_cm", slide, *ref.slide_cm, 0.0,
                          c.slide_hoof >= 0 ? std::string(kHoofNames[c.slide_hoof]) : std::string("no hoof slides")));
  }
  if (ref.fore_steps_during_slide > 0) {
    const double need = ref.fore_steps_during_slide;
    out.push_back(verdict("stop.fore_steps_during_slide", c.fore_touchdowns_during_slide, Range{need, kAtLeast},
                          c.slide_hoof >= 0 && c.fore_touchdowns_during_slide >= need));
  }
  return out;
}

namespace {

const Verdict* findVerdict(const std::vector<Verdict>& v, const std::string& key) {
  for (const Verdict& x : v)
    if (x.key == key) return &x;
  return nullptr;
}

std::string rangeText(const Range& r, const char* f) {
  if (std::isinf(r.hi)) return "≥ " + printfNumber(f, r.lo);
  if (r.lo == r.hi) return printfNumber(f, r.lo);
  return printfNumber(f, r.lo) + (r.lo < 0.0 || r.hi < 0.0 ? ".." : "–") + printfNumber(f, r.hi);
}

std::string verdictText(const Verdict* v, const char* f) {
  if (!v) return "(no reference)";
  return rangeText(v->range, f) + (v->ok ? "  ok" : "  OUTSIDE");
}

nlohmann::json rangeJson(const Range& r) {
  return nlohmann::json::array({r.lo, std::isinf(r.hi) ? nlohmann::json(nullptr) : nlohmann::json(r.hi)});
}

// A hoof's per-frame slide problem that is the sliding stop's own slide (and nothing else slides).
bool expectedSlide(const ClipInfo& c, const GaitReference* ref, int h) {
  const HoofInfo& hi = c.hooves[h];
  return ref && ref->slide_cm && h >= 2 && hi.stance_slide_cm >= kSlidingStanceCm &&
         hi.max_slide_outside_stance_mm <= c.slide_limit_mm;
}

}  // namespace

std::string formatClipInfo(const ClipInfo& c, const GaitReference* ref) {
  const std::vector<Verdict> verdicts = ref ? clipVerdicts(c, *ref) : std::vector<Verdict>{};
  const auto find = [&](const std::string& key) { return findVerdict(verdicts, key); };
  std::string s;
  char line[512];
  std::snprintf(line, sizeof line, "clip %s: %.2f s, measured %.2f–%.2f s at 1 kHz, %d strides%s\n", c.name.c_str(),
                c.duration_s, c.start_s, c.end_s, c.strides,
                ref ? (" (reference: " + ref->gait + ", docs/gait-reference.md)").c_str() : " (no gait reference)");
  s += line;
  const bool gait = ref && ref->periodic;
  s += "hoof     touchdown  duty   peak cm  lowest cm  slide mm/frame  stance slide cm   reference touchdown (±" +
       printfNumber("%.2f", kTouchdownTolerance) + " stride), duty\n";
  bool starred = false;
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi = c.hooves[h];
    std::string r = "-";
    if (gait) {
      const Verdict* td = find(std::string(kHoofNames[h]) + ".touchdown_phase");
      const Verdict* duty = find(std::string(kHoofNames[h]) + ".duty_factor");
      r = td ? rangeText(td->range, "%.2f") + (td->note.empty() ? "" : "*") + (td->ok ? " ok" : " OUTSIDE") : "-";
      starred = starred || (td && !td->note.empty());
      r += ", " + verdictText(duty, "%.2f");
    }
    std::snprintf(line, sizeof line, "%-8s %9.3f  %5.3f  %7.1f  %9.2f  %14.1f  %15.1f   %s\n", kHoofNames[h],
                  hi.touchdown_phase, hi.duty_factor, hi.peak_height_cm, hi.lowest_cm, hi.max_slide_mm, hi.stance_slide_cm,
                  r.c_str());
    s += line;
  }
  if (starred) {
    const Verdict* lf = find("lfHoof.touchdown_phase");
    const Verdict* rf = find("rfHoof.touchdown_phase");
    s += "  * gallop fore pair compared with the one-suspension phases " + printfNumber("%.3f", lf->range.lo) + "/" +
         printfNumber("%.3f", rf->range.lo) + printfNumber(" at %.2f Hz", c.stride_hz) +
         " (right hind .10 + Witte's hind stance):\n"
         "    the table's .50/.60 with Witte's stance times give two suspensions where gait-reference counts one\n"
         "    (docs/horse-clips.md \"Gallop phases\"). Against the table's phases they are " +
         printfNumber("%.2f", phaseDistance(c.hooves[0].touchdown_phase, ref->touchdown_phase[0])) + "/" +
         printfNumber("%.2f", phaseDistance(c.hooves[1].touchdown_phase, ref->touchdown_phase[1])) + " away: " +
         (phaseDistance(c.hooves[0].touchdown_phase, ref->touchdown_phase[0]) <= kTouchdownTolerance &&
                  phaseDistance(c.hooves[1].touchdown_phase, ref->touchdown_phase[1]) <= kTouchdownTolerance
              ? "ok"
              : "OUTSIDE") +
         "\n";
  }
  std::string order;
  for (int h : c.footfall_order) order += std::string(order.empty() ? "" : " ") + kHoofNames[h];
  s += "footfall order: " + (order.empty() ? std::string("(no full stride)") : order) + "\n";
  const auto row = [&](const char* label, const char* vf, double v, const char* key, const char* rf) {
    std::snprintf(line, sizeof line, "%-28s ", label);
    s += line + printfNumber(vf, v) + "   reference " + (gait ? verdictText(find(key), rf) : std::string("-")) + "\n";
  };
  row("stride frequency (Hz)", "%.3f", c.stride_hz, "stride_hz", "%.2f");
  row("stride length (cm)", "%.1f", c.stride_length_cm, "stride_length_cm", "%.0f");
  row("speed (cm/s)", "%.1f", c.speed_cm_s, "speed_cm_s", "%.0f");
  row("suspensions per stride", "%.2f", c.suspensions_per_stride, "suspensions_per_stride", "%.0f");
  row("suspension length (ms)", "%.1f", c.suspension_ms, "suspension_ms", "%.0f");
  row("rear pivot ty p-p (cm)", "%.2f", c.pivot_ty_peak_to_peak_cm, "rear_pivot_ty_peak_to_peak_cm", "%.0f");
  row("rear pivot cycles/stride", "%.2f", c.pivot_ty_cycles_per_stride, "rear_pivot_cycles_per_stride", "%.0f");
  row("pitch range (deg)", "%.2f", c.pitch_max_deg - c.pitch_min_deg, "pitch_range_deg", "%.0f");
  std::snprintf(line, sizeof line, "%-28s %.2f..%.2f\n", "pitch rearPivot.rz (deg)", c.pitch_min_deg, c.pitch_max_deg);
  s += line;
  // The whole window, strides or not: what the scripted movements are judged by (not shown for gaits).
  if (!gait) {
    std::snprintf(line, sizeof line,
                  "whole clip: pitch %.2f..%.2f deg, held at 40–70 deg for %.2f s, %d croup-up%s (pitch below -10 deg)\n",
                  c.pitch_lowest_deg, c.pitch_highest_deg, c.pitch_held_s, c.croup_ups, c.croup_ups == 1 ? "" : "s");
    s += line;
    if (c.airborne_phases > 0)
      std::snprintf(line, sizeof line, "airborne phases: %d, longest %.0f ms from %.2f s, pitch %.2f deg as it began\n",
                    c.airborne_phases, c.longest_airborne_ms, c.longest_airborne_from_s, c.liftoff_pitch_deg);
    else
      std::snprintf(line, sizeof line, "airborne phases: none\n");
    s += line;
    if (c.slide_hoof >= 0) {
      const HoofInfo& hi = c.hooves[c.slide_hoof];
      std::snprintf(line, sizeof line, "largest slide while down: %s %.1f cm (%.2f–%.2f s), %d fore touchdowns meanwhile\n",
                    kHoofNames[c.slide_hoof], hi.stance_slide_cm, hi.stance_slide_from_s, hi.stance_slide_to_s,
                    c.fore_touchdowns_during_slide);
    } else {
      std::snprintf(line, sizeof line, "largest slide while down: none (no stance moves %.0f cm)\n", kSlidingStanceCm);
    }
    s += line;
  }
  if (ref && !ref->periodic) {
    const auto scripted = [&](const char* label, const char* vf, const char* key, const char* rf, const char* why) {
      const Verdict* v = find(key);
      if (!v) return;
      std::snprintf(line, sizeof line, "%-28s ", label);
      s += line + printfNumber(vf, v->value) + "   reference " + verdictText(v, rf) + "  (" + why +
           (v->note.empty() ? std::string() : "; " + v->note) + ")\n";
    };
    scripted("rear: peak pitch (deg)", "%.2f", "rear.peak_pitch_deg", "%.0f", "Kuhnel 5.4");
    scripted("rear: held at 40-70 deg (s)", "%.2f", "rear.held_s", "%.1f", "longest continuous stay in the band");
    scripted("buck: croup-up pitch (deg)", "%.2f", "buck.croup_pitch_deg", "%.0f", "Kuhnel 5.6");
    scripted("buck: all four hooves off", "%.0f", "buck.airborne_phases", "%.0f", "airborne phases, one per buck");
    scripted("jump: take-off pitch (deg)", "%.2f", "jump.takeoff_pitch_deg", "%.1f", "21.4 ± 2.5, Colborne 1995");
    scripted("stop: slide (cm)", "%.1f", "stop.slide_cm", "%.0f", "up to ≈ 10 m, Kuhnel 5.5");
    scripted("stop: fore steps in slide", "%.0f", "stop.fore_steps_during_slide", "%.0f", "the forelegs keep stepping");
  }
  std::snprintf(line, sizeof line, "%-28s %.0f /s (%s at %.2f s)\n", "fastest channel change", c.max_channel_step,
                c.max_step_channel.c_str(), c.max_step_at_s);
  s += line;
  if (c.problems.empty()) s += "no hoof slides or sinks\n";
  for (const std::string& p : c.problems) {
    bool expected = false;
    for (int h = 2; h < 4; ++h)
      expected = expected || (expectedSlide(c, ref, h) && p.rfind(std::string(kHoofNames[h]) + " slides", 0) == 0);
    s += (expected ? "slide (the sliding stop's, expected): " : "problem: ") + p + "\n";
  }
  if (ref) {
    std::string outside;
    for (const Verdict& v : verdicts)
      if (!v.ok) outside += (outside.empty() ? "" : ", ") + v.key;
    const std::string n = std::to_string(verdicts.size()) + (verdicts.size() == 1 ? " number" : " numbers");
    s += outside.empty() ? "verdict: all " + n + " inside the reference\n"
                         : "verdict: OUTSIDE the reference (of " + n + "): " + outside + "\n";
  }
  return s;
}

nlohmann::json clipInfoJson(const ClipInfo& c, const GaitReference* ref) {
  const std::vector<Verdict> verdicts = ref ? clipVerdicts(c, *ref) : std::vector<Verdict>{};
  nlohmann::json j;
  j["name"] = c.name;
  j["duration_s"] = c.duration_s;
  j["measured_s"] = {c.start_s, c.end_s};
  j["strides"] = c.strides;
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi = c.hooves[h];
    nlohmann::json hj = {{"touchdown_phase", hi.touchdown_phase}, {"duty_factor", hi.duty_factor},
                         {"peak_height_cm", hi.peak_height_cm}, {"lowest_cm", hi.lowest_cm},
                         {"max_slide_mm_per_frame", hi.max_slide_mm}, {"touchdowns", hi.touchdowns},
                         {"stance_slide_cm", hi.stance_slide_cm},
                         {"stance_slide_s", {hi.stance_slide_from_s, hi.stance_slide_to_s}},
                         {"max_slide_mm_per_frame_outside_that_stance", hi.max_slide_outside_stance_mm}};
    if (ref && ref->periodic) {
      if (const Verdict* td = findVerdict(verdicts, std::string(kHoofNames[h]) + ".touchdown_phase")) {
        hj["reference_touchdown_phase"] = rangeJson(td->range);
        hj["touchdown_ok"] = td->ok;
        if (!td->note.empty()) {
          // The gallop's fore pair: judged against the one-suspension phase; the table's verdict beside it.
          hj["reference_touchdown_phase_table"] = rangeJson(ref->touchdown_phase[h]);
          hj["touchdown_ok_table"] = phaseDistance(hi.touchdown_phase, ref->touchdown_phase[h]) <= kTouchdownTolerance + 1e-9;
        }
      }
      if (const Verdict* duty = findVerdict(verdicts, std::string(kHoofNames[h]) + ".duty_factor")) {
        hj["reference_duty_factor"] = rangeJson(duty->range);
        hj["duty_ok"] = duty->ok;
      }
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
  j["whole_clip"] = {{"pitch_deg", {c.pitch_lowest_deg, c.pitch_highest_deg}},
                     {"pitch_held_40_70_s", c.pitch_held_s},
                     {"croup_ups", c.croup_ups},
                     {"airborne_phases", c.airborne_phases},
                     {"longest_airborne_ms", c.longest_airborne_ms},
                     {"longest_airborne_from_s", c.longest_airborne_from_s},
                     {"liftoff_pitch_deg", c.liftoff_pitch_deg},
                     {"slide_hoof", c.slide_hoof >= 0 ? nlohmann::json(kHoofNames[c.slide_hoof]) : nlohmann::json(nullptr)},
                     {"fore_touchdowns_during_slide", c.fore_touchdowns_during_slide}};
  j["fastest_channel"] = {{"channel", c.max_step_channel}, {"per_s", c.max_channel_step}, {"at_s", c.max_step_at_s}};
  j["problems"] = c.problems;
  j["expected_slides"] = nlohmann::json::array();
  for (int h = 2; h < 4; ++h)
    if (expectedSlide(c, ref, h) && c.hooves[h].max_slide_mm > c.slide_limit_mm) j["expected_slides"].push_back(kHoofNames[h]);
  if (ref) {
    nlohmann::json reference = {{"gait", ref->gait}, {"periodic", ref->periodic},
                                {"touchdown_tolerance", kTouchdownTolerance},
                                {"per_stride_tolerance", kPerStrideTolerance},
                                {"source", "docs/gait-reference.md"}};
    nlohmann::json flags = nlohmann::json::object(), details = nlohmann::json::array();
    bool all = true;
    for (const Verdict& v : verdicts) {
      flags[v.key] = v.ok;
      all = all && v.ok;
      reference[v.key] = rangeJson(v.range);
      nlohmann::json d = {{"key", v.key}, {"value", v.value}, {"reference", rangeJson(v.range)}, {"ok", v.ok}};
      if (!v.note.empty()) d["note"] = v.note;
      details.push_back(d);
    }
    // Kept for readers of the earlier format: the counts as whole numbers.
    if (ref->periodic) {
      reference["suspensions_per_stride"] = ref->suspensions_per_stride;
      reference["rear_pivot_cycles_per_stride"] = ref->pivot_cycles_per_stride;
    }
    j["reference"] = reference;
    j["verdicts"] = flags;
    j["verdict_details"] = details;
    j["all_ok"] = all;
  }
  return j;
}

}  // namespace stirrup::rig
