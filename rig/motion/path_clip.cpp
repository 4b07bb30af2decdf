#include "rig/motion/path_clip.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "rig/error.h"
#include "rig/motion/gaits.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {

constexpr double kBankingGravityCmS2 = 981.0;
// The movement's speed and stride frequency are sampled this often into its piecewise-linear ramps:
// fine enough that the ramps follow the smooth speed profile to well under a millimetre of travel.
constexpr double kRampStepS = 1.0 / 60.0;
// The turn direction for the lead is read along the path this often, and curvature is averaged over
// this much path either side, so a wobble between two points does not count as a turn.
constexpr double kTurnStepCm = 10.0;
constexpr double kTurnSmoothingCm = 100.0;
// How long a gait or lead change blends, in strides of the slower gait. Issue 15 asks for about one.
// Unpaced, the hooves swung up to 28% faster through a walk-trot change than in either steady gait
// at one stride, 17% at a stride and a half; the blends are now paced (Movement::paced_blends) and
// meet the bound at a stride and a half (tests/rig/motion/path_clip_test.cpp,
// TransitionsAreNoFasterThanTheSteadyGaits).
constexpr double kBlendStrides = 1.5;
// A mesh terrain is checked under the path every kCoverageStepCm, out to the hooves' reach ahead of,
// behind and beside the travel frame (the default horse's hooves, with room for a stride's swing).
constexpr double kCoverageStepCm = 25.0;
constexpr double kHoofReachCm = 150.0;
constexpr double kHoofReachSideCm = 30.0;
// A turn the lead follows changes the heading by at least this much (degrees).
constexpr double kMinTurnDeg = 20.0;
// The rear pivot's height above the ground in the default horse (its root joint, 128 cm): the body
// leans into a turn about the ground under it, so the pivot moves in by this times sin(roll).
constexpr double kPivotHeightCm = 128.0;

bool hasLead(PathGait g) { return g == PathGait::Canter || g == PathGait::Gallop; }

GaitParams gaitParams(PathGait g, Lead lead, double speed_cm_s) {
  switch (g) {
    case PathGait::Walk: return walkParams();
    case PathGait::Trot: return trotParams();
    case PathGait::Canter: return canterParams(lead);
    case PathGait::Gallop: return gallopParams(std::max(speed_cm_s, 900.0), lead);
  }
  return trotParams();
}

struct Event {
  double time = 0;
  bool is_gait = true;
  PathGait gait = PathGait::Walk;
  Lead lead = Lead::Right;
};

}  // namespace

PathClip::PathClip(PathClipParams params, std::shared_ptr<const Terrain> terrain, const std::string& source)
    : params_(std::move(params)), terrain_(std::move(terrain)), path_(params_.points, source) {
  const double length = path_.length();
  if (terrain_ && terrain_->triangles()) checkTerrainCovers(source);
  // How long the speed profile needs to be tabled: the path at the slowest key's speed, and a margin.
  double slowest = 0.0;
  for (const auto& k : params_.speed) slowest = slowest == 0.0 ? k.speed : std::min(slowest, k.speed);
  const double table_s = slowest > 0.0 && std::isfinite(slowest)
                             ? std::min(params_.max_duration_s, length / slowest + 1.0)
                             : 1.0;
  const SpeedProfile speed(params_.speed, params_.over, table_s, source);

  // The ramps: speed sampled from the profile; travel is their exact integral.
  Movement& m = movement_;
  m.name = "path";
  m.speed_cm_s = Ramp();
  const auto steps = static_cast<std::size_t>(std::ceil(table_s / kRampStepS));
  for (std::size_t i = 0; i <= steps; ++i) {
    const double t = double(i) * kRampStepS;
    m.speed_cm_s.add(t, speed.speedAtTime(t));
  }
  if (m.travelCm(double(steps) * kRampStepS) < length)
    throw InputError(source + ": speed: expected speeds that ride the whole path (" + numberText(length) +
                     " cm) within " + numberText(params_.max_duration_s) + " s");
  const double end_s = std::min(timeAtDistance(length), params_.max_duration_s);
  m.duration_s = end_s;

  makeSections(speed, turnsToLead(), end_s);
  weighOscillations(speed, steps);
  m.variation = params_.variation;
  m.seed = params_.seed;
  m.paced_blends = true;  // issue 15: no channel faster through a transition than in the steady gaits

  GaitTimeline timeline;
  timeline.variation = params_.variation;
  timeline.seed = params_.seed;
  for (int hoof = 0; hoof < 4; ++hoof)
    m.hooves[std::size_t(hoof)] = scanFootfalls(m, timeline, hoof, -2.0, end_s + 2.0, 1e9);
}

// A mesh terrain must be under every hoof the whole way: the path and its hooves' reach.
void PathClip::checkTerrainCovers(const std::string& source) const {
  const double length = path_.length();
  for (double d = -kHoofReachCm; d <= length + kHoofReachCm; d += kCoverageStepCm)
    for (const double side : {-kHoofReachSideCm, 0.0, kHoofReachSideCm}) {
      const GroundPath::Sample at = extended(d);
      const glm::dvec2 q = at.position + glm::dvec2{-at.tangent.y, at.tangent.x} * side;
      if (!terrain_->covers(q.x, q.y))
        throw InputError(source + ": points: expected the path over the terrain mesh, but it leaves it near (" +
                         numberText(std::round(q.x)) + ", " + numberText(std::round(q.y)) + ") cm");
    }
}

double PathClip::timeAtDistance(double s) const {
  double a = 0.0, b = 1.0;
  while (movement_.travelCm(b) < s) b *= 2.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (a + b);
    (movement_.travelCm(mid) < s ? a : b) = mid;
  }
  return 0.5 * (a + b);
}

// Turns along the path, for the lead: runs of one curvature sign above the threshold.
std::vector<PathClip::Turn> PathClip::turnsToLead() const {
  const double length = path_.length();
  std::vector<Turn> turns;
  for (double s = 0.0; s <= length; s += kTurnStepCm) {
    const double k = meanCurvature(s, kTurnSmoothingCm);
    if (std::abs(k) < params_.turn_curvature) continue;
    const Lead lead = k > 0.0 ? Lead::Right : Lead::Left;
    if (!turns.empty() && turns.back().lead == lead && s - turns.back().to_cm <= kTurnStepCm * 1.5)
      turns.back().to_cm = s;
    else
      turns.push_back({s, s, lead});
  }
  // A run that turns the horse by less than kMinTurnDeg is a wobble of the curve (a spline bends a
  // little at its ends and between points), not a turn to lead into.
  std::erase_if(turns, [this](const Turn& t) {
    return std::abs(std::remainder(path_.at(t.to_cm).heading_deg - path_.at(t.from_cm).heading_deg, 360.0)) < kMinTurnDeg;
  });
  for (std::size_t i = 1; i < turns.size();)
    if (turns[i].lead == turns[i - 1].lead) turns[i - 1].to_cm = turns[i].to_cm, turns.erase(turns.begin() + long(i));
    else ++i;
  return turns;
}

// The sections: a new one wherever the gait changes, or the lead changes at the canter or gallop.
void PathClip::makeSections(const SpeedProfile& speed, const std::vector<Turn>& turns, double end_s) {
  // Events in time: gait changes from the schedule, lead changes on the straights between turns that
  // go opposite ways (centred half a stride after the first ends, or mid-straight if it is shorter).
  const GaitSchedule schedule(speed, params_.thresholds);
  std::vector<Event> events;
  for (const auto& c : schedule.changes())
    if (c.time < end_s) events.push_back({c.time, true, c.to, Lead::Right});
  for (std::size_t i = 1; i < turns.size(); ++i) {
    if (turns[i].lead == turns[i - 1].lead) continue;
    const double exit_s = timeAtDistance(turns[i - 1].to_cm), entry_s = timeAtDistance(turns[i].from_cm);
    const double stride_s = 1.0 / gaitParams(schedule.gaitAt(exit_s), turns[i].lead, speed.speedAtTime(exit_s)).stride_hz;
    double centre = exit_s + 0.5 * stride_s;
    if (centre + 0.5 * stride_s > entry_s) centre = 0.5 * (exit_s + entry_s);
    if (centre < end_s) events.push_back({centre, false, PathGait::Walk, turns[i].lead});
  }
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.time < b.time; });

  PathGait gait = schedule.gaitAt(0.0);
  Lead lead = turns.empty() ? params_.first_lead : turns.front().lead;
  sections_.push_back({0.0, end_s, gait, lead, 0.0, 0.0});
  for (const Event& e : events) {
    const PathGait new_gait = e.is_gait ? e.gait : gait;
    const Lead new_lead = e.is_gait ? lead : e.lead;
    const bool split = new_gait != gait || (hasLead(new_gait) && new_lead != lead);
    gait = new_gait;
    lead = new_lead;
    if (!split) {
      sections_.back().lead = hasLead(sections_.back().gait) ? sections_.back().lead : lead;
      continue;
    }
    // A stride and a half of the slower of the two gaits (kBlendStrides).
    const double f0 = gaitParams(sections_.back().gait, sections_.back().lead, speed.speedAtTime(e.time)).stride_hz;
    const double f1 = gaitParams(gait, lead, speed.speedAtTime(e.time)).stride_hz;
    const double blend = kBlendStrides / std::min(f0, f1);
    sections_.back().end_s = e.time;
    sections_.back().blend_out_s = blend;
    sections_.push_back({e.time, end_s, gait, lead, blend, 0.0});
  }
  // Blends never overlap: each takes at most 45% of the sections on either side.
  for (std::size_t i = 1; i < sections_.size(); ++i) {
    const double room = 0.9 * std::min(sections_[i - 1].end_s - sections_[i - 1].start_s,
                                       sections_[i].end_s - sections_[i].start_s);
    const double blend = std::min(sections_[i].blend_in_s, room);
    sections_[i].blend_in_s = sections_[i - 1].blend_out_s = blend;
  }
}

// One oscillation entry per section, weighted in and out across its blends, and the stride frequency
// blended with the same weights over the ramps' `steps`.
void PathClip::weighOscillations(const SpeedProfile& speed, std::size_t steps) {
  Movement& m = movement_;
  m.oscillation.clear();
  for (std::size_t i = 0; i < sections_.size(); ++i) {
    const Section& sec = sections_[i];
    const double mid_speed = speed.speedAtTime(0.5 * (sec.start_s + sec.end_s));
    Keys w;
    if (i == 0) w.add(sec.start_s, 1.0);
    else w.add(sec.start_s - 0.5 * sec.blend_in_s, 0.0).add(sec.start_s + 0.5 * sec.blend_in_s, 1.0);
    if (i + 1 < sections_.size())
      w.add(sec.end_s - 0.5 * sec.blend_out_s, 1.0).add(sec.end_s + 0.5 * sec.blend_out_s, 0.0);
    m.oscillation.push_back({gaitParams(sec.gait, sec.lead, mid_speed), w});
  }
  m.stride_hz = Ramp();
  for (std::size_t i = 0; i <= steps; ++i) {
    const double t = double(i) * kRampStepS;
    double sum = 0.0, total = 0.0;
    for (const auto& [g, w] : m.oscillation) {
      const double x = w.at(t);
      sum += x * g.stride_hz;
      total += x;
    }
    m.stride_hz.add(t, total > 0.0 ? sum / total : m.oscillation.front().first.stride_hz);
  }
}

const Terrain& PathClip::terrain() const {
  static const Terrain flat;
  return terrain_ ? *terrain_ : flat;
}

GroundPath::Sample PathClip::extended(double s) const {
  const double length = path_.length();
  GroundPath::Sample p = path_.at(std::clamp(s, 0.0, length));
  if (s < 0.0 || s > length) {
    p.position += p.tangent * (s < 0.0 ? s : s - length);
    p.curvature = 0.0;
  }
  return p;
}

double PathClip::meanCurvature(double s, double half_window_cm) const {
  // Curvature is the heading's rate along the path, so its mean over the window is exactly the
  // heading's change across it: continuous in s, though the spline's curvature steps at its points.
  const double turn_deg = std::remainder(extended(s + half_window_cm).heading_deg - extended(s - half_window_cm).heading_deg, 360.0);
  return turn_deg / kDegreesPerRadian / (2.0 * half_window_cm);
}

double PathClip::turnRollDeg(double t) const {
  const double v = movement_.speed_cm_s.at(t), f = movement_.stride_hz.at(t);
  const double k = meanCurvature(movement_.travelCm(t), 0.5 * v / f);
  const double roll = std::atan(v * v * k / kBankingGravityCmS2) * kDegreesPerRadian;
  const double limit = params_.roll_limit_deg;
  return limit > 0.0 ? limit * std::tanh(roll / limit) : 0.0;
}

GroundPath::Sample PathClip::placeTravelFrame(double s, HorseFrame& f, double& pitch) const {
  const GroundPath::Sample here = extended(s);
  const glm::dvec2 ahead = here.tangent, right{-here.tangent.y, here.tangent.x};
  const Terrain& ground = terrain();

  // The travel frame over the ground: height and pitch from the ground under the rest hoof places.
  double fore_h = 0, hind_h = 0, fore_x = 0, hind_x = 0;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec2 r = params_.hoof_rest[std::size_t(i)];
    const glm::dvec2 w = here.position + ahead * r.x + right * r.y;
    const double h = ground.height(w.x, w.y);
    (i < 2 ? fore_h : hind_h) += 0.5 * h;
    (i < 2 ? fore_x : hind_x) += 0.5 * r.x;
  }
  pitch = std::atan2(fore_h - hind_h, fore_x - hind_x);
  f.travel_cm = here.position.x;
  f.travel_z_cm = here.position.y;
  f.heading_deg = here.heading_deg;
  f.ground_pitch_deg = pitch * kDegreesPerRadian;
  f.ground_y_cm = hind_h + (fore_h - hind_h) * (0.0 - hind_x) / (fore_x - hind_x);
  return here;
}

HorseFrame PathClip::sampleTravel(double t) const {
  // The travel as sampleMovement finds it (the distance along the path), without legs or trunk.
  HorseFrame f;
  double pitch = 0.0;
  placeTravelFrame(movement_.travelCm(t), f, pitch);
  return f;
}

HorseFrame PathClip::sample(double t) const {
  HorseFrame f = sampleMovement(movement_, t);
  const double s = f.travel_cm;
  double pitch = 0.0;
  const GroundPath::Sample here = placeTravelFrame(s, f, pitch);
  const glm::dvec2 ahead = here.tangent, right{-here.tangent.y, here.tangent.x};
  const Terrain& ground = terrain();
  const double cp = std::cos(pitch), sp = std::sin(pitch);

  // Each hoof at its place along the path, seen from the travel frame.
  using C = HorseChannel;
  static constexpr std::array<std::array<C, 2>, 4> kTxTz = {{{C::lfHoofTx, C::lfHoofTz},
                                                              {C::rfHoofTx, C::rfHoofTz},
                                                              {C::lbHoofTx, C::lbHoofTz},
                                                              {C::rbHoofTx, C::rbHoofTz}}};
  for (std::size_t i = 0; i < 4; ++i) {
    const glm::dvec2 r = params_.hoof_rest[i];
    const GroundPath::Sample at = extended(s + r.x + f.controls[kTxTz[i][0]]);
    const glm::dvec2 place = at.position + glm::dvec2{-at.tangent.y, at.tangent.x} * r.y;
    const glm::dvec2 d = place - here.position;
    const double lx = glm::dot(d, ahead), lz = glm::dot(d, right);
    const double ly = ground.height(place.x, place.y) - f.ground_y_cm;
    f.controls[kTxTz[i][0]] = lx * cp + ly * sp - r.x;
    f.controls[kTxTz[i][1]] = lz - r.y;
    f.hoof_ground_cm[i] = -lx * sp + ly * cp;
  }

  // Lean into the turn about the ground under the pivot.
  const double roll = turnRollDeg(t);
  const double roll_rad = roll / kDegreesPerRadian;
  f.controls[C::rearPivotRx] += roll;
  f.controls[C::rearPivotTz] += kPivotHeightCm * std::sin(roll_rad);
  f.controls[C::rearPivotTy] -= kPivotHeightCm * (1.0 - std::cos(roll_rad));
  return f;
}

}  // namespace stirrup::rig
