#include "scene/camera_motion.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "rig/rider_rig.h"
#include "rig/units.h"

namespace stirrup::scene {
namespace {


glm::dvec3 dvec3Of(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

glm::dvec3 dampedFollow(const std::function<glm::dvec3(double)>& path, double t, double tau) {
  if (!(tau > 0.0)) return path(t);
  constexpr double kDerivStep = 1.0 / 480.0;
  // Before t = 0 the path continues at its mean velocity over the first window (steady travel
  // continues; a bob or a stride is not extrapolated).
  const glm::dvec3 p0 = path(0.0);
  const glm::dvec3 v0 = (path(10.0 * tau) - p0) / (10.0 * tau);
  auto at = [&](double u) { return u >= 0.0 ? path(u) : p0 + v0 * u; };
  auto velocity = [&](double u) {
    if (u < 0.0) return v0;
    const double lo = std::max(0.0, u - kDerivStep);
    return (at(u + kDerivStep) - at(lo)) / (u + kDerivStep - lo);
  };
  // Midpoint rule over [0, 10 tau] (the kernel's weight beyond it is 5e-4), normalised by the
  // discrete weights so a constant path is returned exactly.
  constexpr int kSteps = 200;
  const double ds = 10.0 * tau / kSteps;
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double s = (i + 0.5) * ds;
    const double h = s * std::exp(-s / tau);
    sum += h * (at(t - s) + s * velocity(t - s));
    weight += h;
  }
  return sum / weight;
}

namespace {

glm::dvec3 travelPointOf(const CameraSpec& spec, const rig::HorseFrame& f) {
  if (spec.treadmill) return glm::dvec3(0.0);
  return {f.travel_cm, f.ground_y_cm, f.travel_z_cm};
}

// followPoint of an already sampled frame (the follow filter samples each time once for the point and
// the heading both).
glm::dvec3 followPointOf(const CameraSpec& spec, const rig::HorseFrame& horse, const rig::RigProfile& profile) {
  if (spec.follow_target == "rider") {
    // The horse and the rider channels only (not bakeFrame: the follow filter calls this hundreds of
    // times a frame, and the travel acceleration bakeFrame adds costs four more clip samples).
    const rig::RiderChannels rider = rig::evaluateRider(horse.controls, profile);
    using H = rig::HorseChannel;
    using R = rig::RiderChannel;
    const rig::HorseChannels& h = horse.controls;
    // The seat: the saddle's rest place turned about the rear pivot as rig::poseHorse turns the body
    // (about -Y by ry, then +Z by rz, then +X by rx), plus the rider's cog offsets in the saddle's frame.
    const glm::dmat3 turn = glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(-h[H::rearPivotRy]), glm::dvec3(0, 1, 0)) *
                                       glm::rotate(glm::dmat4(1.0), glm::radians(h[H::rearPivotRz]), glm::dvec3(0, 0, 1)) *
                                       glm::rotate(glm::dmat4(1.0), glm::radians(h[H::rearPivotRx]), glm::dvec3(1, 0, 0)));
    const glm::dvec3 lever = dvec3Of(spec.seat_from_pivot_cm);
    const glm::dvec3 cog(rider[R::cogTx] * profile.rider_unit_cm, rider[R::cogTy] * profile.rider_unit_cm, 0.0);
    const glm::dvec3 pivot(h[H::rearPivotTx], h[H::rearPivotTy], h[H::rearPivotTz]);
    // In the travel frame (along and up: the seat's sway to the side is not followed), then turned
    // by its heading (about -Y, as rig::travelMatrix).
    const glm::dvec3 seat = pivot + turn * (lever + cog) - lever;
    const double a = glm::radians(horse.heading_deg);
    return travelPointOf(spec, horse) + glm::dvec3(seat.x * std::cos(a), seat.y, seat.x * std::sin(a));
  }
  return travelPointOf(spec, horse);
}

// The clip at `seconds` as far as the followed point and the heading need it: the travel frame alone
// unless the camera follows the rider's seat, which reads the horse's channels.
rig::HorseFrame sampleFollowed(const CameraSpec& spec, const rig::Clip& clip, double seconds) {
  return spec.follow_target == "rider" ? clip.sample(seconds) : clip.sampleTravel(seconds);
}

}  // namespace

glm::dvec3 travelPoint(const CameraSpec& spec, const rig::Clip& clip, double seconds) {
  return travelPointOf(spec, clip.sampleTravel(seconds));
}

glm::dvec3 followPoint(const CameraSpec& spec, const rig::Clip& clip, const rig::RigProfile& profile,
                       double seconds) {
  return followPointOf(spec, sampleFollowed(spec, clip, seconds), profile);
}

glm::dvec3 followOffset(const CameraSpec& spec, const rig::Clip& clip, const rig::RigProfile& profile,
                        double seconds, double tau) {
  return followFrame(spec, clip, profile, seconds, tau).point;
}

FollowFrame followFrame(const CameraSpec& spec, const rig::Clip& clip, const rig::RigProfile& profile,
                        double seconds, double tau) {
  // Only the height is damped (the bob); across the frame the followed point is followed exactly.
  // Damping the travel too made the camera overshoot where the horse decelerates (the filter is
  // lag-free only for constant speed): in stop_close the rider drifted from 76% to 18% of the frame's
  // width, and in the rear, where the seat swings 30 cm back as the body rises, by 21%.
  const rig::HorseFrame now = sampleFollowed(spec, clip, seconds);
  const glm::dvec3 point = followPointOf(spec, now, profile);
  FollowFrame out;
  if (!(tau > 0.0)) {
    out.point = point;
    out.heading_deg = now.heading_deg;
    return out;
  }
  // One filter pass for the height (y) and the heading's direction (x = cos, z = sin): the filter
  // works on each component alone, so the height is exactly what it is filtered alone.
  const glm::dvec3 damped = dampedFollow(
      [&](double u) {
        const rig::HorseFrame f = sampleFollowed(spec, clip, u);
        const double a = glm::radians(f.heading_deg);
        return glm::dvec3(std::cos(a), followPointOf(spec, f, profile).y, std::sin(a));
      },
      seconds, tau);
  out.point = {point.x, damped.y, point.z};
  out.heading_deg = glm::degrees(std::atan2(damped.z, damped.x));
  return out;
}

HeadingTurn::HeadingTurn(double heading_deg) : none_(heading_deg == 0.0) {
  if (none_) return;
  const double a = glm::radians(heading_deg);
  c_ = std::cos(a);
  s_ = std::sin(a);
}

glm::dvec3 HeadingTurn::operator()(const glm::dvec3& v) const {
  if (none_) return v;  // exactly: straight clips keep the frames they had
  return {v.x * c_ - v.z * s_, v.y, v.x * s_ + v.z * c_};
}

glm::dvec3 turnByHeading(const glm::dvec3& v, double heading_deg) { return HeadingTurn(heading_deg)(v); }

double cameraHeadingAtFrame(const CameraSpec& spec, const SceneSpec& scene, const rig::Clip& clip,
                            const rig::RigProfile& profile, int frame) {
  if (spec.motion != "follow") return 0.0;
  return cameraFollowAtFrame(spec, scene, clip, profile, frame).heading_deg;
}

FollowFrame cameraFollowAtFrame(const CameraSpec& spec, const SceneSpec& scene, const rig::Clip& clip,
                                const rig::RigProfile& profile, int frame) {
  if (spec.motion == "fixed") return {};
  const int shown = spec.hold_frame > 0 ? spec.hold_frame : frame;
  const double t = frameTime(scene, shown);
  if (spec.motion == "orbit") return {followPoint(spec, clip, profile, t), 0.0};
  return followFrame(spec, clip, profile, t, spec.hold_frame > 0 ? 0.0 : spec.damping_s);
}

Camera cameraFromFollow(const CameraSpec& spec, const FollowFrame& follow, int frame) {
  Camera c;
  c.projection = spec.orthographic ? Camera::Projection::Orthographic : Camera::Projection::Perspective;
  c.fov_deg = spec.fov_deg;
  c.ortho_height_cm = spec.ortho_height_cm;
  c.up = dvec3Of(spec.up);
  glm::dvec3 position = dvec3Of(spec.position);
  glm::dvec3 target = dvec3Of(spec.target);
  if (spec.motion == "fixed") {
    c.position = position;
    c.target = target;
    return c;
  }
  if (spec.motion == "orbit") {
    const double deg = spec.orbit_frames > 0 ? 360.0 / spec.orbit_frames : spec.orbit_deg_per_frame;
    const double a = deg * (frame - 1) * rig::kPi / 180.0;
    const glm::dvec3 rel = position - target;
    // Counter-clockwise seen from above: from the horse's right side (+Z) toward its front (+X).
    position = target + glm::dvec3(rel.x * std::cos(a) + rel.z * std::sin(a), rel.y,
                                   -rel.x * std::sin(a) + rel.z * std::cos(a));
  } else {
    position = turnByHeading(position, follow.heading_deg);
    target = turnByHeading(target, follow.heading_deg);
  }
  c.position = position + follow.point;
  c.target = target + follow.point;
  return c;
}

Camera cameraAtFrame(const CameraSpec& spec, const SceneSpec& scene, const rig::Clip& clip,
                     const rig::RigProfile& profile, int frame) {
  return cameraFromFollow(spec, cameraFollowAtFrame(spec, scene, clip, profile, frame), frame);
}

}  // namespace stirrup::scene
