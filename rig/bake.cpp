#include "rig/bake.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

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

// The rig takes only finite numbers: every number a scene, mapping, profile or crowd holds is checked
// at load (issue 60), so a NaN or an infinity here is a fault of the program, never of the input. Named,
// with the clip and time, rather than left to surface later as a bent spine or a blank frame.
void requireFinite(double v, const Clip& clip, double seconds, const std::string& what) {
  if (std::isfinite(v)) return;
  throw std::logic_error("bakeFrame: the clip \"" + clip.name() + "\" at " + std::to_string(seconds) + " s: " + what + " is " +
                         std::to_string(v) + " (a number that is not finite reached the rig)");
}

void requireFinite(const BakedFrame& b, const Clip& clip) {
  const HorseFrame& h = b.horse;
  for (std::size_t c = 0; c < kHorseChannelCount; ++c) requireFinite(h.controls.value[c], clip, b.seconds, std::string(kHorseChannelNames[c]));
  for (std::size_t c = 0; c < kRiderChannelCount; ++c) requireFinite(b.rider.value[c], clip, b.seconds, std::string(kRiderChannelNames[c]));
  const std::pair<const char*, double> travel[] = {
      {"travel_cm", h.travel_cm}, {"travel_z_cm", h.travel_z_cm}, {"heading_deg", h.heading_deg},
      {"travel_accel_cm_s2", h.travel_accel_cm_s2}, {"travel_side_accel_cm_s2", h.travel_side_accel_cm_s2},
      {"ground_y_cm", h.ground_y_cm}, {"ground_pitch_deg", h.ground_pitch_deg}, {"neck_rz", h.neck_rz}, {"head_rz", h.head_rz},
      {"tail_rz", h.tail_rz}, {"tail_ry", h.tail_ry}};
  for (const auto& [what, v] : travel) requireFinite(v, clip, b.seconds, what);
  for (std::size_t leg = 0; leg < 4; ++leg) requireFinite(h.hoof_ground_cm[leg], clip, b.seconds, "hoof_ground_cm[" + std::to_string(leg) + "]");
}

}  // namespace

double travelAcceleration(const Clip& clip, double seconds) {
  return accelerationInTravelFrame(clip, seconds, clip.sampleTravel(seconds).heading_deg).x;
}

BakedFrame bakeFrame(const Clip& clip, const RigProfile& profile, int frame, double seconds) {
  requireFinite(seconds, clip, 0.0, "the time");
  BakedFrame b;
  b.frame = frame;
  b.seconds = seconds;
  b.horse = clip.sample(seconds);
  const glm::dvec2 a = accelerationInTravelFrame(clip, seconds, b.horse.heading_deg);
  b.horse.travel_accel_cm_s2 = a.x;
  b.horse.travel_side_accel_cm_s2 = a.y;
  b.rider = evaluateRider(b.horse.controls, profile);
  requireFinite(b, clip);
  return b;
}

}  // namespace stirrup::rig
