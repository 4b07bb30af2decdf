// The contract's three rotation channels of a control (docs/channels.md) as one rotation, and back: rz +
// pitches the front up (about +Z, X toward Y), rx + rolls toward the right (about +X, Y toward +Z), ry +
// yaws to the right (about -Y), composed yaw, then pitch, then roll: R = Ry(-ry) * Rz(rz) * Rx(rx). Clip
// files store rotations this way (rig/io/gltf_clip.h), and a keyed horse's controls are read back this
// way (rig/io/keyed_horse_clip.h).
#pragma once

#include <array>

#include <glm/gtc/quaternion.hpp>

namespace stirrup::rig {

// Degrees in; the rotation.
glm::dquat rotationFromChannels(double rx, double ry, double rz);
// The rotation's channels in degrees: {rx, ry, rz}.
std::array<double, 3> channelsFromRotation(const glm::dquat& q);

}  // namespace stirrup::rig
