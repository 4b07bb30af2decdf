// Posing a horse and its rider: the one call every consumer (shot, bake, tests) makes, poseMounted,
// over the three posing jobs it runs in order: the horse (rig/horse_pose.h), the tack (rig/tack_pose.h)
// and the rider (rig/rider_pose.h). Explicit inputs, explicit outputs, no hidden state. Each returns
// world matrices, one per joint of the character's skeleton, for skinMesh.
//
// Signs follow docs/channels.md by meaning. In the world (+X travel, +Y up, +Z the horse's
// right): "front end up" is a rotation about +Z, "roll toward the right" about +X, "yaw to the
// right" about -Y. A rider's "lean forward" is about -Z, "lean to her right" about +X. Where the
// contract leaves a rider's sense open, rig/rider_pose.h says what was decided.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "rig/balance.h"
#include "rig/channels.h"
#include "rig/character.h"
#include "rig/clip.h"
#include "rig/horse_pose.h"
#include "rig/rider_pose.h"
#include "rig/rig_profile.h"
#include "rig/tack_pose.h"

namespace stirrup::rig {

// Both characters at one frame, the way every consumer (shot, bake, tests) poses them: poseHorse,
// placeStirrups, poseRider with the profile's balance stage, placeReins. World matrices, one per joint
// of each skeleton. The rigid rider (profile.rigid) has no balance stage: she rides like a statue.
struct MountedPose {
  std::vector<glm::mat4> horse, rider;
  HorseReach reach;       // hooves short of their targets (poseHorse)
  BalanceResult balance;  // what the balance stage decided (all zero for the rigid rider)
};
MountedPose poseMounted(const Character& horse, const Character& rider, const HorseFrame& frame,
                        const RiderChannels& r, const RigProfile& profile);

}  // namespace stirrup::rig
