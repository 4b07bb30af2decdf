// A rig profile: every weight, offset and limit of the rider rig (Kuhnel 2003, section 8 and
// Appendix B) as a named parameter, so a profile file can retune the rider without touching code.
// Each parameter's JSON key is `eqN.name` (or `knee.` / `hair.` / `cloth.` for the Appendix B drives
// that have no equation number); the key table with its citations lives in rig_profile.cpp and is
// documented in docs/rider-rig.md. RigProfile::thesis() holds the values the thesis used, with the
// contradictions between prose and code decided as that document's table says.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace stirrup::rig {

struct RigProfile {
  std::string name = "thesis";
  std::string doc;
  // Units: horse translations (cm) are divided by horse_unit_cm before the thesis's expressions;
  // rider translations come out in rider units and rider_unit_cm maps them to cm for posing.
  double horse_unit_cm = 10, rider_unit_cm = 10;

  // Equation 1: lowerBack.rz (lean forward).
  struct LowerBackPitch {
    double w1_pivot_pitch = 0.07;   // x rearPivot.rz x (rearPivot.ty + h1)
    double h1_pivot_height = 2;     // added to the rear pivot height
    double w2_front_reach = 0.25;   // x (mean front hoof tx - rearPivot.tx)
    double w3_hind_reach = 0.25;    // x (rearPivot.tx - mean hind hoof tx)
    double w4_pivot_pitch_gain = 0.1;
    double h2_pivot_pitch = 5;      // added to |rearPivot.rz|
    double w5_front_height = 0.9;
    double w6_hind_height = 0.4;
    double w7_hoof_height = 0.4;
    double front_height_limit = 18;  // sum of the front hoof heights is clamped to this
    double hind_height_limit = 15;   // sum of the hind hoof heights is clamped to this
    double front_limited_lf_tx_offset = 0;  // Appendix B branch 2 adds 2.5 to lfHoof.tx; we do not
  } eq1;
  struct LowerBackRoll { double w1_counter_roll = -1; } eq2;          // lowerBack.ry
  struct LowerBackTwist { double w1_twist = 0.5; } eq3;              // lowerBack.rx
  struct Waist { double w1_lower_back = 1.7; } eq4;                  // waist.rz
  struct HipPitch { double w1_lower_back = 0.8; } eq5;               // hip.rz
  struct HipRoll {                                                   // hip.ry
    double w1_pivot_roll = 0.5;
    double w2_hind_height_difference = 2;
  } eq6;
  struct Lift {                                                      // cog.ty
    double w1_front_height = 2;
    double w2_scale = 0.01;
    double lift_limit = 15;
  } eq7;
  struct SeatShift {                                                 // cog.tx
    double w1_pivot_pitch = 2;
    double w2_scale = 0.1;
    double shift_limit = 1;  // symmetric: [-shift_limit, +shift_limit]
  } eq8;
  struct SquashStretch {                                             // spine*/neck/headA.ty
    double h1_squash = 0.1;
    double w1_spine_divisor = 6;  // spineC, spineD, spineF
    double w1_neck_divisor = 7;   // neck, headA (Appendix B)
  } eq9;
  struct HeadPitch {                                                 // head.rz
    double w1_lower_back = 0.9;
    double w2_lift = 18;
    double rest_pitch = 5;
    double lower_back_min = -20;
    double lower_back_max = 17;
  } eq10;
  struct HeadTurn { double w1_pivot_roll = 0.8; } eq11;              // head.ry
  struct WristForward {                                              // l/rWrist.tx
    double w1_lower_back = 0.0001;
    double w2_front_reach = 0.008;
    double lower_back_limit = 17;  // symmetric: [-limit, +limit]
    double rear_pivot_rz_rest = 0;
  } eq12;
  struct WristUp {                                                   // l/rWrist.ty
    double w1_hoof_height = 0.03;
    double w2_pivot_height = 0.0005;
    double hoof_height_limit = 20;
  } eq13;
  struct FootForward {                                               // l/rFoot.tx
    double w1_pivot_pitch = 0.005;
    double h1_reach_gain = 0.08;
    double w3_back_arch = 0.02;
    double w2_lower_back = 0.005;
    double reach_max = 0;  // the front-reach term is clamped to at most this (feet not too far forward)
    double rear_pivot_rz_rest = 0;
  } eq14;
  struct FootPitch {                                                 // l/rFoot.rz
    double w1 = 2;
    double w2_rig_scale = 6;
    double foot_tx_rest = 0;
  } eq15;
  struct FootRoll {                                                  // l/rFoot.ry, l/rFoot.rx
    double w1_twist = 1.7;
    double twist_offset = -1;
    double w2_side = 0.1;
    double side_offset = 1;
    double hoof_height_limit = 15;
  } eq16;
  struct FootOut {                                                   // l/rFoot.tz
    double w1_hoof_height = 0.05;
    double w2_pivot_roll = 0.05;
    double rest_offset = 0;
    double hoof_height_limit = 15;
  } eq17;
  struct KneeOut { double w1_foot = 1.1; } eq18;                     // l/rKnee.tz
  struct KneeUp {                                                    // l/rKnee.ty (Appendix B)
    double w1_hoof_height = 0.03;
    double rest_offset = 0;
    double hoof_height_limit = 15;
  } knee;
  struct Hair {                                                      // hair.up, hair.side
    double up_w = 0.7;
    double hoof_height_offset = 2;
    double side_w = 0.02;
  } hair;
  struct Cloth {                                                     // cloth.up, cloth.side
    double up_w = 0.7;
    double hoof_height_offset = 2;
    double side_w1_pivot_roll = 0.5;
    double side_w2_hind_height_difference = 2;
  } cloth;

  // The balance stage (rig/balance.h; docs/rider-rig.md, "Balance"): how the channels' fold becomes
  // the trunk's pose in world space. Not a thesis equation: the channels above stay exactly Appendix
  // B's; this decides where the trunk goes when the horse pitches far from level, where the thesis's
  // expressions grow without bound (a 170° fold on the 55° rear) or fold the rider the wrong way (the
  // buck's kick). amount 0 is the thesis pose as posing limits it (rig::RiderPoseParams), 1 the
  // balanced pose.
  struct Balance {
    double amount = 1;                // "balance": 0 the thesis pose .. 1 balanced
    double stirrup_share = 0.25;      // of her weight over the stirrups (the rest over the seat)
    double inertia_share = 0.3;       // of the horse's travel acceleration she leans against
    double turn_share = 1;            // of a turn's tilt of the apparent vertical her roll channels answer
    double slope_response = 1;        // uphill: of the slope she leans forward of her flat-ground lean
    double downhill_response = 0;     // downhill: of the slope she leans back of it (0: upright, as on the flat)
    double band_forward_deg = 35;     // soft band around the vertical the channels move her through
    double band_back_deg = 25;
    double max_fold_deg = 75;         // trunk ahead of the saddle's upright: the chest stops short of the neck
    double max_extension_deg = 45;    // trunk behind the saddle's upright: the back stops short of the croup
    double head_counter = 1;          // of the stage's turn the neck turns back, so she keeps looking ahead
    double seat_rise_cm = 5.5;        // at the full fold her seat is at least this far above where she sits
  } balance;

  // How a rider the rig seats sets her stirrup leathers (rig/characters/seating.h; docs/characters.md,
  // "Seating"): with her leg hanging long the tread is at her ankle bone, then she takes them up this
  // many holes (2.5 cm each): 0 for dressage, 2 for a general-purpose seat, 4 for jumping. The
  // generated rider is built in her stirrups and keeps the horse's leathers as built.
  struct Seat {
    double stirrup_holes_up = 2;
  } seat;

  // A rider rigidly fixed to the saddle: evaluateRider returns every rider channel at its rest value
  // (0), whatever the horse does, so she rides the saddle like a statue. The layered review movies
  // compare the rigged rider with this one to show what the rig adds (docs/rider-rig.md, "The rigid
  // rider"). The weights above are ignored while it is set. In a profile file: "rigid": true.
  bool rigid = false;

  // The thesis's values (the member initialisers above), named "thesis".
  static RigProfile thesis();
  // The built-in profile "rigid": thesis() with rigid set. loadRigProfile("rigid", ...) returns it
  // when the profiles folder has no rigid.json.
  static RigProfile rigidRider();
};

// Why a parameter's valid range is what it is (docs/rider-rig.md, "Valid ranges"). A profile file,
// a scene's profile_overrides and `--set` reject a value outside its parameter's range.
enum class RangeKind {
  Unit,        // cm per unit: 0.1 (a millimetre) to 1000 (10 m)
  Weight,      // a multiplier: -10 to +10 times the thesis value
  Divisor,     // a divisor: a tenth to ten times the thesis value, never 0 or negative
  Limit,       // a clamp on a sum of hoof heights or a channel, in units: 0 to 1000
  AngleLimit,  // a clamp on an angle, in degrees: up to a half turn, on its own side of 0
  Angle,       // an offset in degrees: -90 to 90
  Length,      // an offset in units: -100 to 100 (10 m at 10 cm a unit)
  Fraction,    // a share or a blend: 0 to 1
  Holes,       // stirrup leather holes: 0 to 16 (a jockey's leathers are 8 to 14 holes up)
};
// The kind's name as the docs' table writes it ("weight", "unit", ...).
std::string_view rangeKindName(RangeKind kind);

// One tunable parameter: its JSON key, where it lives, the thesis passage it comes from, and the
// closed range [min, max] of values a profile may give it.
struct RigParameter {
  std::string_view key;
  double& (*field)(RigProfile&);
  std::string_view cites;
  RangeKind kind;
  double min, max;
  // Read-only access through the same accessor; nothing is written through the cast.
  const double& get(const RigProfile& p) const { return field(const_cast<RigProfile&>(p)); }
  bool accepts(double value) const { return value >= min && value <= max; }  // false for NaN
};
// Every parameter, in equation order (horse_unit_cm and rider_unit_cm first).
std::span<const RigParameter> rigParameters();
const RigParameter* findRigParameter(std::string_view key);

}  // namespace stirrup::rig
