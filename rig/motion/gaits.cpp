#include "rig/motion/gaits.h"

#include <cmath>

#include "rig/error.h"
#include "rig/motion/noise.h"

namespace stirrup::rig {
namespace {

// Per-hoof gait quantities blended at time t with the timeline's weights. Touchdown phases are
// unwrapped against the first gait so the blend takes the short way round the stride.
struct HoofGait {
  double touchdown = 0.0, duty = 0.5, lift_cm = 10.0;
};

HoofGait blendedHoof(const Movement& m, int hoof, double t) {
  HoofGait out{0.0, 0.0, 0.0};
  double total = 0.0, reference = m.oscillation.front().first.touchdown_phase[hoof];
  for (const auto& [g, weight] : m.oscillation) {
    // Unwrap along the whole timeline (not only the gaits playing now) so the result is continuous.
    double td = g.touchdown_phase[hoof];
    td -= std::round(td - reference);
    reference = td;
    const double w = weight.empty() ? 1.0 : weight.at(t);
    if (w <= 0.0) continue;
    out.touchdown += w * td;
    out.duty += w * g.duty_factor[hoof];
    out.lift_cm += w * g.hoof_lift_cm * (hoof < 2 ? g.fore_lift_scale : 1.0);
    total += w;
  }
  if (total > 0.0) {
    out.touchdown /= total;
    out.duty /= total;
    out.lift_cm /= total;
  }
  return out;
}

}  // namespace

double applyGaitTimeline(const GaitTimeline& tl, Movement& m) {
  if (tl.segments.empty()) throw InputError("gait timeline: no gaits");
  m.speed_cm_s = Ramp();
  m.stride_hz = Ramp();
  m.oscillation.clear();
  const double half = 0.5 * tl.blend_s;
  double start = 0.0;
  for (std::size_t i = 0; i < tl.segments.size(); ++i) {
    const GaitSegment& seg = tl.segments[i];
    const double end = start + seg.duration_s;
    const bool first = i == 0, last = i + 1 == tl.segments.size();
    // Constant within the segment, linear across the blend windows at its ends.
    m.speed_cm_s.add(first ? start : start + half, seg.gait.speed_cm_s);
    m.stride_hz.add(first ? start : start + half, seg.gait.stride_hz);
    if (!last) {
      m.speed_cm_s.add(end - half, seg.gait.speed_cm_s);
      m.stride_hz.add(end - half, seg.gait.stride_hz);
    }
    Keys w;
    if (!first) w.add(start - half, 0.0).add(start + half, 1.0);
    else w.add(start, 1.0);
    if (!last) w.add(end - half, 1.0).add(end + half, 0.0);
    m.oscillation.push_back({seg.gait, w});
    start = end;
  }
  m.variation = tl.variation;
  m.seed = tl.seed;
  return start;
}

HoofSchedule scanFootfalls(const Movement& m, const GaitTimeline& tl, int hoof, double from_s, double to_s,
                           double lift_by_s) {
  HoofSchedule out;
  const auto hoofPhase = [&](double t) { return m.stridePhase(t) - blendedHoof(m, hoof, t).touchdown; };
  // The time in [a, b] where hoofPhase reaches `target` (hoofPhase increases with t).
  const auto solve = [&](double a, double b, double target) {
    for (int i = 0; i < 50; ++i) {
      const double mid = 0.5 * (a + b);
      (hoofPhase(mid) < target ? a : b) = mid;
    }
    return 0.5 * (a + b);
  };
  constexpr double kScanStep = 0.002;
  double t = from_s;
  double k = std::floor(hoofPhase(t));
  while (t < to_s) {
    const double t1 = t + kScanStep;
    if (std::floor(hoofPhase(t1)) > k) {
      k += 1.0;
      const double down = solve(t, t1, k);
      const HoofGait g = blendedHoof(m, hoof, down);
      // Lift-off: the hoof phase has advanced by the duty factor.
      double b = down;
      while (hoofPhase(b) < k + g.duty) b += kScanStep;
      const double up = solve(b - kScanStep, b, k + g.duty);
      if (up > lift_by_s) break;
      Footfall f;
      f.down_s = down;
      f.up_s = up;
      // Centred on the rest place: lands half a stance ahead, leaves half a stance behind.
      const auto stride = static_cast<std::int64_t>(k);
      const double jitter = tl.variation * hashSigned(tl.seed, stride, hoof);
      f.x_cm = 0.5 * (m.travelCm(down) + m.travelCm(up)) + 2.0 * jitter;
      f.swing.lift_cm = g.lift_cm * (1.0 + 0.15 * tl.variation * hashSigned(tl.seed + 1, stride, hoof));
      out.push_back(f);
      t = down;
    }
    t = std::max(t, t1);
    if (!out.empty() && t < out.back().up_s) t = out.back().up_s;  // no touchdown while down
    k = std::max(k, std::floor(hoofPhase(t)));
  }
  return out;
}

}  // namespace stirrup::rig
