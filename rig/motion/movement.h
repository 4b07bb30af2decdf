// A movement clip: a horse motion assembled from a footfall schedule (per hoof, when it is down and
// where it stands in the world), a travel speed over time, and trunk curves. Generators build the
// schedule once (rig/motion/gaits.h, rig/motion/movement_clips.h); sampling is then a pure function of time, so any
// frame can be evaluated alone.
//
// Hooves that are down stay put in the world (tx = world place - travel), unless the footfall is marked
// `slides` (the hind hooves of a sliding stop: they ride along with the body). In the air a hoof moves
// from one footfall to the next along a Hermite curve whose end velocities match the stance, so it
// leaves and meets the ground without a velocity pop.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "rig/clip.h"
#include "rig/motion/procedural_gait.h"

namespace stirrup::rig {

// A piecewise-linear function of time (constant outside its keys) with its exact integral, so travel
// and stride phase are closed-form integrals of speed and stride frequency.
class Ramp {
 public:
  Ramp() = default;
  explicit Ramp(double constant) { keys_.push_back({0.0, constant}); }
  void add(double t, double v);  // keys must be added in increasing t
  double at(double t) const;
  double integral(double t) const;  // ∫_0^t at(u) du (negative for t < 0)

 private:
  double piece(double a, double b) const { return 0.5 * (at(a) + at(b)) * (b - a); }
  std::vector<std::pair<double, double>> keys_;
  // ∫_0^key at each key after 0, summed piece by piece in time order (so a lookup gives the same bits
  // as summing the pieces up to t one by one): a path clip's ramps have a key every few frames and
  // its footfall scan asks for thousands of integrals.
  std::vector<double> area_to_key_;
};

// A smooth keyed curve: values at times, eased between keys (smoothstep, zero slope at each key), so
// a held pose has no overshoot and every curve is C1. Zero when empty.
class Keys {
 public:
  Keys& add(double t, double v);  // keys must be added in increasing t
  double at(double t) const;
  bool empty() const { return keys_.empty(); }

 private:
  std::vector<std::pair<double, double>> keys_;
};

// How a hoof travels in the air after a footfall, to the next one.
struct SwingShape {
  double lift_cm = 10.0;   // peak height above the straight path
  double plateau = 0.0;    // fraction of the swing held at the peak (0 = arc, e.g. 0.6 = legs held up)
  double reach_cm = 0.0;   // extra forward (+) or backward (-) excursion at the peak (tuck, kick)
  bool carried = false;    // rides on the flight elevation (jump): height above ground includes it
  // Strokes while held at the peak (a rearing horse paws the air): circles of radius paw_cm, faded in
  // and out over the plateau so the hoof stays C1; paw_phase (0..1) offsets one leg from the other.
  double paw_cm = 0.0;
  int paw_strokes = 0;
  double paw_phase = 0.0;
};

struct Footfall {
  double down_s = 0.0;     // touchdown time
  double up_s = 0.0;       // lift-off time (> down_s)
  double x_cm = 0.0;       // world place along the travel direction while down
  bool slides = false;     // while down the hoof rides with the body at tx = slide_tx_cm (sliding stop)
  double slide_tx_cm = 0.0;
  SwingShape swing;        // the flight that follows this footfall
};

using HoofSchedule = std::vector<Footfall>;  // sorted by time, not overlapping

struct Movement {
  std::string name;
  double duration_s = 1.0;
  Ramp speed_cm_s{0.0};
  Ramp stride_hz{1.0};
  std::array<HoofSchedule, 4> hooves;  // indexed by Hoof
  // Gaits whose trunk oscillation plays, each with a weight over time (blends sum to 1).
  std::vector<std::pair<GaitParams, Keys>> oscillation;
  Keys oscillation_gain;                // scales all oscillation (empty = 1); fades it for a jump
  double variation = 0.0;               // 0..1: seeded, smooth amplitude variation of the trunk
  unsigned seed = 0;
  // Blends paced to the steady gaits (a path clip's transitions, issue 15: no channel faster than in
  // the steady gaits on either side). A gait playing above its own stride frequency, as the slower gait
  // does through a blend, scales its trunk oscillation by its frequency over the one playing, so its
  // channels keep their steady speed rather than their amplitude; footfalls pace their swings
  // (scanFootfalls, rig/motion/gaits.h). Without it a blend mixes the gaits as they are.
  bool paced_blends = false;
  // Keyed offsets added to channels (rearPivot, backMid; hoof channels are ignored) and body parts.
  std::array<Keys, kHorseChannelCount> channel_keys;
  Keys neck_rz, head_rz, tail_rz, tail_ry;
  std::vector<Obstacle> obstacles;      // the jump's fence
  // Ballistic flight (jump): the body follows a parabola between take-off and landing.
  double flight_start_s = 0.0, flight_end_s = 0.0, flight_apex_cm = 0.0;

  double travelCm(double t) const { return speed_cm_s.integral(t); }
  double stridePhase(double t) const { return stride_hz.integral(t); }
  double flightElevationCm(double t) const;
};

HorseFrame sampleMovement(const Movement& m, double seconds);

class MovementClip final : public Clip {
 public:
  explicit MovementClip(Movement m);
  std::string name() const override { return movement_.name; }
  double duration() const override { return movement_.duration_s; }
  HorseFrame sample(double seconds) const override { return sampleMovement(movement_, seconds); }
  std::vector<Obstacle> obstacles() const override { return movement_.obstacles; }
  const Movement& movement() const { return movement_; }

 private:
  Movement movement_;
};

}  // namespace stirrup::rig
