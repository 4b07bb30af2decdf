#include "rig/bake.h"

#include "rig/rider_rig.h"

namespace stirrup::rig {

double travelAcceleration(const Clip& clip, double seconds) {
  // A second difference over kAccelerationWindowS: the acceleration averaged under a triangle of that
  // half-width, so a braking that starts at once (the stop) eases the rider's lean in over a fifth of
  // a second instead of snapping it in one frame. Before t = 0 a clip may clamp (a movement starting
  // at a gallop would seem to jump from rest), so the stencil starts at t = 0 there.
  constexpr double h = kAccelerationWindowS;
  const double t0 = seconds - h >= 0.0 ? seconds - h : seconds;
  const double a = clip.sample(t0).travel_cm, b = clip.sample(t0 + h).travel_cm, c = clip.sample(t0 + 2.0 * h).travel_cm;
  return (a - 2.0 * b + c) / (h * h);
}

BakedFrame bakeFrame(const Clip& clip, const RigProfile& profile, int frame, double seconds) {
  BakedFrame b;
  b.frame = frame;
  b.seconds = seconds;
  b.horse = clip.sample(seconds);
  b.horse.travel_accel_cm_s2 = travelAcceleration(clip, seconds);
  b.rider = evaluateRider(b.horse.controls, profile);
  return b;
}

}  // namespace stirrup::rig
