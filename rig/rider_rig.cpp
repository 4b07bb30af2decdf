#include "rig/rider_rig.h"

#include <algorithm>
#include <cmath>

namespace stirrup::rig {
namespace {

using H = HorseChannel;
using R = RiderChannel;

// The quantities the thesis's expressions read, measured once per frame. Translations are in thesis
// units (horse cm / horse_unit_cm), rotations in degrees.
struct HorseMeasures {
  double pivot_tx = 0, pivot_ty = 0;               // rearPivot translation
  double pivot_rx = 0, pivot_rz = 0;               // rearPivot roll, pitch
  double back_mid_rz = 0;                          // backMid arch
  double lf_tx = 0, rf_tx = 0, lb_tx = 0, rb_tx = 0;
  double lb_ty = 0, rb_ty = 0;
  double front_height = 0;  // lfHoof.ty + rfHoof.ty
  double hind_height = 0;   // lbHoof.ty + rbHoof.ty
  double all_height = 0;    // the four hoof heights
  double front_mean_tx = 0, hind_mean_tx = 0;
};

HorseMeasures measureHorse(const HorseChannels& horse, double horse_unit_cm) {
  const double to_units = 1.0 / horse_unit_cm;
  HorseMeasures m;
  m.pivot_tx = horse[H::rearPivotTx] * to_units;
  m.pivot_ty = horse[H::rearPivotTy] * to_units;
  m.pivot_rx = horse[H::rearPivotRx];
  m.pivot_rz = horse[H::rearPivotRz];
  m.back_mid_rz = horse[H::backMidRz];
  m.lf_tx = horse[H::lfHoofTx] * to_units;
  m.rf_tx = horse[H::rfHoofTx] * to_units;
  m.lb_tx = horse[H::lbHoofTx] * to_units;
  m.rb_tx = horse[H::rbHoofTx] * to_units;
  m.lb_ty = horse[H::lbHoofTy] * to_units;
  m.rb_ty = horse[H::rbHoofTy] * to_units;
  m.front_height = (horse[H::lfHoofTy] + horse[H::rfHoofTy]) * to_units;
  m.hind_height = m.lb_ty + m.rb_ty;
  m.all_height = m.front_height + m.hind_height;
  m.front_mean_tx = (m.lf_tx + m.rf_tx) / 2;
  m.hind_mean_tx = (m.lb_tx + m.rb_tx) / 2;
  return m;
}

// Appendix B's limits substitute the limit for the input once it is reached: a clamp from above.
double atMost(double value, double limit) { return std::min(value, limit); }

// Equation 1, with Appendix B's four branches as clamps of the front and hind hoof heights.
double lowerBackPitch(const HorseMeasures& m, const RigProfile::LowerBackPitch& k) {
  const double front_height = atMost(m.front_height, k.front_height_limit);
  const double hind_height = atMost(m.hind_height, k.hind_height_limit);
  // Branch 2 of Appendix B shifts lfHoof.tx while the front heights are clamped (default 0: see docs).
  const bool only_front_limited = m.front_height >= k.front_height_limit && m.hind_height < k.hind_height_limit;
  const double lf_shift = only_front_limited ? k.front_limited_lf_tx_offset : 0.0;
  const double front_mean_tx = m.front_mean_tx + lf_shift / 2;

  const double pivot = m.pivot_rz * (m.pivot_ty + k.h1_pivot_height) * k.w1_pivot_pitch;
  // Front hooves reaching ahead of the body and hind hooves trailing behind it both tip the rider
  // forward; drawn toward the middle they tip her back.
  const double front_reach = (front_mean_tx - m.pivot_tx) * k.w2_front_reach;
  const double hind_reach = (m.pivot_tx - m.hind_mean_tx) * k.w3_hind_reach;
  // Lifted forefeet lean her forward, more so the more the body pitches (either way).
  const double front_lift =
      front_height * ((std::abs(m.pivot_rz) + k.h2_pivot_pitch) * k.w4_pivot_pitch_gain) * k.w5_front_height;
  const double hind_lift = hind_height * k.w6_hind_height;
  return pivot + front_reach + hind_reach + (front_lift - hind_lift) * k.w7_hoof_height;
}

// Equation 7: spread of each pair, where each pair sits against the body, and the lifted forefeet.
double seatLift(const HorseMeasures& m, const RigProfile::Lift& k) {
  const double spread = std::abs(m.lb_tx - m.rb_tx) + std::abs(m.lf_tx - m.rf_tx);
  const double hind_under = m.hind_mean_tx - m.pivot_tx;    // hind hooves forward under the body: up
  const double front_under = m.pivot_tx - m.front_mean_tx;  // fore hooves back under it: up
  const double lift =
      (spread + hind_under + front_under + m.front_height * k.w1_front_height) * k.w2_scale;
  return atMost(lift, k.lift_limit);
}

// Equation 8, clamped to the saddle.
double seatShift(const HorseMeasures& m, double lower_back_rz, const RigProfile::SeatShift& k) {
  const double shift = (m.pivot_rz * k.w1_pivot_pitch - lower_back_rz) * k.w2_scale;
  return std::clamp(shift, -k.shift_limit, k.shift_limit);
}

// Equation 10: the head counters the lean (clamped) and bobs with the lift.
double headPitch(double lower_back_rz, double lift, const RigProfile::HeadPitch& k) {
  const double lean = std::clamp(lower_back_rz, k.lower_back_min, k.lower_back_max);
  return -lean * k.w1_lower_back - lift * k.w2_lift + k.rest_pitch;
}

// Equation 12 (Appendix B form): a trace of the lean, plus the fore hooves' reach once the body pitches.
double wristForward(const HorseMeasures& m, double lower_back_rz, const RigProfile::WristForward& k) {
  const double lean = std::clamp(lower_back_rz, -k.lower_back_limit, k.lower_back_limit);
  const double pitch = std::abs(m.pivot_rz - k.rear_pivot_rz_rest);
  return lean * k.w1_lower_back + (m.front_mean_tx - m.pivot_tx) * pitch * k.w2_front_reach;
}

// Equation 13: hands bounce with the hooves, less as the whole horse rises.
double wristUp(const HorseMeasures& m, const RigProfile::WristUp& k) {
  return atMost(m.all_height, k.hoof_height_limit) * k.w1_hoof_height - m.pivot_ty * k.w2_pivot_height;
}

// Equation 14 (Appendix B form): feet follow the fore hooves' reach (never forward of rest: the
// reach term is clamped), and swing back as she leans into a pitching body.
double footForward(const HorseMeasures& m, double lower_back_rz, const RigProfile::FootForward& k) {
  const double reach_gain = std::abs(m.pivot_rz) * k.w1_pivot_pitch + k.h1_reach_gain + m.back_mid_rz * k.w3_back_arch;
  const double reach = atMost((m.front_mean_tx - m.pivot_tx) * reach_gain, k.reach_max);
  const double pitch = std::abs(m.pivot_rz - k.rear_pivot_rz_rest);
  return reach - pitch * lower_back_rz * k.w2_lower_back;
}

}  // namespace

RiderChannels evaluateRider(const HorseChannels& horse, const RigProfile& p) {
  RiderChannels r;
  if (p.rigid) return r;  // fixed to the saddle: every channel at rest (RigProfile::rigid)
  const HorseMeasures m = measureHorse(horse, p.horse_unit_cm);

  // Lower back first: the waist, hips, seat, head, wrists and feet read it.
  const double lower_back_rz = lowerBackPitch(m, p.eq1);
  const double lower_back_ry = m.pivot_rx * p.eq2.w1_counter_roll;  // Eq 2
  r[R::lowerBackRz] = lower_back_rz;
  r[R::lowerBackRy] = lower_back_ry;
  r[R::lowerBackRx] = lower_back_ry * p.eq3.w1_twist;  // Eq 3
  r[R::waistRz] = lower_back_rz * p.eq4.w1_lower_back;  // Eq 4
  r[R::hipRz] = lower_back_rz * p.eq5.w1_lower_back;  // Eq 5
  r[R::hipRy] = m.pivot_rx * p.eq6.w1_pivot_roll + (m.rb_ty - m.lb_ty) * p.eq6.w2_hind_height_difference;  // Eq 6

  const double lift = seatLift(m, p.eq7);
  r[R::cogTy] = lift;
  r[R::cogTx] = seatShift(m, lower_back_rz, p.eq8);

  // Eq 9: offsets from each joint's rest height, starting h1 squashed.
  const double spine_ty = -p.eq9.h1_squash + lift / p.eq9.w1_spine_divisor;
  const double neck_ty = -p.eq9.h1_squash + lift / p.eq9.w1_neck_divisor;
  r[R::spineCTy] = spine_ty;
  r[R::spineDTy] = spine_ty;
  r[R::spineFTy] = spine_ty;
  r[R::neckTy] = neck_ty;
  r[R::headATy] = neck_ty;

  r[R::headRz] = headPitch(lower_back_rz, lift, p.eq10);
  r[R::headRy] = m.pivot_rx * p.eq11.w1_pivot_roll;  // Eq 11

  const double wrist_tx = wristForward(m, lower_back_rz, p.eq12);
  const double wrist_ty = wristUp(m, p.eq13);
  r[R::lWristTx] = wrist_tx;
  r[R::rWristTx] = wrist_tx;
  r[R::lWristTy] = wrist_ty;
  r[R::rWristTy] = wrist_ty;

  const double foot_tx = footForward(m, lower_back_rz, p.eq14);
  r[R::lFootTx] = foot_tx;
  r[R::rFootTx] = foot_tx;
  // Eq 15: toe up as the foot goes forward; each foot reads its own tx.
  r[R::lFootRz] = (r[R::lFootTx] + p.eq15.foot_tx_rest) * p.eq15.w2_rig_scale * p.eq15.w1;
  r[R::rFootRz] = (r[R::rFootTx] + p.eq15.foot_tx_rest) * p.eq15.w2_rig_scale * p.eq15.w1;

  // Eq 16: twist the same way on both feet; the side-to-side roll is mirrored (left +, right -).
  const double roll_height = atMost(m.all_height, p.eq16.hoof_height_limit);
  const double twist = roll_height * -p.eq16.w1_twist + p.eq16.twist_offset;
  r[R::lFootRy] = twist;
  r[R::rFootRy] = twist;
  r[R::lFootRx] = roll_height * p.eq16.w2_side + p.eq16.side_offset;
  r[R::rFootRx] = roll_height * -p.eq16.w2_side + p.eq16.side_offset;

  // Eq 17: both feet come in against the belly as the hooves lift.
  const double foot_tz = atMost(m.all_height, p.eq17.hoof_height_limit) * -p.eq17.w1_hoof_height -
                         m.pivot_rx * p.eq17.w2_pivot_roll + p.eq17.rest_offset;
  r[R::lFootTz] = foot_tz;
  r[R::rFootTz] = foot_tz;
  // Eq 18: each knee moves opposite its own foot, so the leg swings.
  r[R::lKneeTz] = -r[R::lFootTz] * p.eq18.w1_foot;
  r[R::rKneeTz] = -r[R::rFootTz] * p.eq18.w1_foot;
  // Appendix B: knees rise with the hooves.
  const double knee_ty = atMost(m.all_height, p.knee.hoof_height_limit) * p.knee.w1_hoof_height + p.knee.rest_offset;
  r[R::lKneeTy] = knee_ty;
  r[R::rKneeTy] = knee_ty;

  // 8.9 and Appendix B: drive values for the braid and the cloth.
  r[R::hairUp] = (m.all_height - p.hair.hoof_height_offset) * p.hair.up_w;
  r[R::hairSide] = (m.all_height - p.hair.hoof_height_offset) * lower_back_ry * -p.hair.side_w;
  r[R::clothUp] = (m.all_height - p.cloth.hoof_height_offset) * p.cloth.up_w;
  r[R::clothSide] = m.pivot_rx * -p.cloth.side_w1_pivot_roll +
                    (m.rb_ty - m.lb_ty) * -p.cloth.side_w2_hind_height_difference;
  return r;
}

}  // namespace stirrup::rig
