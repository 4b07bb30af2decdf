#include "rig/motion/gaits.h"

#include <algorithm>
#include <cmath>

#include "rig/error.h"
#include "rig/motion/noise.h"

namespace stirrup::rig {
namespace {

// Per-hoof gait quantities blended at time t with the timeline's weights. Touchdown phases are
// unwrapped against the first gait so the blend takes the short way round the stride.
struct HoofGait {
  double touchdown = 0.0, duty = 0.5, lift_cm = 10.0;
  double lift_cm_s = 0.0;   // lift over the steady swing time, (1 - duty) / stride_hz
  double top_lift_cm = 0.0; // the highest lift of the gaits playing
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
    const double scale = hoof < 2 ? g.fore_lift_scale : 1.0, lift = g.hoof_lift_cm * scale;
    out.lift_cm += w * g.hoof_lift_cm * scale;
    out.lift_cm_s += w * lift * g.stride_hz / (1.0 - g.duty_factor[hoof]);
    out.top_lift_cm = std::max(out.top_lift_cm, lift);
    total += w;
  }
  if (total > 0.0) {
    out.touchdown /= total;
    out.duty /= total;
    out.lift_cm /= total;
    out.lift_cm_s /= total;
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
      // The next two touchdowns, which the phase fixes whatever this stance does (paced blends only).
      double next = down, after = down;
      if (m.paced_blends) {
        // hoofPhase only increases, so coarse steps bracket each crossing for the bisection.
        constexpr double kBracketStep = 0.05;
        while (hoofPhase(next) < k + 1.0) next += kBracketStep;
        next = solve(next - kBracketStep, next, k + 1.0);
        after = next;
        while (hoofPhase(after) < k + 2.0) after += kBracketStep;
        after = solve(after - kBracketStep, after, k + 2.0);
      }
      // Lift-off: the hoof phase has advanced by the duty factor. Paced (gaits.h): by the duty factor
      // d at the time, counting the phase from the earlier of the touchdown phases at touchdown and
      // now, and within d of this cycle c (touchdown to next touchdown). The swing after covers half
      // this stance s and half the next (at most d of the next cycle c'), plus the body's travel in the
      // air: at the gait's pace when (s + d c') / 2 <= d / (1 - d) (c - s), so when c' > c the stance
      // ends by d (2c - (1 - d) c') / (1 + d), and never before half of d c.
      const auto inStance = [&](double x) {
        if (!m.paced_blends) return hoofPhase(x) < k + g.duty;
        const HoofGait now = blendedHoof(m, hoof, x);
        const double d = now.duty, cycle = next - down, next_cycle = after - next;
        const double pace = std::clamp((2.0 * cycle - (1.0 - d) * next_cycle) / (1.0 + d), 0.5 * cycle, cycle);
        return m.stridePhase(x) - std::min(now.touchdown, g.touchdown) < k + d && x - down < d * pace;
      };
      double b = down;
      while (inStance(b)) b += kScanStep;
      double a = b - kScanStep;
      for (int i = 0; i < 50; ++i) {
        const double mid = 0.5 * (a + b);
        (inStance(mid) ? a : b) = mid;
      }
      const double up = 0.5 * (a + b);
      if (up > lift_by_s) break;
      double lift_cm = g.lift_cm;
      if (m.paced_blends) {  // the swing's time at the gaits' blended lift rate, no higher than they lift
        const HoofGait at_up = blendedHoof(m, hoof, up);
        lift_cm = std::min(at_up.lift_cm_s * (next - up), at_up.top_lift_cm);
      }
      Footfall f;
      f.down_s = down;
      f.up_s = up;
      // Centred on the rest place: lands half a stance ahead, leaves half a stance behind.
      const auto stride = static_cast<std::int64_t>(k);
      const double jitter = tl.variation * hashSigned(tl.seed, stride, hoof);
      f.x_cm = 0.5 * (m.travelCm(down) + m.travelCm(up)) + 2.0 * jitter;
      f.swing.lift_cm = lift_cm * (1.0 + 0.15 * tl.variation * hashSigned(tl.seed + 1, stride, hoof));
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
