#include "rig/motion/speed_profile.h"

#include <algorithm>
#include <cmath>

#include "rig/error.h"

namespace stirrup::rig {
namespace {


}  // namespace

SpeedProfile::SpeedProfile(std::vector<Key> keys, Over over, double duration_s, const std::string& source)
    : keys_(std::move(keys)), over_(over), duration_(duration_s) {
  if (keys_.empty()) throw InputError(source + ": speed: expected at least one key [" +
                                      std::string(over == Over::Time ? "seconds" : "cm") + ", cm/s], got none");
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const std::string field = source + ": speed[" + std::to_string(i) + "]";
    if (!(std::abs(keys_[i].at) <= kMaxKeyAt))
      throw InputError(field + ": expected a " + (over == Over::Time ? "time from -1e+07 to 1e+07 s" : "distance from -1e+07 to 1e+07 cm") +
                       ", got " + numberText(keys_[i].at));
    if (!(keys_[i].speed >= kMinSpeedCmS && keys_[i].speed <= kMaxSpeedCmS))
      throw InputError(field + ": expected a speed from " + numberText(kMinSpeedCmS) + " to " + numberText(kMaxSpeedCmS) + " cm/s, got " +
                       numberText(keys_[i].speed));
    if (i > 0 && !(keys_[i].at > keys_[i - 1].at))
      throw InputError(field + ": expected a " + (over == Over::Time ? "time" : "distance") + " after speed[" +
                       std::to_string(i - 1) + "]'s " + numberText(keys_[i - 1].at) + ", got " + numberText(keys_[i].at));
  }
  if (!(std::isfinite(duration_s) && duration_s >= 0.0)) throw InputError(source + ": duration: expected a time >= 0");
  // Fritsch-Carlson: secant slopes, averaged at the inner keys, zero where the secants change sign,
  // then scaled so that no segment overshoots.
  const std::size_t n = keys_.size();
  slopes_.assign(n, 0.0);
  std::vector<double> secant(n > 1 ? n - 1 : 0);
  for (std::size_t i = 0; i + 1 < n; ++i)
    secant[i] = (keys_[i + 1].speed - keys_[i].speed) / (keys_[i + 1].at - keys_[i].at);
  for (std::size_t i = 1; i + 1 < n; ++i)
    slopes_[i] = secant[i - 1] * secant[i] <= 0.0 ? 0.0 : 0.5 * (secant[i - 1] + secant[i]);
  if (n > 1) slopes_[0] = secant[0], slopes_[n - 1] = secant[n - 2];
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (secant[i] == 0.0) {
      slopes_[i] = slopes_[i + 1] = 0.0;
      continue;
    }
    const double a = slopes_[i] / secant[i], b = slopes_[i + 1] / secant[i];
    const double r = a * a + b * b;
    if (r > 9.0) {
      const double t = 3.0 / std::sqrt(r);
      slopes_[i] = t * a * secant[i];
      slopes_[i + 1] = t * b * secant[i];
    }
  }
  // Distance by time: RK4 on ds/dt = v(t) or v(s).
  const std::size_t steps = std::size_t(std::ceil(duration_ / kStepS)) + 1;
  distance_.assign(steps + 1, 0.0);
  auto rate = [&](double t, double s) { return speedAtKey(over_ == Over::Time ? t : s); };
  for (std::size_t i = 0; i < steps; ++i) {
    const double t = double(i) * kStepS, s = distance_[i], h = kStepS;
    const double k1 = rate(t, s), k2 = rate(t + h / 2, s + h / 2 * k1), k3 = rate(t + h / 2, s + h / 2 * k2),
                 k4 = rate(t + h, s + h * k3);
    distance_[i + 1] = s + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
}

double SpeedProfile::speedAtKey(double x) const {
  if (x <= keys_.front().at) return keys_.front().speed;
  if (x >= keys_.back().at) return keys_.back().speed;
  const auto it = std::upper_bound(keys_.begin(), keys_.end(), x, [](double v, const Key& k) { return v < k.at; });
  const std::size_t i = std::size_t(it - keys_.begin()) - 1;
  const double h = keys_[i + 1].at - keys_[i].at, u = (x - keys_[i].at) / h, u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * keys_[i].speed + (u3 - 2 * u2 + u) * h * slopes_[i] +
         (-2 * u3 + 3 * u2) * keys_[i + 1].speed + (u3 - u2) * h * slopes_[i + 1];
}

double SpeedProfile::distanceAtTime(double t) const {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, double(distance_.size() - 1) * kStepS);
  const std::size_t i = std::min(std::size_t(t / kStepS), distance_.size() - 2);
  const double u = (t - double(i) * kStepS) / kStepS;
  // Cubic Hermite between table entries with the speeds as slopes: C1 in time, like the speed.
  const double s0 = distance_[i], s1 = distance_[i + 1];
  const double v0 = over_ == Over::Time ? speedAtKey(double(i) * kStepS) : speedAtKey(s0);
  const double v1 = over_ == Over::Time ? speedAtKey(double(i + 1) * kStepS) : speedAtKey(s1);
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * s0 + (u3 - 2 * u2 + u) * kStepS * v0 + (-2 * u3 + 3 * u2) * s1 + (u3 - u2) * kStepS * v1;
}

double SpeedProfile::speedAtTime(double t) const {
  return over_ == Over::Time ? speedAtKey(t) : speedAtKey(distanceAtTime(t));
}

const char* pathGaitName(PathGait g) {
  switch (g) {
    case PathGait::Walk: return "walk";
    case PathGait::Trot: return "trot";
    case PathGait::Canter: return "canter";
    case PathGait::Gallop: return "gallop";
  }
  return "?";
}

GaitSchedule::GaitSchedule(const SpeedProfile& speed, const GaitThresholds& th) {
  // The first gait from the starting speed, between thresholds by the midpoint of each band.
  const double v0 = speed.speedAtTime(0.0);
  first_ = v0 >= 0.5 * (th.canter_gallop_up + th.canter_gallop_down)   ? PathGait::Gallop
           : v0 >= 0.5 * (th.trot_canter_up + th.trot_canter_down)     ? PathGait::Canter
           : v0 >= 0.5 * (th.walk_trot_up + th.walk_trot_down)         ? PathGait::Trot
                                                                       : PathGait::Walk;
  PathGait g = first_;
  const std::size_t steps = std::size_t(std::ceil(speed.duration() / SpeedProfile::kStepS));
  for (std::size_t i = 1; i <= steps; ++i) {
    const double t = double(i) * SpeedProfile::kStepS, v = speed.speedAtTime(t);
    PathGait next = g;
    // One gait at a time, up or down, each past its own threshold.
    if (g == PathGait::Walk && v >= th.walk_trot_up) next = PathGait::Trot;
    else if (g == PathGait::Trot && v >= th.trot_canter_up) next = PathGait::Canter;
    else if (g == PathGait::Trot && v < th.walk_trot_down) next = PathGait::Walk;
    else if (g == PathGait::Canter && v >= th.canter_gallop_up) next = PathGait::Gallop;
    else if (g == PathGait::Canter && v < th.trot_canter_down) next = PathGait::Trot;
    else if (g == PathGait::Gallop && v < th.canter_gallop_down) next = PathGait::Canter;
    if (next != g) {
      changes_.push_back({t, g, next});
      g = next;
    }
  }
}

PathGait GaitSchedule::gaitAt(double t) const {
  PathGait g = first_;
  for (const Change& c : changes_) {
    if (c.time > t) break;
    g = c.to;
  }
  return g;
}

}  // namespace stirrup::rig
