#include "rig/bake.h"

#include "rig/rider_rig.h"

namespace stirrup::rig {

BakedFrame bakeFrame(const Clip& clip, const RigProfile& profile, int frame, double seconds) {
  BakedFrame b;
  b.frame = frame;
  b.seconds = seconds;
  b.horse = clip.sample(seconds);
  b.rider = evaluateRider(b.horse.controls, profile);
  return b;
}

}  // namespace stirrup::rig
