// How fast a horse goes along its path (issue 15): speed keys over time or over distance along the
// path (cm/s), and the gait that speed asks for, with hysteresis.
//
// Speeds between keys follow a monotone cubic (Fritsch and Carlson 1980, "Monotone piecewise cubic
// interpolation", SIAM J. Numer. Anal. 17(2)): it never overshoots its keys, so a horse slowing from
// 9 to 2 m/s never dips below 2 on the way, and it is C1, so the acceleration the balance stage reads
// (rig/balance.h) has no steps. Before the first key and after the last the speed holds.
//
// The distance travelled by time t is integrated once at construction (fourth-order Runge-Kutta over
// kStepS) into a table, then interpolated: a pure function of t, the same on every machine.
#pragma once

#include <string>
#include <vector>

namespace stirrup::rig {

class SpeedProfile {
 public:
  enum class Over { Time, Distance };
  struct Key {
    double at = 0;      // seconds (Over::Time) or cm along the path (Over::Distance)
    double speed = 0;   // cm/s, > 0
  };
  // `duration_s`: how long the table covers (the clip's duration). Throws rig::InputError
  // "SOURCE: speed[i]: expected ..." for no keys, a key not after the one before it, a time or distance
  // past kMaxKeyAt, or a speed outside kMinSpeedCmS to kMaxSpeedCmS.
  SpeedProfile(std::vector<Key> keys, Over over, double duration_s, const std::string& source);

  static constexpr double kStepS = 1.0 / 240.0;
  // The speeds and key places a path may hold (our choices): from 1 cm/s (slower is standing still, and
  // 1e-320 would make a ride of forever) to 50 m/s (past any horse: the limits check reports what a horse
  // cannot do); keys within a day's seconds or 100 km along the path.
  static constexpr double kMinSpeedCmS = 1.0, kMaxSpeedCmS = 5000.0;
  static constexpr double kMaxKeyAt = 1e7;

  double speedAtTime(double t) const;      // cm/s
  double distanceAtTime(double t) const;   // cm from the start; t clamped to [0, duration]
  double duration() const { return duration_; }

 private:
  double speedAtKey(double x) const;  // the monotone cubic through the keys, at time or distance x

  std::vector<Key> keys_;
  std::vector<double> slopes_;   // Fritsch-Carlson tangents at the keys
  Over over_;
  double duration_;
  std::vector<double> distance_;  // at t = i * kStepS
};

// The gaits a path clip moves in, slowest first.
enum class PathGait { Walk, Trot, Canter, Gallop };
const char* pathGaitName(PathGait g);

// Speeds (cm/s) where the gait changes, going up and coming down: a horse speeding up changes gait
// at `up`, slowing down at `down`, so a speed hovering near a threshold does not flicker between two
// gaits. Walk-trot: Griffin, Kram, Wickler and Hoyt 2004 ("Biomechanical and energetic determinants of
// the walk-trot transition in horses", J. Exp. Biol. 207) measured 1.6-2.3 m/s across horses of 90 to
// 720 kg, at a Froude number of about 0.35. Trot-canter 4-5 m/s and canter-gallop 7-8 m/s are the
// ranges issue 15 gives; Wickler et al. 2003 (J. Exp. Biol. 206) bracket the trot-gallop change
// between the fastest sustained trot and the slowest sustained gallop, as up and down do here.
struct GaitThresholds {
  double walk_trot_up = 220, walk_trot_down = 180;        // walk-trot about 1.8-2.2 m/s
  double trot_canter_up = 500, trot_canter_down = 400;    // trot-canter about 4-5 m/s
  double canter_gallop_up = 800, canter_gallop_down = 700;  // canter-gallop about 7-8 m/s
};

// The gait at every time of a speed profile, decided once by walking the profile forward from t = 0
// in steps of SpeedProfile::kStepS with the hysteresis above; `changes` holds each change's time.
class GaitSchedule {
 public:
  GaitSchedule(const SpeedProfile& speed, const GaitThresholds& thresholds = {});
  struct Change {
    double time = 0;
    PathGait from = PathGait::Walk, to = PathGait::Walk;
  };
  PathGait gaitAt(double t) const;
  const std::vector<Change>& changes() const { return changes_; }

 private:
  PathGait first_ = PathGait::Walk;
  std::vector<Change> changes_;
};

}  // namespace stirrup::rig
