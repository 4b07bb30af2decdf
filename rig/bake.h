// The bake job: sample the clip, then evaluate the rider controls from the horse controls.
// Explicit inputs and outputs, no state: frame N can be baked alone, on any machine, in any order.
#pragma once

#include "rig/clip.h"
#include "rig/rig_profile.h"

namespace stirrup::rig {

struct BakedFrame {
  int frame = 1;
  double seconds = 0.0;
  HorseFrame horse;
  RiderChannels rider;
};

BakedFrame bakeFrame(const Clip& clip, const RigProfile& profile, int frame, double seconds);

}  // namespace stirrup::rig
