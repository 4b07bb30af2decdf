#include "rig/pose.h"

#include <algorithm>
#include <cmath>

namespace stirrup::rig {

MountedPose poseMounted(const Character& horse, const Character& rider, const HorseFrame& frame,
                        const RiderChannels& channels, const RigProfile& profile) {
  const double unit = profile.rider_unit_cm;
  const RiderPoseParams params;
  // In a turn her roll channels answer the horse's roll from the apparent vertical (rig/balance.h); on a
  // straight line, and for the rigid rider, the tilt is 0 and the channels are posed as they are.
  const double tilt = profile.rigid ? 0.0 : turnTiltDegrees(frame.travel_side_accel_cm_s2, profile.balance);
  const RiderChannels r = limitRiderChannels(answerTiltedVertical(channels, frame.controls, profile, tilt), params, unit);
  MountedPose p;
  p.horse = poseHorse(horse, frame, {}, &p.reach);
  placeStirrups(horse, p.horse, r, unit);
  if (profile.rigid) {
    p.rider = poseRider(rider, horse, p.horse, r, unit, params);
  } else {
    BalanceStage stage;
    stage.params = profile.balance;
    const double asked = std::abs(torsoFold(channels, params)), allowed = std::abs(torsoFold(r, params));
    stage.fold_scale = allowed > 1e-9 ? std::max(asked / allowed, 1.0) : 1.0;
    stage.accel_cm_s2 = frame.travel_accel_cm_s2;
    stage.ground_pitch_deg = frame.ground_pitch_deg;
    p.rider = poseRider(rider, horse, p.horse, r, unit, params, &stage, &p.balance);
    p.balance.turn_tilt_deg = tilt;
  }
  placeReins(horse, p.horse, rider, p.rider);
  return p;
}

}  // namespace stirrup::rig
