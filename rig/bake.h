// The bake job: sample the clip, then evaluate the rider controls from the horse controls.
// Explicit inputs and outputs, no state: frame N can be baked alone, on any machine, in any order.
#pragma once

#include <glm/vec2.hpp>

#include "rig/clip.h"
#include "rig/rig_profile.h"

namespace stirrup::rig {

struct BakedFrame {
  int frame = 1;
  double seconds = 0.0;
  HorseFrame horse;
  RiderChannels rider;
};

// Samples the clip at `seconds` (with the travel's acceleration, travelAcceleration) and evaluates
// the rider channels.
BakedFrame bakeFrame(const Clip& clip, const RigProfile& profile, int frame, double seconds);

// The clip's travel acceleration at `seconds` (cm/s²), by a second difference of its travel over
// kAccelerationWindowS each side: smoothed, so a lean that follows it never jumps between frames.
// travelAccelerationOnGround is the whole of it in the ground plane, (world x, world z): in a turn it
// holds the centripetal part, toward the turn's centre. travelAcceleration is its part along the
// heading, which the balance stage leans against (HorseFrame::travel_accel_cm_s2); bakeFrame also
// keeps the sideways part (HorseFrame::travel_side_accel_cm_s2), whose tilt of the apparent vertical
// the stage answers in a turn.
inline constexpr double kAccelerationWindowS = 0.2;
glm::dvec2 travelAccelerationOnGround(const Clip& clip, double seconds);
double travelAcceleration(const Clip& clip, double seconds);

}  // namespace stirrup::rig
