// The horse movements of Kuhnel 2003 section 5 as parameterised generators: steady gaits (walk, trot,
// canter, gallop), a gait sequence with phase-continuous transitions, the sliding stop, the jump, the
// rear and the buck. Defaults follow docs/gait-reference.md; each builder returns a Movement
// whose footfall schedule and trunk curves are fixed at construction (rig/motion/movement.h samples them).
#pragma once

#include <string>
#include <vector>

#include "rig/motion/gaits.h"
#include "rig/motion/movement.h"

namespace stirrup::rig {

struct Variation {
  double amount = 0.1;  // 0 = exactly periodic; 1 = strong (lift ±15%, landing ±2 cm, trunk ±25%)
  unsigned seed = 1;
};

// A steady gait, `duration_s` long, through the footfall scheduler (use ProceduralGait for the exactly
// periodic closed form).
Movement makeSteadyGait(const GaitParams& gait, double duration_s, Variation v = {});

// Gaits one after another, `segment_s` each, blended over `blend_s`.
Movement makeGaitSequence(const std::vector<GaitParams>& gaits, double segment_s, double blend_s,
                          Variation v = {});

// gait-reference / Kuhnel 5.5: the hind legs lock under the body and slide (the one place a hoof that
// is down moves in the world), the forelegs keep stepping, back rounded, croup lowered, front up.
struct StopParams {
  double entry_speed_cm_s = 900.0;  // gallop (gait-reference: 9 m/s, Witte 2006)
  double entry_s = 1.5;             // gallop before the stop
  double slide_s = 1.6;             // slide ≈ speed x slide_s / 2 = 7.2 m (gait-reference: up to ≈ 10 m)
  double hind_under_cm = 45.0;      // hind hooves drawn forward under the body
  double croup_drop_cm = 40.0;      // rear pivot lowered while sliding
  double pitch_deg = 8.0;           // front end up
  double fore_lift_cm = 12.0;
  double settle_s = 1.4;            // standing after the slide
  Lead lead = Lead::Right;
};
Movement makeStop(const StopParams& p, Variation v = {});
// A gait sequence that ends in the sliding stop from its last gait.
Movement makeGaitSequenceToStop(const std::vector<GaitParams>& gaits, double segment_s, double blend_s,
                                const StopParams& p, Variation v = {});

// Kuhnel 5.1 / gait-reference (Colborne et al. 1995): approach, take-off, flight, landing, recovery.
struct JumpParams {
  double fence_height_cm = 90.0;
  double approach_speed_cm_s = 600.0;  // canter
  int approach_strides = 3;
  int recovery_strides = 3;
  double takeoff_pitch_deg = 21.4;     // gait-reference: trunk 21.4 ± 2.5° at lift-off of the leading hind
  double landing_pitch_deg = -14.0;
  // Legs folded in flight: hoof height above the ground as the body would stand (forehoof near the
  // elbow, hind hoof under the flexed hock). ≈: no measurement in gait-reference.
  double fore_tuck_cm = 70.0;
  double hind_tuck_cm = 55.0;
  double clearance_cm = 15.0;
  Lead lead = Lead::Right;
};
Movement makeJump(const JumpParams& p, Variation v = {});
// The time of take-off and of the first fore touchdown of a jump built from p.
struct JumpTimes {
  double takeoff_s = 0.0, landing_s = 0.0, apex_cm = 0.0;
};
// The fence stands where the horse is at the top of its flight (Obstacle::travel_cm).
JumpTimes jumpTimes(const JumpParams& p);

// Kuhnel 5.4 / gait-reference: trunk pitched 40–70° on the hind legs, held 0.5–2 s, forelegs up.
struct RearParams {
  double angle_deg = 55.0;
  double rise_s = 0.8;
  double hold_s = 1.2;
  double descend_s = 0.7;
  double hind_under_cm = 25.0;
  double shoulder_cm = 120.0;  // hips to shoulders: how far the forehand swings up and back
  // Kuhnel 5.4: "to stay up in the air longer it will often use a kicking motion to aid balance".
  int paw_strokes = 2;          // strokes of each foreleg while held up (0: held still)
  double paw_cm = 16.0;         // reach of a stroke. ≈: no measurement in gait-reference
};
Movement makeRear(const RearParams& p, Variation v = {});
struct RearTimes {
  double hold_start_s = 0.0, hold_end_s = 0.0;
};
RearTimes rearTimes(const RearParams& p);

// Kuhnel 5.6 / gait-reference: head down, back arched, all four legs leave the ground, croup up
// −20..−35°, hind kick 0.3–0.5 s, some twist. Each buck: the forehand rises, the hind legs push off
// before the forelegs land (a leap with all four hooves in the air), then the forelegs plant while the
// croup goes up and the hind legs kick back.
struct BuckParams {
  int bucks = 3;
  double period_s = 1.1;
  double croup_deg = -28.0;
  double kick_s = 0.4;
  double kick_lift_cm = 55.0;
  double twist_deg = 8.0;
  double front_rise_deg = 12.0;
  double leap_s = 0.12;  // the hind hooves leave this long before the left fore lands
};
// When things happen in buck number `buck` (0-based), in seconds from the clip's start.
struct BuckTimes {
  double start_s = 0.0;        // the forehand starts to rise
  double hind_off_s = 0.0;     // the left hind leaves the ground: the leap begins
  double fore_land_s = 0.0;    // the left fore lands: the leap ends
  double croup_peak_s = 0.0;   // the croup is highest, the hind legs kicked out
  double hind_land_s = 0.0;    // the left hind lands again
};
BuckTimes buckTimes(const BuckParams& p, int buck);
Movement makeBuck(const BuckParams& p, Variation v = {});

}  // namespace stirrup::rig
