#include "rig/motion/procedural_gait.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rig/error.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {


double wrap01(double x) { return x - std::floor(x); }

struct HoofState {
  double tx = 0.0;  // ahead of the rest place, cm
  double ty = 0.0;  // height above the ground, cm
};

// One hoof at stride phase p. During stance the hoof is fixed in the world, so in the travel frame
// it slides back at the body's speed from +S/2 to -S/2. During swing it returns along a Hermite curve
// whose end tangents match the stance velocity, so the hoof leaves and meets the ground without a
// velocity pop, and rises on a sine arc that is highest at mid-swing.
HoofState hoofAt(double p, double touchdown, double duty, double stance_cm, double lift_cm) {
  const double since_touchdown = wrap01(p - touchdown);
  HoofState h;
  if (since_touchdown < duty) {
    const double s = since_touchdown / duty;
    h.tx = stance_cm * (0.5 - s);
    return h;
  }
  const double s = (since_touchdown - duty) / (1.0 - duty);
  // Stance velocity in swing-normalised time: d(tx)/ds = -stance_cm * (1 - duty) / duty.
  const double m = -stance_cm * (1.0 - duty) / duty;
  const double p0 = -0.5 * stance_cm, p1 = 0.5 * stance_cm;
  const double s2 = s * s, s3 = s2 * s;
  h.tx = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m + (-2 * s3 + 3 * s2) * p1 +
         (s3 - s2) * m;
  h.ty = lift_cm * std::pow(std::sin(kPi * s), 1.5);
  return h;
}

}  // namespace

GaitParams trotParams() {
  GaitParams g;
  // Front end level as each fore lands (.04, .54: each diagonal's hind lands 30 ms first), highest
  // between: a fore landing with the front end up falls short of the default horse's reach
  // (docs/horse-clips.md, "Legs").
  g.pitch_peak_after_low = 0.07;
  return g;
}

GaitParams walkParams() {
  GaitParams g;
  g.name = "walk";
  g.speed_cm_s = 180.0;                 // gait-reference: walk 1.8–1.9 m/s
  g.stride_hz = 0.95;                   // gait-reference: stride ≈ 1.0–1.1 s (length 1.89 m)
  g.touchdown_phase = {0.25, 0.75, 0.0, 0.5};  // gait-reference: lateral sequence LH 0 LF .25 RH .5 RF .75
  g.duty_factor = {0.64, 0.64, 0.66, 0.66};    // gait-reference: ≈ 0.60–0.70
  g.hoof_lift_cm = 11.0;                // gait-reference: ≈ 10–20 cm at walk and trot
  g.fore_lift_scale = 1.1;
  g.trunk_bounce_cm = 3.0;              // ≈ (no measurement in gait-reference): half the trot's
  g.trunk_cycles_per_stride = 2;        // one rise per hind step
  g.trunk_low_phase = 0.15;
  g.pitch_deg = 1.0;
  g.pitch_peak_after_low = 0.35;        // highest at .5, level as the fores land (.25, .75), as at the trot
  g.roll_deg = 1.5;
  g.neck_nod_deg = 4.0;                 // the walk nods more than the trot
  g.tail_swing_deg = 5.0;
  return g;
}

GaitParams canterParams(Lead lead) {
  GaitParams g;
  g.name = "canter";
  g.speed_cm_s = 600.0;                 // gait-reference: 3–4 m at 5–7 m/s
  g.stride_hz = 1.0 / 0.6;              // gait-reference: stride ≈ 0.55–0.65 s (length 3.6 m)
  // gait-reference, right lead: LH 0 (trailing hind), LF with RH ≈ .25–.30, RF (leading) ≈ .50–.55.
  g.touchdown_phase = {0.28, 0.52, 0.0, 0.27};
  // ≈: no canter duty factor in gait-reference; 0.36 keeps 1–3 hooves down and one suspension
  // (≈ 0.12 of the stride, 70 ms) after the leading fore.
  g.duty_factor = {0.36, 0.36, 0.37, 0.37};
  g.hoof_lift_cm = 18.0;                // gait-reference: more than walk and trot
  g.fore_lift_scale = 1.2;
  g.trunk_bounce_cm = 9.0;              // ≈; gait-reference: rises and falls once per stride
  g.trunk_cycles_per_stride = 1;
  g.trunk_low_phase = 0.33;             // lowest with three hooves down (LH, LF, RH)
  g.pitch_deg = 3.5;                    // gait-reference: pitch range ≈ 5–10° (7°)
  // Front end highest at .83, as the leading fore pushes off into the suspension, lowest at .33 with
  // three hooves down, and about level as the leading fore lands (.52). gait-reference gives the
  // range only; with the peak at .58 (a quarter stride after the low point, as at the trot) the
  // leading fore landed with the front end up, beyond the default horse's reach
  // (docs/horse-clips.md, "Legs").
  g.pitch_peak_after_low = 0.5;
  g.roll_deg = 1.5;
  g.neck_nod_deg = 6.0;
  g.tail_swing_deg = 8.0;
  if (lead == Lead::Left) {
    std::swap(g.touchdown_phase[0], g.touchdown_phase[1]);
    std::swap(g.touchdown_phase[2], g.touchdown_phase[3]);
    std::swap(g.duty_factor[0], g.duty_factor[1]);
    std::swap(g.duty_factor[2], g.duty_factor[3]);
    // Keep the trailing hind at phase 0 for the left lead too (RH trails).
    const double shift = g.touchdown_phase[3];
    for (double& p : g.touchdown_phase) p = wrap01(p - shift);
  }
  return g;
}

GaitParams gallopParams(double speed_cm_s, Lead lead) {
  GaitParams g;
  g.name = "gallop";
  // gait-reference (Witte 2006): 2.0 Hz at 9 m/s -> 2.4 Hz at 17 m/s; fore duty 0.26 -> 0.18,
  // hind stance 143 -> 94 ms. Interpolated linearly in speed, clamped to the measured range.
  const double u = std::clamp((speed_cm_s - 900.0) / 800.0, 0.0, 1.0);
  g.speed_cm_s = speed_cm_s;
  g.stride_hz = 2.0 + 0.4 * u;
  const double fore_duty = 0.26 - 0.08 * u;
  const double hind_duty = (0.143 - 0.049 * u) * g.stride_hz;
  // gait-reference transverse gallop, right lead: LH 0, RH .10, LF .50, RF .60 (Muybridge). With
  // Witte's stance times those phases leave a second airborne gap between RH lift-off and LF
  // touchdown, where gait-reference (and Kuhnel 5.3) count one suspension: we move the fore pair
  // earlier keeping its .10 lag, so that LF lands .026 of a stride before RH lifts off (LF .36, RF .46
  // at 9 m/s; LF .30, RF .40 at 17 m/s, where the hind stance is shorter), which leaves one suspension
  // after the leading fore at every speed (docs/horse-clips.md, "Gallop phases").
  const double lf = 0.36 - (0.143 * 2.0 - hind_duty);
  g.touchdown_phase = {lf, lf + 0.10, 0.0, 0.10};
  g.duty_factor = {fore_duty, fore_duty, hind_duty, hind_duty};
  g.hoof_lift_cm = 24.0;                // gait-reference: more than walk and trot
  g.fore_lift_scale = 1.2;
  g.trunk_bounce_cm = 10.0;             // ≈; once per stride as at the canter
  g.trunk_cycles_per_stride = 1;
  g.trunk_low_phase = 0.30;
  g.pitch_deg = 4.0;                    // gait-reference: pitch range ≈ 5–10° (8°)
  g.pitch_peak_after_low = 0.5;         // as at the canter: highest in the suspension after the fores
  g.roll_deg = 1.0;
  g.neck_nod_deg = 8.0;
  g.tail_swing_deg = 10.0;
  if (lead == Lead::Left) {
    std::swap(g.touchdown_phase[0], g.touchdown_phase[1]);
    std::swap(g.touchdown_phase[2], g.touchdown_phase[3]);
    const double shift = g.touchdown_phase[3];
    for (double& p : g.touchdown_phase) p = wrap01(p - shift);
  }
  return g;
}

std::optional<GaitParams> gaitParamsByName(const std::string& name, Lead lead) {
  if (name == "walk") return walkParams();
  if (name == "trot") return trotParams();
  if (name == "canter") return canterParams(lead);
  if (name == "gallop") return gallopParams(900.0, lead);
  return std::nullopt;
}

void addTrunkMotion(const GaitParams& g, double p, double gain, HorseFrame& f) {
  // Trunk: lowest at mid-stance, highest in the suspension between beats.
  const double cycles = static_cast<double>(g.trunk_cycles_per_stride);
  const double bounce = -0.5 * g.trunk_bounce_cm * std::cos(2 * kPi * cycles * (p - g.trunk_low_phase));
  f.controls[HorseChannel::rearPivotTy] += gain * bounce;
  // Pitch once per stride, front end up as the fore pair pushes off.
  f.controls[HorseChannel::rearPivotRz] +=
      gain * g.pitch_deg * std::sin(2 * kPi * (p - g.trunk_low_phase - g.pitch_peak_after_low + 0.25));
  // Roll toward the side whose hind leg is in stance.
  f.controls[HorseChannel::rearPivotRx] += gain * g.roll_deg * std::sin(2 * kPi * (p - g.touchdown_phase[2]));
  f.controls[HorseChannel::backMidRz] += gain * 0.3 * bounce;

  // Follow-through: the neck nods a quarter cycle after the trunk, the tail swings once per stride.
  const double neck = g.neck_nod_deg * std::sin(2 * kPi * cycles * (p - g.trunk_low_phase) - 0.5 * kPi);
  f.neck_rz += gain * neck;
  f.head_rz += gain * -0.5 * neck;
  f.tail_rz += gain * 0.5 * g.tail_swing_deg * std::cos(2 * kPi * cycles * (p - g.trunk_low_phase));
  f.tail_ry += gain * g.tail_swing_deg * std::sin(2 * kPi * p);
}

ProceduralGait::ProceduralGait(GaitParams params, double duration_s)
    : params_(std::move(params)), duration_s_(duration_s) {
  if (!(params_.speed_cm_s >= 0.0)) throw InputError("gait " + params_.name + ": speed must be >= 0");
  if (!(params_.stride_hz > 0.0)) throw InputError("gait " + params_.name + ": stride_hz must be > 0");
  for (double d : params_.duty_factor)
    if (!(d > 0.0 && d < 1.0))
      throw InputError("gait " + params_.name + ": duty factors must be between 0 and 1");
}

HorseFrame ProceduralGait::sample(double t) const {
  const GaitParams& g = params_;
  const double p = wrap01(t * g.stride_hz);
  HorseFrame f;
  f.travel_cm = g.speed_cm_s * t;

  static constexpr std::array<std::array<HorseChannel, 3>, 4> kHoofChannels = {{
      {HorseChannel::lfHoofTx, HorseChannel::lfHoofTy, HorseChannel::lfHoofTz},
      {HorseChannel::rfHoofTx, HorseChannel::rfHoofTy, HorseChannel::rfHoofTz},
      {HorseChannel::lbHoofTx, HorseChannel::lbHoofTy, HorseChannel::lbHoofTz},
      {HorseChannel::rbHoofTx, HorseChannel::rbHoofTy, HorseChannel::rbHoofTz},
  }};
  const double stride_cm = g.speed_cm_s / g.stride_hz;
  for (std::size_t i = 0; i < 4; ++i) {
    const bool fore = i < 2;
    const double stance_cm = stride_cm * g.duty_factor[i];
    const HoofState h = hoofAt(p, g.touchdown_phase[i], g.duty_factor[i], stance_cm,
                               g.hoof_lift_cm * (fore ? g.fore_lift_scale : 1.0));
    f.controls[kHoofChannels[i][0]] = h.tx;
    f.controls[kHoofChannels[i][1]] = h.ty;
    f.controls[kHoofChannels[i][2]] = 0.0;
  }

  addTrunkMotion(g, p, 1.0, f);
  return f;
}

}  // namespace stirrup::rig
