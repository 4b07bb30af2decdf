// Limits a horse has (issue 36): how fast it runs, how hard it speeds up and slows down, how tight it
// turns at a speed, how steep a grade it climbs or descends, and how steep the ground under one hoof
// may be. A path clip (rig/motion/path_clip.h) is checked against them when its scene loads, so "a
// path of 20 cm hairpins at 1500 cm/s" or "hills of 5000 cm amplitude at 100 cm wavelength" is a
// one-line error naming the scene, the field, the path segment and time, the value and the limit,
// instead of a horse whose legs stretch like rubber. docs/horse-limits.md explains each figure.
//
// Every limit is an upper bound on what horses have been measured or estimated to do: a shot inside
// them may still look wrong, a shot outside them cannot be right. [C] marks a figure measured in the
// source; [E] an estimate made from it (the source's own numbers do not give the bound directly).
//
// How a path is checked. The path is sampled every kSampleStepCm of arc length; at each sample the
// time the horse gets there (the speed profile's), its speed and acceleration, the curvature averaged
// over the horse's length (fore to hind hooves: a body cannot turn tighter than it is long, and the
// spline's own curvature steps at its points), the grade of the ground between its fore and hind
// hooves, and the steepest ground under a hoof's footprint on either hoof track are read. A run of
// samples over one limit is one breach, reported from where it starts with its worst value.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "rig/motion/path_clip.h"

namespace stirrup::rig {

struct HorseLimits {
  static constexpr double kGravityCmS2 = 981.0;
  // Top speed [C]: 70.76 km/h = 1966 cm/s, the fastest recorded (Winning Brew, 2008, over two
  // furlongs; the Jockey Club's record); race tracking of 3,357 races found speeds above 19 m/s
  // (Spence et al.). No horse has been timed faster: a path asking more is refused.
  double top_speed_cm_s = 1966.0;
  // Speeding up [E] (Williams, Tan, Usherwood and Wilson 2009, "Pitch then power: limitations to
  // acceleration in quadrupeds", Biol. Lett. 5:610): at low speed polo ponies accelerate at most as
  // hard as they can without pitching nose up, about 0.5-0.6 g; at high speed muscle power limits
  // them, so the bound falls with speed. We take a = min(0.6 g, P / v), the power-limited part with a
  // mass-specific power P (W/kg) at which a horse reaches 15 m/s from a stand in 5 s, the quickest of
  // the 5-7 s estimated: P = 24.2 W/kg = 242 000 cm²/s³, so 3.0 m/s² remain at 8 m/s and 0.13 g at
  // top speed, where the estimate falls towards 0.1 g.
  double max_accel_g = 0.6;
  double seconds_to_15_m_s = 5.0;
  // The power P that reaches 15 m/s from a stand in seconds_to_15_m_s under a = min(a0, P / v).
  double accelPowerCm2S3() const;
  // Slowing down [E] (the same paper): braking is limited by pitching tail up, at most about 0.7-0.9 g.
  double max_decel_g = 0.9;
  // Turning [E] (Tan and Wilson 2011, "Grip and limb force limits to turning performance in
  // competition horses", Proc. R. Soc. B 278:2105): in tight polo turns the heading's rate falls as
  // speed rises as hoof-ground friction capping the centripetal force predicts, v²/r ≤ μ g. The paper
  // does not give μ as a bound; 0.6-0.8 is the estimate for hooves on grass, and we take its top:
  // 0.8 g = 785 cm/s² (at 8 m/s, a radius of 8 m). Large fast bends are limited by limb force first
  // (horses slow on them); that is not checked here.
  double hoof_friction = 0.8;
  // Grades [E] from the USDA Forest Service's Equestrian Design Guidebook (Hancock et al. 2007: horses
  // "easily can master steady grades steeper than 10 percent - even 20 percent") and riders' reports
  // of 20% trail climbs with steeper short pitches: a short ridden climb up to 35°. Descents: walked
  // down to about 30°, slid down soft ground sitting back to 40-45° (the Italian cavalry at Tor di
  // Quinto, 1906 photographs); we refuse beyond 45°.
  double max_climb_deg = 35.0;
  double max_descent_deg = 45.0;
  // Cantering and galloping [E]: a horse is not cantered up or down a grade steeper than about 20°
  // (the same sources: steep pitches are walked).
  double max_canter_grade_deg = 20.0;
  // Footing [E]: no ground under one hoof may be steeper than the steepest a horse stands on at all
  // (the descent limit), measured across the hoof's footprint in any direction.
  double max_footing_deg = 45.0;
  // The default horse's hoof: 2 × its hoof_radius of 6 cm (rig/characters/horse_character.h).
  double hoof_footprint_cm = 12.0;
  // Each gait's top speed (issue 49), for the generated gaits (walk, trot, canter, gallop and the
  // movements' approach speeds; a path picks its gait from its speed, so only its top speed applies).
  // Walk [E]: horses change to the trot at 1.6-2.3 m/s, at a Froude number of 0.35 (Griffin, Kram,
  // Wickler and Hoyt 2004, "Biomechanical and energetic determinants of the walk-trot transition in
  // horses", J. Exp. Biol. 207:4215); a walk held past the fastest of them tops out near 2.5 m/s.
  double max_walk_cm_s = 250.0;
  // Trot [C]: the fastest trotted mile, 1:48.4 (Homicide Hunter, 2018, a harness trotter; Standardbred
  // Canada), 1609.344 m / 108.4 s = 14.85 m/s.
  double max_trot_cm_s = 1485.0;
  // Canter [E]: horses change from the canter to the gallop at 7-8 m/s (docs/paths-and-terrain.md,
  // "Gait"), and a ridden canter is estimated to reach 8-10 m/s; faster is a gallop.
  double max_canter_cm_s = 1000.0;
  // Gallop: top_speed_cm_s, the record.
};

// Which limit a breach breaks.
enum class HorseLimit { Speed, Acceleration, Deceleration, Turn, Climb, Descent, CanterGrade, Footing };
const char* horseLimitName(HorseLimit limit);  // "speed", "acceleration", ..., "footing"

struct LimitBreach {
  HorseLimit limit = HorseLimit::Speed;
  // The field to change: "speed" or "points" of the path (after its clip field), or the scene's "terrain".
  std::string field;
  int segment = 0;        // path segment (points[i] to points[i + 1]) where the run starts
  double time_s = 0;      // when the run starts
  double distance_cm = 0; // where along the path it starts
  // The worst sample of the run (the largest value / limit) and its limit, in the units of the text.
  double value = 0, bound = 0;
  double speed_cm_s = 0;  // the speed there
  std::string text;       // "segment 3 from 2.41 s: ...", one line
};

// A generated gait's speed (a steady gait's speed_cm_s, the stop's entry_speed_cm_s, the jump's
// approach_speed_cm_s, a sequence's gaits): the clip's field that sets it, the gait it is ridden at
// (walk, trot, canter or gallop) and the speed.
struct GaitSpeed {
  std::string field;
  std::string gait;
  double speed_cm_s = 0;
};
// A gait's speed beyond what horses do at that gait: the speed, the gait's top speed and where it comes
// from (HorseLimits::max_walk_cm_s ... top_speed_cm_s).
struct GaitSpeedBreach {
  GaitSpeed speed;
  double bound_cm_s = 0;
  std::string verb;    // "walks"
  std::string source;  // a few words
  // "900 cm/s is faster than a horse walks (at most 250 cm/s: SOURCE" + `then` + ")": one line.
  std::string text(const std::string& then = "") const;
};
// The breach, or nullopt when the speed is within its gait's limit (or the gait is not one of the four).
std::optional<GaitSpeedBreach> gaitSpeedBreach(const GaitSpeed& speed, const HorseLimits& limits = {});

// The limits read along one path. Built once (a few milliseconds for a minute of path); then lookups.
class PathLimitCheck {
 public:
  // `file` names the scene and `clip_field` the path's clip in it ("clip", "crowd.pairs[3]") in
  // messages. Throws rig::InputError for a path or speed the path clip itself refuses. `terrain`
  // null = flat.
  PathLimitCheck(const PathClipParams& params, const Terrain* terrain, std::string file, std::string clip_field,
                 const HorseLimits& limits = {});

  static constexpr double kSampleStepCm = 5.0;
  // A path longer than kMaxSamples × kSampleStepCm (10 km) is sampled more coarsely, so the table stays
  // within a few tens of megabytes.
  static constexpr int kMaxSamples = 200000;

  // One entry per run of samples over a limit, in order of time (then of HorseLimit).
  const std::vector<LimitBreach>& breaches() const { return breaches_; }
  // The breach furthest beyond its limit (the largest value / limit; the earliest of equals), or null
  // when the path is inside every limit.
  const LimitBreach* worst() const;
  // "FILE: CLIP.FIELD: TEXT" (or "FILE: terrain: under CLIP.points, TEXT") of the worst breach, ""
  // when there is none: the error a scene beyond a limit is refused with.
  std::string error() const;
  std::string errorText(const LimitBreach& b) const;
  // The limits broken between t0 and t1 (seconds), the worst sample of each, for a frame's warning.
  std::vector<LimitBreach> during(double t0, double t1) const;
  const std::string& clipField() const { return clip_field_; }

 private:
  struct Sample {
    double s = 0, t = 0, v = 0;
    int segment = 0;
    std::array<double, 8> value{}, bound{};  // by HorseLimit; bound 0 = not applicable here
    double radius_cm = 0;                    // the turn's radius (averaged curvature)
  };
  LimitBreach breachAt(HorseLimit limit, const Sample& start, const Sample& worst) const;

  std::string file_, clip_field_;
  HorseLimits limits_;
  std::vector<Sample> samples_;
  std::vector<LimitBreach> breaches_;
};

// A clip's own travel against the same limits, for a clip with no path to read (a glTF clip from another
// tool): the travel frame's speed, its rate along the heading, and the centripetal acceleration of its
// turning (speed × the heading's rate), each from differences over kTravelWindowS either side of the
// time (a hand-keyed or captured root jitters from frame to frame; half a second is a trot stride).
struct TravelLimits {
  static constexpr double kTravelWindowS = 0.25;
  double time_s = 0, speed_cm_s = 0, accel_cm_s2 = 0, centripetal_cm_s2 = 0;
  // The limits broken at this time: (limit, one line with the value and the bound).
  std::vector<std::pair<HorseLimit, std::string>> breaches;
};
TravelLimits travelLimitsAt(const Clip& clip, double time_s, const HorseLimits& limits = {});

}  // namespace stirrup::rig
