#include "rig/motion/clip_measure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
constexpr int kLeftHind = 2;

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

}  // namespace stirrup::rig
