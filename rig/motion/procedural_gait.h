// A procedural horse gait from a footfall schedule: per-hoof touchdown phase and duty factor, a stride
// frequency and a speed. Hooves that are down stay put in the world; hooves in the air follow a smooth
// arc highest at mid-swing; the trunk rises, falls, pitches and rolls locked to the footfalls.
// Defaults match docs/gait-reference.md (the trot: 3.6 m/s, 1.26 Hz, duty factor 0.40).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "rig/clip.h"

namespace stirrup::rig {

enum class Hoof { LeftFore = 0, RightFore = 1, LeftHind = 2, RightHind = 3 };

struct GaitParams {
  std::string name = "trot";
  double speed_cm_s = 360.0;         // gait-reference: trot 3.6 ± 0.1 m/s (Gómez Álvarez 2009)
  double stride_hz = 1.26;           // gait-reference: stride 794 ± 14 ms (Holmström)
  // Touchdown phase per hoof as a fraction of the stride, left hind = 0 (gait-reference table),
  // indexed by Hoof. Trot: diagonal pairs, the hind of each pair landing ~30 ms before its fore.
  std::array<double, 4> touchdown_phase = {0.5 + 0.038, 0.038, 0.0, 0.5};
  std::array<double, 4> duty_factor = {0.40, 0.40, 0.40, 0.40};  // trot ≈ 0.35–0.45
  double hoof_lift_cm = 14.0;        // peak hoof height at mid-swing, walk/trot ≈ 10–20 cm
  double fore_lift_scale = 1.15;     // forelegs fold higher than hind legs at the trot
  // Trunk: vertical peak to peak at the hips, cycles per stride (2 at the trot, 1 at the canter),
  // and the phase of the lowest point (mid-stance of the first diagonal pair).
  double trunk_bounce_cm = 6.0;      // withers ≈ 7 cm p-p at the trot (Buchner 2000)
  int trunk_cycles_per_stride = 2;
  double trunk_low_phase = 0.22;
  double pitch_deg = 1.5;            // amplitude; trot trunk pitch range ≈ 2–4°
  // Where in the stride the front end is highest, after the lowest point of the trunk (fraction of a
  // stride; the pitch rises through zero at the lowest point plus this, less a quarter).
  double pitch_peak_after_low = 0.25;
  double roll_deg = 1.0;             // amplitude, once per stride
  double neck_nod_deg = 2.0;         // head and neck nod with the bounce
  double tail_swing_deg = 6.0;
};

enum class Lead { Left, Right };

GaitParams trotParams();
GaitParams walkParams();
GaitParams canterParams(Lead lead = Lead::Right);
// Transverse gallop at 9–17 m/s: stride frequency and fore duty factor follow Witte et al. 2006.
GaitParams gallopParams(double speed_cm_s = 900.0, Lead lead = Lead::Right);
// The named gait ("walk", "trot", "canter", "gallop"), or nullopt.
std::optional<GaitParams> gaitParamsByName(const std::string& name, Lead lead = Lead::Right);

// The trunk and body follow-through of a gait at stride phase p (rearPivot ty/rx/rz, backMid.rz, neck,
// head, tail), scaled by `gain` and added to `f`. Hoof channels and travel are left alone.
void addTrunkMotion(const GaitParams& g, double p, double gain, HorseFrame& f);

class ProceduralGait final : public Clip {
 public:
  explicit ProceduralGait(GaitParams params, double duration_s = 10.0);

  std::string name() const override { return params_.name; }
  double duration() const override { return duration_s_; }
  HorseFrame sample(double seconds) const override;

  const GaitParams& params() const { return params_; }
  double strideLengthCm() const { return params_.speed_cm_s / params_.stride_hz; }

 private:
  GaitParams params_;
  double duration_s_;
};

}  // namespace stirrup::rig
