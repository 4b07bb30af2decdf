#include "rig/rig_profile.h"

#include <array>

namespace stirrup::rig {
namespace {

// One table entry per parameter. The lambda names the field once, so key and field cannot drift.
// The range follows the parameter's kind (rig_profile.h, RangeKind; docs/rider-rig.md "Valid ranges"):
// weights +-10x the thesis value, divisors 1/10x to 10x, limits 0 to 1000 units, angle offsets +-90
// degrees, length offsets +-100 units, units 0.1 to 1000 cm.
#define STIRRUP_RIG_PARAM(KEY, MEMBER, KIND, MIN, MAX, CITES) \
  RigParameter { KEY, [](RigProfile& p) -> double& { return p.MEMBER; }, CITES, KIND, MIN, MAX }

const std::array kParameters = {
    STIRRUP_RIG_PARAM("horse_unit_cm", horse_unit_cm, RangeKind::Unit, 0.1, 1000,
                      "Units (docs/rider-rig.md): cm per thesis unit; horse translations are divided by it"),
    STIRRUP_RIG_PARAM("rider_unit_cm", rider_unit_cm, RangeKind::Unit, 0.1, 1000,
                      "Units (docs/rider-rig.md): cm per rider unit, used when posing the rider"),

    STIRRUP_RIG_PARAM("eq1.w1_pivot_pitch", eq1.w1_pivot_pitch, RangeKind::Weight, -0.7, 0.7, "Eq 1 w1 = 0.07: rearPivot.rz x (rearPivot.ty + h1) x w1"),
    STIRRUP_RIG_PARAM("eq1.h1_pivot_height", eq1.h1_pivot_height, RangeKind::Length, -100, 100, "Eq 1 h1 = 2: added to the rear pivot height"),
    STIRRUP_RIG_PARAM("eq1.w2_front_reach", eq1.w2_front_reach, RangeKind::Weight, -2.5, 2.5, "Eq 1 w2 = 0.25: (mean front hoof tx - rearPivot.tx) x w2"),
    STIRRUP_RIG_PARAM("eq1.w3_hind_reach", eq1.w3_hind_reach, RangeKind::Weight, -2.5, 2.5, "Eq 1 w3 = 0.25: (rearPivot.tx - mean hind hoof tx) x w3"),
    STIRRUP_RIG_PARAM("eq1.w4_pivot_pitch_gain", eq1.w4_pivot_pitch_gain, RangeKind::Weight, -1, 1, "Eq 1 w4 = 0.1: (|rearPivot.rz| + h2) x w4 scales the front hoof height"),
    STIRRUP_RIG_PARAM("eq1.h2_pivot_pitch", eq1.h2_pivot_pitch, RangeKind::Angle, -90, 90, "Eq 1 h2 = 5: added to |rearPivot.rz|"),
    STIRRUP_RIG_PARAM("eq1.w5_front_height", eq1.w5_front_height, RangeKind::Weight, -9, 9, "Eq 1 w5 = 0.9: weight of the front hoof height term"),
    STIRRUP_RIG_PARAM("eq1.w6_hind_height", eq1.w6_hind_height, RangeKind::Weight, -4, 4, "Eq 1 w6 = 0.4: weight of the hind hoof height"),
    STIRRUP_RIG_PARAM("eq1.w7_hoof_height", eq1.w7_hoof_height, RangeKind::Weight, -4, 4, "Eq 1 w7 = 0.40: weight of (front term - hind term)"),
    STIRRUP_RIG_PARAM("eq1.front_height_limit", eq1.front_height_limit, RangeKind::Limit, 0, 1000, "Eq 1, Appendix B: sum of front hoof heights clamped to 18"),
    STIRRUP_RIG_PARAM("eq1.hind_height_limit", eq1.hind_height_limit, RangeKind::Limit, 0, 1000, "Eq 1, Appendix B: sum of hind hoof heights clamped to 15"),
    STIRRUP_RIG_PARAM("eq1.front_limited_lf_tx_offset", eq1.front_limited_lf_tx_offset, RangeKind::Length, -100, 100,
                      "Eq 1, Appendix B branch 2 adds 2.5 to lfHoof.tx; decided 0 (a jump in the lean)"),

    STIRRUP_RIG_PARAM("eq2.w1_counter_roll", eq2.w1_counter_roll, RangeKind::Weight, -10, 10, "Eq 2: lowerBack.ry = rearPivot.rx x -1"),
    STIRRUP_RIG_PARAM("eq3.w1_twist", eq3.w1_twist, RangeKind::Weight, -5, 5, "Eq 3 w1 = 0.5: lowerBack.rx = lowerBack.ry x w1"),
    STIRRUP_RIG_PARAM("eq4.w1_lower_back", eq4.w1_lower_back, RangeKind::Weight, -17, 17, "Eq 4 w1 = 1.7: waist.rz = lowerBack.rz x w1"),
    STIRRUP_RIG_PARAM("eq5.w1_lower_back", eq5.w1_lower_back, RangeKind::Weight, -8, 8, "Eq 5 w1 = 0.8: hip.rz = lowerBack.rz x w1"),
    STIRRUP_RIG_PARAM("eq6.w1_pivot_roll", eq6.w1_pivot_roll, RangeKind::Weight, -5, 5, "Eq 6 w1 = 0.5: hip.ry = rearPivot.rx x w1 + ..."),
    STIRRUP_RIG_PARAM("eq6.w2_hind_height_difference", eq6.w2_hind_height_difference, RangeKind::Weight, -20, 20,
                      "Eq 6 w2 = 2: ... + (rbHoof.ty - lbHoof.ty) x w2"),
    STIRRUP_RIG_PARAM("eq7.w1_front_height", eq7.w1_front_height, RangeKind::Weight, -20, 20, "Eq 7 w1 = 2: front hoof heights x w1"),
    STIRRUP_RIG_PARAM("eq7.w2_scale", eq7.w2_scale, RangeKind::Weight, -0.1, 0.1, "Eq 7 w2 = 0.01: the whole lift x w2"),
    STIRRUP_RIG_PARAM("eq7.lift_limit", eq7.lift_limit, RangeKind::Limit, 0, 1000, "Eq 7, Appendix B: lift clamped to at most 15"),
    STIRRUP_RIG_PARAM("eq8.w1_pivot_pitch", eq8.w1_pivot_pitch, RangeKind::Weight, -20, 20, "Eq 8 w1 = 2: rearPivot.rz x w1"),
    STIRRUP_RIG_PARAM("eq8.w2_scale", eq8.w2_scale, RangeKind::Weight, -1, 1, "Eq 8 w2 = 0.1: (rearPivot.rz x w1 - lowerBack.rz) x w2"),
    STIRRUP_RIG_PARAM("eq8.shift_limit", eq8.shift_limit, RangeKind::Limit, 0, 1000, "Eq 8, Appendix B: seat shift clamped to [-1, 1]"),
    STIRRUP_RIG_PARAM("eq9.h1_squash", eq9.h1_squash, RangeKind::Length, -100, 100, "Eq 9 h1 = 0.1: joints start this much lower than rest"),
    STIRRUP_RIG_PARAM("eq9.w1_spine_divisor", eq9.w1_spine_divisor, RangeKind::Divisor, 0.6, 60, "Eq 9 w1 = 6: spineC/D/F.ty = -h1 + lift / w1"),
    STIRRUP_RIG_PARAM("eq9.w1_neck_divisor", eq9.w1_neck_divisor, RangeKind::Divisor, 0.7, 70, "Eq 9, Appendix B: neck/headA.ty = -h1 + lift / 7"),
    STIRRUP_RIG_PARAM("eq10.w1_lower_back", eq10.w1_lower_back, RangeKind::Weight, -9, 9, "Eq 10 w1 = 0.9: lowerBack.rz x -w1"),
    STIRRUP_RIG_PARAM("eq10.w2_lift", eq10.w2_lift, RangeKind::Weight, -180, 180, "Eq 10 w2 = 18: - lift x w2"),
    STIRRUP_RIG_PARAM("eq10.rest_pitch", eq10.rest_pitch, RangeKind::Angle, -90, 90, "Eq 10: + 5 degrees down"),
    STIRRUP_RIG_PARAM("eq10.lower_back_min", eq10.lower_back_min, RangeKind::AngleLimit, -180, 0, "Eq 10, Appendix B: lowerBack.rz clamped to >= -20 for the head"),
    STIRRUP_RIG_PARAM("eq10.lower_back_max", eq10.lower_back_max, RangeKind::AngleLimit, 0, 180, "Eq 10, Appendix B: lowerBack.rz clamped to <= 17 for the head"),
    STIRRUP_RIG_PARAM("eq11.w1_pivot_roll", eq11.w1_pivot_roll, RangeKind::Weight, -8, 8, "Eq 11, Appendix B: head.ry = rearPivot.rx x 0.8 (prose: x -1)"),
    STIRRUP_RIG_PARAM("eq12.w1_lower_back", eq12.w1_lower_back, RangeKind::Weight, -0.001, 0.001, "Eq 12 w1 = 0.0001: lowerBack.rz x w1"),
    STIRRUP_RIG_PARAM("eq12.w2_front_reach", eq12.w2_front_reach, RangeKind::Weight, -0.08, 0.08,
                      "Eq 12, Appendix B: + (mean front hoof tx - rearPivot.tx) x |rearPivot.rz| x 0.008"),
    STIRRUP_RIG_PARAM("eq12.lower_back_limit", eq12.lower_back_limit, RangeKind::AngleLimit, 0, 180, "Eq 12, Appendix B: lowerBack.rz clamped to [-17, 17]"),
    STIRRUP_RIG_PARAM("eq12.rear_pivot_rz_rest", eq12.rear_pivot_rz_rest, RangeKind::Angle, -90, 90,
                      "Eq 12, Appendix B branch 3 reads |rearPivot.rz - 0.572|; decided 0 (offsets from rest)"),
    STIRRUP_RIG_PARAM("eq13.w1_hoof_height", eq13.w1_hoof_height, RangeKind::Weight, -0.3, 0.3, "Eq 13 w1 = 0.03: sum of hoof heights x w1"),
    STIRRUP_RIG_PARAM("eq13.w2_pivot_height", eq13.w2_pivot_height, RangeKind::Weight, -0.005, 0.005, "Eq 13 w2 = 0.0005: - rearPivot.ty x w2"),
    STIRRUP_RIG_PARAM("eq13.hoof_height_limit", eq13.hoof_height_limit, RangeKind::Limit, 0, 1000, "Eq 13, Appendix B: sum of hoof heights clamped to 20"),
    STIRRUP_RIG_PARAM("eq14.w1_pivot_pitch", eq14.w1_pivot_pitch, RangeKind::Weight, -0.05, 0.05, "Eq 14 w1 = 0.005: |rearPivot.rz| x w1"),
    STIRRUP_RIG_PARAM("eq14.h1_reach_gain", eq14.h1_reach_gain, RangeKind::Weight, -0.8, 0.8, "Eq 14 h1: prose 0.8, Appendix B 0.08 (decided 0.08)"),
    STIRRUP_RIG_PARAM("eq14.w3_back_arch", eq14.w3_back_arch, RangeKind::Weight, -0.2, 0.2, "Eq 14, Appendix B: + backMid.rz x 0.02 in the reach gain"),
    STIRRUP_RIG_PARAM("eq14.w2_lower_back", eq14.w2_lower_back, RangeKind::Weight, -0.05, 0.05, "Eq 14 w2 = 0.005: - |rearPivot.rz| x lowerBack.rz x w2"),
    STIRRUP_RIG_PARAM("eq14.reach_max", eq14.reach_max, RangeKind::Length, -100, 100, "Eq 14, Appendix B: the front-reach term clamped to <= 0"),
    STIRRUP_RIG_PARAM("eq14.rear_pivot_rz_rest", eq14.rear_pivot_rz_rest, RangeKind::Angle, -90, 90,
                      "Eq 14, Appendix B else-branch reads |rearPivot.rz - 0.572|; decided 0 (offsets from rest)"),
    STIRRUP_RIG_PARAM("eq15.w1", eq15.w1, RangeKind::Weight, -20, 20, "Eq 15 w1 = 2: foot.rz = foot.tx x w1 (x rig scale)"),
    STIRRUP_RIG_PARAM("eq15.w2_rig_scale", eq15.w2_rig_scale, RangeKind::Weight, -60, 60, "Eq 15, Appendix B: (foot.tx + 3) x -6 x 2; the 6 (sign: toe up)"),
    STIRRUP_RIG_PARAM("eq15.foot_tx_rest", eq15.foot_tx_rest, RangeKind::Length, -100, 100, "Eq 15, Appendix B: + 3, the thesis rig's rest foot tx; decided 0"),
    STIRRUP_RIG_PARAM("eq16.w1_twist", eq16.w1_twist, RangeKind::Weight, -17, 17, "Eq 16 w1 = 1.7: foot.ry = sum of hoof heights x -w1 + offset"),
    STIRRUP_RIG_PARAM("eq16.twist_offset", eq16.twist_offset, RangeKind::Angle, -90, 90, "Eq 16, Appendix B: foot.ry ... - 1"),
    STIRRUP_RIG_PARAM("eq16.w2_side", eq16.w2_side, RangeKind::Weight, -1, 1, "Eq 16, Appendix B: foot.rx = sum of hoof heights x (+0.1 left, -0.1 right) + offset"),
    STIRRUP_RIG_PARAM("eq16.side_offset", eq16.side_offset, RangeKind::Angle, -90, 90, "Eq 16, Appendix B: foot.rx ... + 1"),
    STIRRUP_RIG_PARAM("eq16.hoof_height_limit", eq16.hoof_height_limit, RangeKind::Limit, 0, 1000, "Eq 16, Appendix B: sum of hoof heights clamped to 15"),
    STIRRUP_RIG_PARAM("eq17.w1_hoof_height", eq17.w1_hoof_height, RangeKind::Weight, -0.5, 0.5, "Eq 17 w1 = 0.05: sum of hoof heights x -w1"),
    STIRRUP_RIG_PARAM("eq17.w2_pivot_roll", eq17.w2_pivot_roll, RangeKind::Weight, -0.5, 0.5, "Eq 17 w2 = 0.05: - rearPivot.rx x w2"),
    STIRRUP_RIG_PARAM("eq17.rest_offset", eq17.rest_offset, RangeKind::Length, -100, 100, "Eq 17, Appendix B: + 2, the thesis rig's rest foot position; decided 0"),
    STIRRUP_RIG_PARAM("eq17.hoof_height_limit", eq17.hoof_height_limit, RangeKind::Limit, 0, 1000, "Eq 17, Appendix B: sum of hoof heights clamped to 15"),
    STIRRUP_RIG_PARAM("eq18.w1_foot", eq18.w1_foot, RangeKind::Weight, -11, 11, "Eq 18 w1 = 1.1: knee.tz = - foot.tz x w1 (offset from rest)"),
    STIRRUP_RIG_PARAM("knee.w1_hoof_height", knee.w1_hoof_height, RangeKind::Weight, -0.3, 0.3, "Appendix B knee ty: sum of hoof heights x 0.03"),
    STIRRUP_RIG_PARAM("knee.rest_offset", knee.rest_offset, RangeKind::Length, -100, 100, "Appendix B knee ty: - 1, the thesis rig's rest knee height; decided 0"),
    STIRRUP_RIG_PARAM("knee.hoof_height_limit", knee.hoof_height_limit, RangeKind::Limit, 0, 1000, "Appendix B knee ty: sum of hoof heights clamped to 15"),
    STIRRUP_RIG_PARAM("hair.up_w", hair.up_w, RangeKind::Weight, -7, 7, "8.9, Appendix B: hair.up = (sum of hoof heights - 2) x 0.7"),
    STIRRUP_RIG_PARAM("hair.hoof_height_offset", hair.hoof_height_offset, RangeKind::Length, -100, 100, "8.9, Appendix B: the 2 subtracted from the hoof heights"),
    STIRRUP_RIG_PARAM("hair.side_w", hair.side_w, RangeKind::Weight, -0.2, 0.2, "8.9, Appendix B: hair.side = (sum of hoof heights - 2) x lowerBack.ry x -0.02"),
    STIRRUP_RIG_PARAM("cloth.up_w", cloth.up_w, RangeKind::Weight, -7, 7, "8.9, Appendix B: cloth.up = (sum of hoof heights - 2) x 0.7"),
    STIRRUP_RIG_PARAM("cloth.hoof_height_offset", cloth.hoof_height_offset, RangeKind::Length, -100, 100, "8.9, Appendix B: the 2 subtracted from the hoof heights"),
    STIRRUP_RIG_PARAM("cloth.side_w1_pivot_roll", cloth.side_w1_pivot_roll, RangeKind::Weight, -5, 5, "8.9, Appendix B: cloth.side = rearPivot.rx x -0.5 + ..."),
    STIRRUP_RIG_PARAM("cloth.side_w2_hind_height_difference", cloth.side_w2_hind_height_difference, RangeKind::Weight, -20, 20,
                      "8.9, Appendix B: ... + (rbHoof.ty - lbHoof.ty) x -2"),
    STIRRUP_RIG_PARAM("balance", balance.amount, RangeKind::Fraction, 0, 1,
                      "Balance (docs/rider-rig.md): 0 the thesis pose, 1 the balanced pose"),
    STIRRUP_RIG_PARAM("balance.stirrup_share", balance.stirrup_share, RangeKind::Fraction, 0, 1,
                      "Balance: share of her weight over the stirrups; the jumping seat (Caprilli) keeps her centred over her feet, Kuhnel 5.4 raises her seat in the rear"),
    STIRRUP_RIG_PARAM("balance.inertia_share", balance.inertia_share, RangeKind::Fraction, 0, 1,
                      "Balance: share of the horse's travel acceleration she leans against; Kuhnel 5.5, in the stop she leans back to compensate for the backward shift in centre of gravity"),
    STIRRUP_RIG_PARAM("balance.turn_share", balance.turn_share, RangeKind::Fraction, 0, 1,
                      "Balance: in a turn her roll channels (Eq 2, 3, 6, 11, 17) answer the horse's roll from the apparent vertical (gravity and the centripetal acceleration) tilted by this share of atan(a/g); 1 keeps her in line with her horse, as horses lean about 1 degree less than atan(a/g) (Brocklehurst, Weller and Pfau) and riding texts keep the rider in line with the horse; 0 the world's vertical, as the thesis"),
    STIRRUP_RIG_PARAM("balance.slope_response", balance.slope_response, RangeKind::Fraction, 0, 1,
                      "Balance: uphill she leans forward of her flat-ground lean by this share of the slope (riding texts: lean forward going up, off the horse's loins); the centre-of-mass term already keeps her upright in the world"),
    STIRRUP_RIG_PARAM("balance.downhill_response", balance.downhill_response, RangeKind::Fraction, 0, 1,
                      "Balance: downhill she leans back of her flat-ground lean by this share of the slope (riding texts: upright or slightly back going down); 0 upright"),
    STIRRUP_RIG_PARAM("balance.band_forward_deg", balance.band_forward_deg, RangeKind::AngleLimit, 0, 90,
                      "Balance: the trunk's lean ahead of the vertical approaches this softly"),
    STIRRUP_RIG_PARAM("balance.band_back_deg", balance.band_back_deg, RangeKind::AngleLimit, 0, 90,
                      "Balance: the trunk's lean behind the vertical approaches this softly"),
    STIRRUP_RIG_PARAM("balance.max_fold_deg", balance.max_fold_deg, RangeKind::AngleLimit, 0, 120,
                      "Balance: the trunk ahead of the saddle's upright at most this; measured on the meshes, the chest stops short of the horse's neck"),
    STIRRUP_RIG_PARAM("balance.max_extension_deg", balance.max_extension_deg, RangeKind::AngleLimit, 0, 90,
                      "Balance: the trunk behind the saddle's upright at most this, short of the croup"),
    STIRRUP_RIG_PARAM("balance.head_counter", balance.head_counter, RangeKind::Fraction, 0, 1,
                      "Balance: the neck turns back this share of the stage's turn; Kuhnel 5.1, the rider keeps looking forward"),
    STIRRUP_RIG_PARAM("balance.seat_rise_cm", balance.seat_rise_cm, RangeKind::Length, 0, 30,
                      "Balance: at the full fold her seat is at least this far (cm) above where she sits, Eq 7's lift included; Kuhnel 5.1 and 5.4, as she leans forward she raises out of the saddle"),
    STIRRUP_RIG_PARAM("seat.stirrup_holes_up", seat.stirrup_holes_up, RangeKind::Holes, 0, 16,
                      "Seat: leathers taken up from the tread at the ankle bone, in 2.5 cm holes; 0 dressage, 2 general, 4 jumping (riding practice, docs/characters.md)"),
};
#undef STIRRUP_RIG_PARAM

}  // namespace

std::span<const RigParameter> rigParameters() { return kParameters; }

std::string_view rangeKindName(RangeKind kind) {
  switch (kind) {
    case RangeKind::Unit: return "unit";
    case RangeKind::Weight: return "weight";
    case RangeKind::Divisor: return "divisor";
    case RangeKind::Limit: return "limit";
    case RangeKind::AngleLimit: return "angle limit";
    case RangeKind::Angle: return "angle";
    case RangeKind::Length: return "length";
    case RangeKind::Fraction: return "fraction";
    case RangeKind::Holes: return "holes";
  }
  return "?";
}

const RigParameter* findRigParameter(std::string_view key) {
  for (const RigParameter& p : kParameters)
    if (p.key == key) return &p;
  return nullptr;
}

RigProfile RigProfile::thesis() {
  RigProfile p;
  p.name = "thesis";
  p.doc = "Kuhnel 2003 as published, contradictions decided as in docs/rider-rig.md";
  return p;
}

RigProfile RigProfile::rigidRider() {
  RigProfile p = thesis();
  p.name = "rigid";
  p.doc = "A rider rigidly fixed to the saddle: every rider channel at rest (what the rig adds, by contrast)";
  p.rigid = true;
  return p;
}

}  // namespace stirrup::rig
