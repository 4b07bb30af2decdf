// A horse on a path (issue 15; Kuhnel 2003, section 10: "the rider's directional commands driving the
// horse"): points on the ground joined by a smooth curve (rig/motion/ground_path.h), a speed profile
// (rig/motion/speed_profile.h) whose gait follows the speed with hysteresis, over flat ground or a
// terrain (rig/motion/terrain.h).
//
// How it is built. Everything is first laid out along the path's arc length, as a straight movement
// (rig/motion/movement.h): travel is the distance along the path, stride phase is the integral of
// stride frequency, each gait and canter lead is one oscillation entry blended into the next over
// a stride and a half, and footfalls are found where each hoof's blended phase crosses a whole stride
// (rig/motion/gaits.h), so a transition keeps every hoof planted through its stance and the stride
// phase continuous. The blends are paced (Movement::paced_blends): stances end, swings lift and the
// trunk oscillates so that no channel moves faster than in the steady gaits on either side (issue 15).
// Sampling then bends that straight movement onto the path:
//   - the travel frame stands at the path's point at the travelled distance, heading along its tangent;
//     over a terrain its height and pitch follow the ground under the four rest hoof places;
//   - a hoof at distance a along the straight movement, with a rest place (x, z) in the travel frame,
//     stands on the path at arc length a (a = travel + x + its tx) and z to the side of it: a planted
//     hoof (a fixed) stays put in the world however the frame turns, inside legs step on shorter arcs
//     than outside legs, and its channels are its place seen from the current travel frame (tx and tz
//     move through a stance in a turn; ty stays the lift above the ground under it, which goes to
//     HorseFrame::hoof_ground_cm);
//   - the body rolls into the turn (rearPivot.rx) by atan(v² κ / g), κ the curvature averaged over
//     one stride of path centred on the horse, softly limited to roll_limit_deg;
//   - cantering and galloping, the lead is the inside lead of the turn the horse is in, or of the next
//     turn when on a straight; when the next turn goes the other way the lead changes (a flying change,
//     one stride's blend) on the straight between, centred half a stride after the first turn ends.
// A pure function of time once built; building takes a few milliseconds per second of clip.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "rig/motion/ground_path.h"
#include "rig/motion/movement.h"
#include "rig/motion/speed_profile.h"
#include "rig/motion/terrain.h"

namespace stirrup::rig {

struct PathClipParams {
  std::vector<glm::dvec2> points;               // cm, (world x, world z)
  std::vector<SpeedProfile::Key> speed;         // speed keys over time or distance
  SpeedProfile::Over over = SpeedProfile::Over::Time;
  GaitThresholds thresholds;
  // Roll into a turn: atan(v² κ / g), the lean that puts the resultant of gravity and the centripetal
  // force through the hooves (as Tan and Wilson 2011, "Grip and limb force limits to turning
  // performance in competition horses", Proc. R. Soc. B 278, model a turning horse), limited softly
  // (tanh) to this. 20° is our choice: a canter on an 8 m circle would lean 24° by the formula.
  double roll_limit_deg = 20.0;
  // Curvature (1/cm) above which the horse counts as turning, for the lead: a radius under 30 m.
  double turn_curvature = 1.0 / 3000.0;
  Lead first_lead = Lead::Right;               // on a path without turns
  double variation = 0.0;                      // 0..1, as the other generators
  unsigned seed = 1;
  double max_duration_s = 600.0;               // the clip ends where the path ends, or here
  std::array<glm::dvec2, 4> hoof_rest = kDefaultHoofRest;
};

class PathClip final : public Clip {
 public:
  // Throws rig::InputError "SOURCE: FIELD: ..." (source e.g. "scene.json: clip") for a bad path or
  // speed, or a path the speeds would take longer than max_duration_s to ride. `terrain` null = flat.
  PathClip(PathClipParams params, std::shared_ptr<const Terrain> terrain, const std::string& source);

  std::string name() const override { return "path"; }
  double duration() const override { return movement_.duration_s; }
  HorseFrame sample(double seconds) const override;
  HorseFrame sampleTravel(double seconds) const override;

  // One stretch of steady gait and lead, between the middles of the blends on either side.
  struct Section {
    double start_s = 0, end_s = 0;
    PathGait gait = PathGait::Walk;
    Lead lead = Lead::Right;      // meaningful at the canter and gallop
    double blend_in_s = 0, blend_out_s = 0;  // the blend windows' widths at its start and end (0 at the clip's ends)
  };
  const std::vector<Section>& sections() const { return sections_; }
  const GroundPath& path() const { return path_; }
  const Terrain& terrain() const;
  const Movement& movement() const { return movement_; }
  // Distance along the path at a time (cm) and the body's roll into the turn there (degrees, + right).
  double distanceAt(double seconds) const { return movement_.travelCm(seconds); }
  double turnRollDeg(double seconds) const;
  double speedAt(double seconds) const { return movement_.speed_cm_s.at(seconds); }

 private:
  // The path at arc length s, continued straight along its end tangents beyond either end.
  GroundPath::Sample extended(double s) const;
  double meanCurvature(double s, double half_window_cm) const;
  // Sets f's travel frame for the distance s along the path (sample and sampleTravel share it):
  // travel_cm, travel_z_cm, heading_deg, ground_pitch_deg, ground_y_cm; returns the path there and
  // the ground's pitch in radians.
  GroundPath::Sample placeTravelFrame(double s, HorseFrame& f, double& pitch) const;

  // The constructor's steps.
  struct Turn {  // a run of the path bending one way, for the lead
    double from_cm, to_cm;
    Lead lead;
  };
  void checkTerrainCovers(const std::string& source) const;
  double timeAtDistance(double s) const;  // by the movement's travel
  std::vector<Turn> turnsToLead() const;
  void makeSections(const SpeedProfile& speed, const std::vector<Turn>& turns, double end_s);
  void weighOscillations(const SpeedProfile& speed, std::size_t ramp_steps);

  PathClipParams params_;
  std::shared_ptr<const Terrain> terrain_;
  GroundPath path_;
  Movement movement_;
  std::vector<Section> sections_;
};

}  // namespace stirrup::rig
