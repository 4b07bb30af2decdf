#include "rig/motion/horse_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <glm/glm.hpp>

#include "rig/error.h"
#include "rig/motion/ground_path.h"
#include "rig/motion/speed_profile.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {

constexpr std::size_t kLimits = 8;
// Acceleration is the speed profile's derivative, by central differences over this (s): the profile's
// own table step, far shorter than any change of speed a horse makes.
constexpr double kAccelStepS = SpeedProfile::kStepS;
// A sample is a run's worst when it is over its limit by this factor more than the worst before it, so
// a steady breach (rounding apart) reports its first sample, the same on every machine.
constexpr double kWorseBy = 1.0 + 1e-9;

// The path at arc length s, continued straight along its end tangents beyond either end (as the path
// clip places hooves beyond them).
GroundPath::Sample extended(const GroundPath& path, double s) {
  GroundPath::Sample p = path.at(std::clamp(s, 0.0, path.length()));
  if (s < 0.0 || s > path.length()) p.position += p.tangent * (s < 0.0 ? s : s - path.length());
  return p;
}

// The seconds the path clip tables its speed profile over: the path at the slowest key's speed.
double speedTableSeconds(const PathClipParams& params, double length) {
  double slowest = 0.0;
  for (const auto& k : params.speed) slowest = slowest == 0.0 ? k.speed : std::min(slowest, k.speed);
  return slowest > 0.0 && std::isfinite(slowest) ? std::min(params.max_duration_s, length / slowest + 1.0) : 1.0;
}

// The horse's length and hoof tracks, from its rest hoof places (lf, rf, lb, rb).
struct HorseFootprint {
  double fore_x = 0, hind_x = 0;  // the fore and hind pairs' middles along the body
  double body_cm = 0, track_cm = 0;
};

HorseFootprint horseFootprint(const std::array<glm::dvec2, 4>& rest) {
  HorseFootprint f;
  f.fore_x = 0.5 * (rest[0].x + rest[1].x), f.hind_x = 0.5 * (rest[2].x + rest[3].x);
  f.body_cm = std::max(f.fore_x - f.hind_x, 1.0);
  f.track_cm = 0.25 * (std::abs(rest[0].y) + std::abs(rest[1].y) + std::abs(rest[2].y) + std::abs(rest[3].y));
  return f;
}

// When the horse has travelled a distance along the path: the samples ask in order of distance, so each
// search starts from the time of the one before.
struct TravelTimes {
  const SpeedProfile& speed;
  double table_s = 0;
  double last = 0;  // the previous sample's time
  // The first time the horse has travelled s: bisection from the previous sample's time (travel grows).
  double at(double s) const {
    double a = last, b = std::max(last, 1e-3);
    while (speed.distanceAtTime(b) < s && b < table_s) b = std::min(table_s, b * 2.0 + 1e-3);
    for (int i = 0; i < 50; ++i) {
      const double mid = 0.5 * (a + b);
      (speed.distanceAtTime(mid) < s ? a : b) = mid;
    }
    return b;
  }
};

// One sample's value and bound of each limit (by HorseLimit; bound 0 = not applicable there).
struct LimitRow {
  std::array<double, kLimits>& value;
  std::array<double, kLimits>& bound;
  void set(HorseLimit limit, double v, double b) const {
    value[std::size_t(limit)] = v;
    bound[std::size_t(limit)] = b;
  }
};

// Speed, and its rate: a forward difference at the clip's start (the speed holds before it). `power`
// (cm²/s³) caps the acceleration at a = P / v.
void readTravelLimits(const LimitRow& row, const SpeedProfile& speed, double t, double v, const HorseLimits& limits, double power) {
  const double g = HorseLimits::kGravityCmS2;
  row.set(HorseLimit::Speed, v, limits.top_speed_cm_s);
  const double t0 = std::max(0.0, t - kAccelStepS), t1 = t + kAccelStepS;
  const double accel = (speed.speedAtTime(t1) - speed.speedAtTime(t0)) / (t1 - t0);
  row.set(HorseLimit::Acceleration, std::max(accel, 0.0), std::min(limits.max_accel_g * g, power / v));
  row.set(HorseLimit::Deceleration, std::max(-accel, 0.0), limits.max_decel_g * g);
}

// The turn: curvature averaged over the horse's length is the heading's change across it. Returns the
// turn's radius (0 going straight).
double readTurnLimit(const LimitRow& row, const GroundPath& path, double s, double v, double body_cm, const HorseLimits& limits) {
  const double turn_deg =
      std::remainder(extended(path, s + 0.5 * body_cm).heading_deg - extended(path, s - 0.5 * body_cm).heading_deg, 360.0);
  const double curvature = std::abs(turn_deg) / kDegreesPerRadian / body_cm;
  row.set(HorseLimit::Turn, v * v * curvature, limits.hoof_friction * HorseLimits::kGravityCmS2);
  return curvature > 0.0 ? 1.0 / curvature : 0.0;
}

double groundHeight(const Terrain* terrain, glm::dvec2 q) { return terrain ? terrain->height(q.x, q.y) : 0.0; }

// Footing: the ground's slope across a hoof's footprint, on the left and right hoof tracks (degrees).
double steepestFooting(const Terrain* terrain, const GroundPath::Sample& here, double track_cm, double half_foot) {
  const glm::dvec2 right{-here.tangent.y, here.tangent.x};
  double steepest = 0.0;
  for (const double side : {-track_cm, track_cm}) {
    const glm::dvec2 q = here.position + right * side;
    const double dx =
        (groundHeight(terrain, q + glm::dvec2{half_foot, 0}) - groundHeight(terrain, q - glm::dvec2{half_foot, 0})) / (2 * half_foot);
    const double dz =
        (groundHeight(terrain, q + glm::dvec2{0, half_foot}) - groundHeight(terrain, q - glm::dvec2{0, half_foot})) / (2 * half_foot);
    steepest = std::max(steepest, std::atan(std::hypot(dx, dz)) * kDegreesPerRadian);
  }
  return steepest;
}

// The ground under the horse at arc length s, time t: its grade between the fore and hind hooves along
// the path (+ climbing), the grade the gait is ridden on, and the footing under the hooves.
void readGroundLimits(const LimitRow& row, const GroundPath& path, const Terrain* terrain, const GaitSchedule& gaits, double s,
                      double t, const HorseFootprint& horse, const HorseLimits& limits) {
  const GroundPath::Sample fore = extended(path, s + horse.fore_x), hind = extended(path, s + horse.hind_x);
  const double grade = std::atan2(groundHeight(terrain, fore.position) - groundHeight(terrain, hind.position), horse.fore_x - horse.hind_x) *
                       kDegreesPerRadian;
  row.set(HorseLimit::Climb, std::max(grade, 0.0), limits.max_climb_deg);
  row.set(HorseLimit::Descent, std::max(-grade, 0.0), limits.max_descent_deg);
  const PathGait gait = gaits.gaitAt(t);
  if (gait == PathGait::Canter || gait == PathGait::Gallop) row.set(HorseLimit::CanterGrade, std::abs(grade), limits.max_canter_grade_deg);
  const double half_foot = 0.5 * limits.hoof_footprint_cm;
  row.set(HorseLimit::Footing, steepestFooting(terrain, extended(path, s), horse.track_cm, half_foot), limits.max_footing_deg);
}

}  // namespace

double HorseLimits::accelPowerCm2S3() const {
  // Time to 1500 cm/s: v_c / a0 at a0 up to v_c = P / a0, then (v² − v_c²) / 2P after (m v dv/dt = m P).
  // T(P) = P / 2a0² + v²/2P falls then rises in P; its smaller root is the horse that only just makes it.
  const double a0 = max_accel_g * kGravityCmS2, v = 1500.0, T = seconds_to_15_m_s;
  const double b = 2.0 * a0 * a0 * T, c = a0 * a0 * v * v;  // P² − b P + c = 0
  const double disc = b * b - 4.0 * c;
  return disc > 0.0 ? 0.5 * (b - std::sqrt(disc)) : 0.5 * b;
}

const char* horseLimitName(HorseLimit limit) {
  switch (limit) {
    case HorseLimit::Speed: return "speed";
    case HorseLimit::Acceleration: return "acceleration";
    case HorseLimit::Deceleration: return "deceleration";
    case HorseLimit::Turn: return "turn";
    case HorseLimit::Climb: return "climb";
    case HorseLimit::Descent: return "descent";
    case HorseLimit::CanterGrade: return "canter grade";
    case HorseLimit::Footing: return "footing";
  }
  return "limit";
}

PathLimitCheck::PathLimitCheck(const PathClipParams& params, const Terrain* terrain, std::string file,
                               std::string clip_field, const HorseLimits& limits)
    : file_(std::move(file)), clip_field_(std::move(clip_field)), limits_(limits) {
  const std::string source = file_ + ": " + clip_field_;
  const GroundPath path(params.points, source);
  const double length = path.length();
  // The speed profile over as long as the path clip tables it.
  const double table_s = speedTableSeconds(params, length);
  const SpeedProfile speed(params.speed, params.over, table_s, source);
  const GaitSchedule gaits(speed, params.thresholds);
  const HorseFootprint horse = horseFootprint(params.hoof_rest);
  const double power = limits_.accelPowerCm2S3();  // cm²/s³: a = P / v
  TravelTimes times{speed, table_s};

  const double step_cm = std::max(kSampleStepCm, length / double(kMaxSamples));
  const int steps = std::max(1, int(std::ceil(length / step_cm)));
  samples_.reserve(std::size_t(steps) + 1);
  int segment = 0;
  const int segments = int(path.points().size()) - 1;
  for (int i = 0; i <= steps; ++i) {
    Sample x;
    x.s = std::min(length, double(i) * step_cm);
    times.last = x.t = i == 0 ? 0.0 : times.at(x.s);
    while (segment + 1 < segments && path.distanceAtPoint(std::size_t(segment) + 1) <= x.s) ++segment;
    x.segment = segment;
    x.v = speed.speedAtTime(x.t);
    const LimitRow row{x.value, x.bound};
    readTravelLimits(row, speed, x.t, x.v, limits_, power);
    x.radius_cm = readTurnLimit(row, path, x.s, x.v, horse.body_cm, limits_);
    if (terrain && !terrain->flat()) readGroundLimits(row, path, terrain, gaits, x.s, x.t, horse, limits_);
    samples_.push_back(x);
  }

  // Runs of samples over each limit.
  for (std::size_t k = 0; k < kLimits; ++k) {
    const Sample* start = nullptr;
    const Sample* worst = nullptr;
    const auto over = [k](const Sample& x) { return x.bound[k] > 0.0 && x.value[k] > x.bound[k]; };
    const auto ratio = [k](const Sample& x) { return x.value[k] / x.bound[k]; };
    for (const Sample& x : samples_) {
      if (over(x)) {
        if (!start) start = worst = &x;
        if (ratio(x) > ratio(*worst) * kWorseBy) worst = &x;
      } else if (start) {
        breaches_.push_back(breachAt(HorseLimit(k), *start, *worst));
        start = worst = nullptr;
      }
    }
    if (start) breaches_.push_back(breachAt(HorseLimit(k), *start, *worst));
  }
  std::stable_sort(breaches_.begin(), breaches_.end(),
                   [](const LimitBreach& a, const LimitBreach& b) { return a.time_s < b.time_s; });
}

LimitBreach PathLimitCheck::breachAt(HorseLimit limit, const Sample& start, const Sample& worst) const {
  const std::size_t k = std::size_t(limit);
  LimitBreach b;
  b.limit = limit;
  b.segment = start.segment;
  b.time_s = start.t;
  b.distance_cm = start.s;
  b.value = worst.value[k];
  b.bound = worst.bound[k];
  b.speed_cm_s = worst.v;
  const std::string v = fixedNumber(b.value, 0), l = fixedNumber(b.bound, 0), vd = fixedNumber(b.value, 1), ld = fixedNumber(b.bound, 1);
  const std::string speed = fixedNumber(worst.v, 0) + " cm/s";
  std::string what;
  switch (limit) {
    case HorseLimit::Speed:
      b.field = "speed";
      what = "a speed of " + v + " cm/s, beyond the " + l + " cm/s no horse has been timed above (the record, 70.76 km/h)";
      break;
    case HorseLimit::Acceleration:
      b.field = "speed";
      what = "speeding up at " + v + " cm/s² at " + speed + ", beyond the " + l +
             " cm/s² a horse reaches at that speed (Williams et al. 2009)";
      break;
    case HorseLimit::Deceleration:
      b.field = "speed";
      what = "slowing at " + v + " cm/s², beyond the " + l + " cm/s² a horse brakes at (Williams et al. 2009)";
      break;
    case HorseLimit::Turn:
      b.field = "points";
      what = "a turn of " + fixedNumber(worst.radius_cm, 0) + " cm radius at " + speed + " asks " + v +
             " cm/s² (v²/r) of the hooves' grip, beyond " + l + " cm/s² (friction " + fixedNumber(limits_.hoof_friction, 1) +
             " × g; Tan and Wilson 2011)";
      break;
    case HorseLimit::Climb:
      b.field = "terrain";
      what = "a climb of " + vd + "° under the horse, beyond the " + ld + "° a ridden horse climbs";
      break;
    case HorseLimit::Descent:
      b.field = "terrain";
      what = "a descent of " + vd + "° under the horse, beyond the " + ld + "° a ridden horse descends";
      break;
    case HorseLimit::CanterGrade:
      b.field = "terrain";
      what = "a grade of " + vd + "° at the canter or gallop (" + speed + "), beyond the " + ld + "° a horse is cantered on";
      break;
    case HorseLimit::Footing:
      b.field = "terrain";
      what = "ground sloping " + vd + "° under a hoof (across its " + fixedNumber(limits_.hoof_footprint_cm, 0) +
             " cm footprint), beyond the " + ld + "° a hoof stands on";
      break;
  }
  b.text = "segment " + std::to_string(start.segment) + " from " + fixedNumber(start.t, 2) + " s: " + what;
  return b;
}

std::string PathLimitCheck::errorText(const LimitBreach& b) const {
  if (b.field == "terrain") return file_ + ": terrain: under " + clip_field_ + ".points, " + b.text;
  return file_ + ": " + clip_field_ + "." + b.field + ": " + b.text;
}

const LimitBreach* PathLimitCheck::worst() const {
  const LimitBreach* w = nullptr;
  for (const LimitBreach& b : breaches_)
    if (!w || b.value / b.bound > w->value / w->bound * kWorseBy) w = &b;
  return w;
}

std::string PathLimitCheck::error() const { return breaches_.empty() ? "" : errorText(*worst()); }

std::vector<LimitBreach> PathLimitCheck::during(double t0, double t1) const {
  std::vector<LimitBreach> out;
  if (samples_.empty()) return out;
  // A window between two samples (a slow horse, a high frame rate) reads the sample nearest its middle.
  const auto first = std::lower_bound(samples_.begin(), samples_.end(), t0, [](const Sample& x, double t) { return x.t < t; });
  if (first == samples_.end() || first->t > t1) {
    const double mid = 0.5 * (t0 + t1);
    const Sample& x = first == samples_.end() ? samples_.back()
                      : first == samples_.begin() || first->t - mid < mid - std::prev(first)->t ? *first
                                                                                                : *std::prev(first);
    t0 = t1 = x.t;
  }
  const auto from = std::lower_bound(samples_.begin(), samples_.end(), t0, [](const Sample& x, double t) { return x.t < t; });
  for (std::size_t k = 0; k < kLimits; ++k) {
    const Sample* worst = nullptr;
    for (auto it = from; it != samples_.end() && it->t <= t1; ++it) {
      const Sample& x = *it;
      if (!(x.bound[k] > 0.0 && x.value[k] > x.bound[k])) continue;
      if (!worst || x.value[k] / x.bound[k] > worst->value[k] / worst->bound[k] * kWorseBy) worst = &x;
    }
    if (worst) out.push_back(breachAt(HorseLimit(k), *worst, *worst));
  }
  return out;
}

namespace {

// Each gait's top speed (HorseLimits, where the sources are given in full), the verb for "faster than a
// horse ...", and the source in a few words for the one-line error.
struct GaitTop {
  const char* gait;
  const char* verb;
  double HorseLimits::*top;
  const char* source;
};
constexpr GaitTop kGaitTops[] = {
    {"walk", "walks", &HorseLimits::max_walk_cm_s,
     "horses change to the trot at 160-230 cm/s, Froude 0.35, Griffin et al. 2004; a walk held past that, an estimate"},
    {"trot", "trots", &HorseLimits::max_trot_cm_s, "the fastest trotted mile, 1:48.4, Homicide Hunter 2018"},
    {"canter", "canters", &HorseLimits::max_canter_cm_s,
     "estimated from horses changing to the gallop at 700-800 cm/s and ridden canters of 800-1000"},
    {"gallop", "gallops", &HorseLimits::top_speed_cm_s, "the fastest recorded horse, 70.76 km/h, Winning Brew 2008"},
};

}  // namespace

std::optional<GaitSpeedBreach> gaitSpeedBreach(const GaitSpeed& speed, const HorseLimits& limits) {
  for (const GaitTop& g : kGaitTops) {
    if (speed.gait != g.gait || !(speed.speed_cm_s > limits.*g.top)) continue;
    return GaitSpeedBreach{speed, limits.*g.top, g.verb, g.source};
  }
  return std::nullopt;
}

std::string GaitSpeedBreach::text(const std::string& then) const {
  return fixedNumber(speed.speed_cm_s, 0) + " cm/s is faster than a horse " + verb + " (at most " + fixedNumber(bound_cm_s, 0) + " cm/s: " +
         source + then + ")";
}

TravelLimits travelLimitsAt(const Clip& clip, double time_s, const HorseLimits& limits) {
  TravelLimits r;
  r.time_s = time_s;
  const double w = TravelLimits::kTravelWindowS, end = clip.duration();
  const double t0 = std::max(0.0, time_s - w), t1 = std::min(end, time_s + w);
  if (t1 - t0 < 1e-6) return r;
  // Velocity on the ground over [a, b] and the heading there.
  const auto velocity = [&clip](double a, double b) {
    const HorseFrame fa = clip.sample(a), fb = clip.sample(b);
    return glm::dvec2(fb.travel_cm - fa.travel_cm, fb.travel_z_cm - fa.travel_z_cm) / (b - a);
  };
  const glm::dvec2 v = velocity(t0, t1);
  r.speed_cm_s = glm::length(v);
  const double tm = 0.5 * (t0 + t1);
  if (tm - t0 > 1e-6 && t1 - tm > 1e-6) {
    const glm::dvec2 va = velocity(t0, tm), vb = velocity(tm, t1);
    const glm::dvec2 a = (vb - va) / (0.5 * (t1 - t0));
    const glm::dvec2 along = r.speed_cm_s > 1e-6 ? v / r.speed_cm_s : glm::dvec2(1, 0);
    r.accel_cm_s2 = glm::dot(a, along);
    r.centripetal_cm_s2 = std::abs(along.x * a.y - along.y * a.x);
  }
  const double g = HorseLimits::kGravityCmS2;
  char text[200];
  if (r.speed_cm_s > limits.top_speed_cm_s) {
    std::snprintf(text, sizeof text, "a speed of %.0f cm/s, beyond the %.0f cm/s no horse has been timed above", r.speed_cm_s,
                  limits.top_speed_cm_s);
    r.breaches.emplace_back(HorseLimit::Speed, text);
  }
  const double accel_bound = std::min(limits.max_accel_g * g, limits.accelPowerCm2S3() / std::max(r.speed_cm_s, 1.0));
  if (r.accel_cm_s2 > accel_bound) {
    std::snprintf(text, sizeof text, "speeding up at %.0f cm/s², beyond the %.0f cm/s² a horse manages at %.0f cm/s",
                  r.accel_cm_s2, accel_bound, r.speed_cm_s);
    r.breaches.emplace_back(HorseLimit::Acceleration, text);
  }
  if (-r.accel_cm_s2 > limits.max_decel_g * g) {
    std::snprintf(text, sizeof text, "slowing down at %.0f cm/s², beyond the %.0f cm/s² (%.1f g) a horse brakes at",
                  -r.accel_cm_s2, limits.max_decel_g * g, limits.max_decel_g);
    r.breaches.emplace_back(HorseLimit::Deceleration, text);
  }
  if (r.centripetal_cm_s2 > limits.hoof_friction * g) {
    std::snprintf(text, sizeof text, "turning at %.0f cm/s² sideways, beyond the %.0f cm/s² (%.1f g) hooves grip at", r.centripetal_cm_s2,
                  limits.hoof_friction * g, limits.hoof_friction);
    r.breaches.emplace_back(HorseLimit::Turn, text);
  }
  return r;
}

}  // namespace stirrup::rig
