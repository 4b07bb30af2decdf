#include "rig/bake.h"

#include <cmath>

#include "rig/rider_rig.h"

namespace stirrup::rig {

glm::dvec2 travelAccelerationOnGround(const Clip& clip, double seconds) {
  // The second difference of the travel frame's ground position over kAccelerationWindowS: the
  // acceleration averaged under a triangle of that half-width, so a braking that starts at once (the
  // stop) eases the rider's lean in over a fifth of a second instead of snapping it in one frame.
  // Before t = 0 a clip may clamp (a movement starting at a gallop would seem to jump from rest), so
  // the stencil starts at t = 0 there.
  constexpr double h = kAccelerationWindowS;
  const double t0 = seconds - h >= 0.0 ? seconds - h : seconds;
  const HorseFrame a = clip.sampleTravel(t0), b = clip.sampleTravel(t0 + h), c = clip.sampleTravel(t0 + 2.0 * h);
  return {(a.travel_cm - 2.0 * b.travel_cm + c.travel_cm) / (h * h),
          (a.travel_z_cm - 2.0 * b.travel_z_cm + c.travel_z_cm) / (h * h)};
}

namespace {

// Along the heading at `seconds` (x) and square to it, + toward the horse's right (y): in a path
// clip's turn the sideways part is the centripetal acceleration.
glm::dvec2 accelerationInTravelFrame(const Clip& clip, double seconds, double heading_deg) {
  const glm::dvec2 a = travelAccelerationOnGround(clip, seconds);
  const double heading = heading_deg * 3.14159265358979323846 / 180.0;
  // The heading turns from +X toward +Z (rig/clip.h), so the horse's right is (-sin, cos) on the ground.
  return {a.x * std::cos(heading) + a.y * std::sin(heading), -a.x * std::sin(heading) + a.y * std::cos(heading)};
}

}  // namespace

double travelAcceleration(const Clip& clip, double seconds) {
  return accelerationInTravelFrame(clip, seconds, clip.sampleTravel(seconds).heading_deg).x;
}

BakedFrame bakeFrame(const Clip& clip, const RigProfile& profile, int frame, double seconds) {
  BakedFrame b;
  b.frame = frame;
  b.seconds = seconds;
  b.horse = clip.sample(seconds);
  const glm::dvec2 a = accelerationInTravelFrame(clip, seconds, b.horse.heading_deg);
  b.horse.travel_accel_cm_s2 = a.x;
  b.horse.travel_side_accel_cm_s2 = a.y;
  b.rider = evaluateRider(b.horse.controls, profile);
  return b;
}

}  // namespace stirrup::rig
