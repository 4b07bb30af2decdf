#include "rig/motion/movement.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rig/motion/noise.h"

namespace stirrup::rig {
namespace {

double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

// Keys (time, value) sorted by time, held flat before the first and after the last; between two keys
// the value is `between(t0, v0, t1, v1)` of the keys either side (linear, or eased).
template <class Between>
double interpolateKeys(const std::vector<std::pair<double, double>>& keys, double t, Between between) {
  if (keys.empty()) return 0.0;
  if (t <= keys.front().first) return keys.front().second;
  if (t >= keys.back().first) return keys.back().second;
  auto it = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const auto& k) { return v < k.first; });
  const auto& [t1, v1] = *it;
  const auto& [t0, v0] = *std::prev(it);
  return between(t0, v0, t1, v1);
}

// 0 -> 1 -> 0 over s in [0, 1]. With plateau 0: sin(pi s)^1.5, highest at mid-swing (the hoof arc of
// docs/gait-reference.md). With a plateau the rise and fall share the rest of the swing.
double swingBump(double s, double plateau) {
  if (plateau <= 0.0) return std::pow(std::sin(std::numbers::pi * std::clamp(s, 0.0, 1.0)), 1.5);
  const double ramp = 0.5 * (1.0 - plateau);
  if (s < ramp) return smoothstep(s / ramp);
  if (s > 1.0 - ramp) return smoothstep((1.0 - s) / ramp);
  return 1.0;
}

constexpr std::array<std::array<HorseChannel, 2>, 4> kHoofPlaneChannels = {{
    {HorseChannel::lfHoofTx, HorseChannel::lfHoofTy},
    {HorseChannel::rfHoofTx, HorseChannel::rfHoofTy},
    {HorseChannel::lbHoofTx, HorseChannel::lbHoofTy},
    {HorseChannel::rbHoofTx, HorseChannel::rbHoofTy},
}};

struct HoofPlace {
  double tx = 0.0, ty = 0.0;
  bool sliding = false;  // down and riding with the body (a sliding stop's hind hoof)
};

// World velocity of a hoof while it is down: zero when planted, the body's speed when it slides.
double stanceWorldSpeed(const Movement& m, const Footfall& f, double t) {
  return f.slides ? m.speed_cm_s.at(t) : 0.0;
}

double stanceWorldX(const Movement& m, const Footfall& f, double t) {
  return f.slides ? m.travelCm(t) + f.slide_tx_cm : f.x_cm;
}

HoofPlace hoofAt(const Movement& m, const HoofSchedule& steps, double t) {
  const double travel = m.travelCm(t);
  if (steps.empty()) return {};
  // The last footfall that has touched down by t (or the first one, before the schedule starts).
  auto it = std::upper_bound(steps.begin(), steps.end(), t,
                             [](double v, const Footfall& f) { return v < f.down_s; });
  if (it == steps.begin()) return {stanceWorldX(m, *it, it->down_s) - travel, 0.0};
  const Footfall& cur = *std::prev(it);
  if (t <= cur.up_s || it == steps.end()) {
    const double held = std::min(t, cur.up_s);  // after the last lift-off the hoof stays where it left
    if (t > cur.up_s && cur.slides) return {stanceWorldX(m, cur, held) - travel, 0.0};
    return {stanceWorldX(m, cur, t) - travel, 0.0, cur.slides && t <= cur.up_s};
  }
  const Footfall& next = *it;
  const double span = next.down_s - cur.up_s;
  const double s = (t - cur.up_s) / span;
  // Hermite in world x between lift-off and touchdown, end tangents = stance velocities.
  const double p0 = stanceWorldX(m, cur, cur.up_s), p1 = stanceWorldX(m, next, next.down_s);
  const double m0 = stanceWorldSpeed(m, cur, cur.up_s) * span;
  const double m1 = stanceWorldSpeed(m, next, next.down_s) * span;
  const double s2 = s * s, s3 = s2 * s;
  const double x = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
  const SwingShape& w = cur.swing;
  const double bump = swingBump(s, w.plateau);
  HoofPlace h;
  h.tx = x - travel + w.reach_cm * bump;
  h.ty = w.lift_cm * bump + (w.carried ? m.flightElevationCm(t) : 0.0);
  if (w.paw_strokes > 0 && w.paw_cm > 0.0 && w.plateau > 0.0) {
    const double ramp = 0.5 * (1.0 - w.plateau);
    const double u = std::clamp((s - ramp) / w.plateau, 0.0, 1.0);  // 0..1 over the plateau
    const double fade = std::pow(std::sin(std::numbers::pi * u), 2.0);
    const double a = 2.0 * std::numbers::pi * (w.paw_strokes * u + w.paw_phase);
    // Forward and up, then back and down: the hoof strikes out and pulls back.
    h.tx += w.paw_cm * fade * std::sin(a);
    h.ty += 0.6 * w.paw_cm * fade * (1.0 - std::cos(a));
  }
  return h;
}

}  // namespace

void Ramp::add(double t, double v) {
  keys_.push_back({t, v});
  // The area from 0 (or from the key before) to this key; keys at or before 0 have none.
  if (t <= 0.0) {
    area_to_key_.push_back(0.0);
    return;
  }
  const std::size_t i = keys_.size() - 1;
  const bool first_after_zero = i == 0 || keys_[i - 1].first <= 0.0;
  const double from = first_after_zero ? 0.0 : keys_[i - 1].first;
  const double before = first_after_zero ? 0.0 : area_to_key_[i - 1];
  area_to_key_.push_back(t > from ? before + piece(from, t) : before);
}

double Ramp::at(double t) const {
  return interpolateKeys(keys_, t, [t](double t0, double v0, double t1, double v1) { return v0 + (v1 - v0) * (t - t0) / (t1 - t0); });
}

double Ramp::integral(double t) const {
  if (keys_.empty()) return 0.0;
  if (t < 0.0) {
    // ∫_t^0, piece by piece from t (rare: only a scan before the clip starts asks).
    double sum = 0.0, x = t;
    for (std::size_t i = 0; i <= keys_.size() && x < 0.0; ++i) {
      const double edge = i < keys_.size() ? std::min(keys_[i].first, 0.0) : 0.0;
      if (edge > x) {
        sum += piece(x, edge);
        x = edge;
      }
    }
    return -sum;
  }
  // The last key in (0, t], then the piece from it to t.
  auto it = std::upper_bound(keys_.begin(), keys_.end(), t, [](double v, const auto& k) { return v < k.first; });
  const std::size_t n = static_cast<std::size_t>(it - keys_.begin());
  if (n == 0 || keys_[n - 1].first <= 0.0) return t > 0.0 ? piece(0.0, t) : 0.0;
  const double from = keys_[n - 1].first;
  return t > from ? area_to_key_[n - 1] + piece(from, t) : area_to_key_[n - 1];
}

Keys& Keys::add(double t, double v) {
  keys_.push_back({t, v});
  return *this;
}

double Keys::at(double t) const {
  return interpolateKeys(keys_, t, [t](double t0, double v0, double t1, double v1) { return v0 + (v1 - v0) * smoothstep((t - t0) / (t1 - t0)); });
}

double Movement::flightElevationCm(double t) const {
  if (!(flight_end_s > flight_start_s) || t <= flight_start_s || t >= flight_end_s) return 0.0;
  // A parabola through 0 at take-off and landing, apex_cm at mid-flight. The builder picks the flight
  // time T = sqrt(8 apex / g), so this is the ballistic path of the centre of gravity.
  const double u = t - flight_start_s, T = flight_end_s - flight_start_s;
  return 4.0 * flight_apex_cm * u * (T - u) / (T * T);
}

HorseFrame sampleMovement(const Movement& m, double t) {
  HorseFrame f;
  f.travel_cm = m.travelCm(t);
  for (std::size_t h = 0; h < 4; ++h) {
    const HoofPlace p = hoofAt(m, m.hooves[h], t);
    f.controls[kHoofPlaneChannels[h][0]] = p.tx;
    f.controls[kHoofPlaneChannels[h][1]] = std::max(0.0, p.ty);
    f.hoof_sliding[h] = p.sliding;
  }
  // Trunk oscillation of the gaits playing, blended at one stride phase so blends cannot pop.
  const double phase = m.stridePhase(t);
  const double p = phase - std::floor(phase);
  double gain = m.oscillation_gain.empty() ? 1.0 : m.oscillation_gain.at(t);
  if (m.variation > 0.0) gain *= 1.0 + 0.25 * m.variation * valueNoise(m.seed, phase, 1);
  for (const auto& [gait, weight] : m.oscillation) {
    double w = weight.empty() ? 1.0 : weight.at(t);
    if (m.paced_blends) w *= std::min(1.0, gait.stride_hz / m.stride_hz.at(t));
    if (w > 0.0) addTrunkMotion(gait, p, gain * w, f);
  }
  for (std::size_t c = 0; c < kHorseChannelCount; ++c) {
    if (c <= static_cast<std::size_t>(HorseChannel::rbHoofTz)) continue;
    f.controls.value[c] += m.channel_keys[c].at(t);
  }
  f.controls[HorseChannel::rearPivotTy] += m.flightElevationCm(t);
  f.neck_rz += m.neck_rz.at(t);
  f.head_rz += m.head_rz.at(t);
  f.tail_rz += m.tail_rz.at(t);
  f.tail_ry += m.tail_ry.at(t);
  return f;
}

MovementClip::MovementClip(Movement m) : movement_(std::move(m)) {}

}  // namespace stirrup::rig
