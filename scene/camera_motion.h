// Camera motion: where a scene camera (CameraSpec) is at a frame, as a pure function of the frame, so
// any frame renders alone, in any order, on any machine.
//   fixed  - position and target in the world.
//   follow - position and target in a frame that follows a point and turns with the horse: the
//            horse's travel frame origin ((travel, ground_y, travel_z): on the ground, over hills) or
//            the rider's seat (the saddle turned about the rear pivot as the body pitches and rolls,
//            plus the rider's cog offsets). Across the frame (x, z) the point is followed exactly, so
//            the subject holds its place however the horse speeds up, slows down or rears; with
//            damping_s > 0 its height (the bob, and the ground's rise and fall) is smoothed by a
//            critically damped filter of that time constant with velocity feed-forward (see
//            dampedFollow), evaluated by resampling the clip over the preceding 10 time constants: no
//            state is carried from one frame to the next. The camera turns about the vertical through
//            the point by the horse's heading (issue 15: a side view stays square to the horse's side
//            through a turn), smoothed by the same filter applied to the heading's direction
//            (cos, sin), so a turn at a steady rate w lags by only ~8 (w tau)^3 radians (1.4° on a
//            circle of 10 m radius at 5 m/s with tau 0.3 s) and wrapping at
//            ±180° needs no care. A straight clip has heading 0: no turn, the frames of before.
//   orbit  - the follow camera (undamped, horse's travel) turned about the vertical through its
//            target by orbit_deg_per_frame (or 360 / orbit_frames) per frame after frame 1.
// A treadmill camera follows nothing along X (the horse moves in place); a held pose camera follows
// the held frame's point.
#pragma once

#include <functional>

#include <glm/vec3.hpp>

#include "rig/clip.h"
#include "rig/rig_profile.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace stirrup::scene {

// The critically damped response to a path p(t), lag-free for constant velocity:
//   y(t) = integral over s >= 0 of h(s) [p(t - s) + s p'(t - s)] ds,  h(s) = s e^(-s/tau) / tau^2.
// Its transfer function is (1 + 3 i w tau) / (1 + i w tau)^3: 1 at rest, a ramp (steady travel) is
// followed exactly, a bob at w tau = 5 is cut to 12%. tau <= 0 returns p(t). Times before 0 see the
// path extrapolated from t = 0 at its mean velocity over [0, 10 tau] (the camera starts steady).
glm::dvec3 dampedFollow(const std::function<glm::dvec3(double)>& path, double t, double tau);

// The point a follow camera follows, in the world, at `seconds` (before damping).
glm::dvec3 followPoint(const CameraSpec& spec, const rig::Clip& clip, const rig::RigProfile& profile,
                       double seconds);
// The horse's travel frame's origin ((travel, ground_y, travel_z); 0 on a treadmill) at `seconds`.
glm::dvec3 travelPoint(const CameraSpec& spec, const rig::Clip& clip, double seconds);
// Where a follow camera is moved to at `seconds`: the followed point, its height damped by
// dampedFollow with time constant tau.
glm::dvec3 followOffset(const CameraSpec& spec, const rig::Clip& clip, const rig::RigProfile& profile,
                        double seconds, double tau);

// Where a follow camera is at `seconds` and which way it faces: followOffset's point, and the heading
// (degrees from +X toward +Z) it turns by, the horse's heading damped by tau as described above.
struct FollowFrame {
  glm::dvec3 point;
  double heading_deg = 0.0;
};
FollowFrame followFrame(const CameraSpec& spec, const rig::Clip& clip, const rig::RigProfile& profile,
                        double seconds, double tau);

// `v` (in a follow camera's frame) turned about the vertical by heading_deg, as rig::travelMatrix turns
// the horse: +X toward +Z.
glm::dvec3 turnByHeading(const glm::dvec3& v, double heading_deg);
// turnByHeading for many vectors by one heading, its cosine and sine found once: the same bits.
class HeadingTurn {
 public:
  explicit HeadingTurn(double heading_deg);
  glm::dvec3 operator()(const glm::dvec3& v) const;

 private:
  bool none_;  // heading 0 exactly: straight clips keep the frames they had
  double c_ = 1.0, s_ = 0.0;
};

// The heading a camera is turned by at `frame` (0 for fixed and orbit cameras).
double cameraHeadingAtFrame(const CameraSpec& spec, const SceneSpec& scene, const rig::Clip& clip,
                            const rig::RigProfile& profile, int frame);

// Where the camera's motion puts it at `frame`, apart from its own position and target: a follow
// camera's followFrame (its point and heading), an orbit's undamped followed point (heading 0), nothing
// for a fixed camera. It reads only the spec's motion, follow_target, treadmill, seat_from_pivot_cm,
// damping_s and hold_frame, so framing a view (scene/view.h), which moves and sizes the camera
// pass after pass, finds it once a frame. The follow filter samples the clip some 600 times; this is
// all of a camera's cost.
FollowFrame cameraFollowAtFrame(const CameraSpec& spec, const SceneSpec& scene, const rig::Clip& clip,
                                const rig::RigProfile& profile, int frame);

// The render camera of `spec` at `frame`, its motion's part given (cameraFollowAtFrame of the same spec,
// or of one that differs only in position, target, lens and size).
Camera cameraFromFollow(const CameraSpec& spec, const FollowFrame& follow, int frame);

// The render camera of `spec` at `frame` of `scene`: cameraFromFollow(spec, cameraFollowAtFrame(...)).
Camera cameraAtFrame(const CameraSpec& spec, const SceneSpec& scene, const rig::Clip& clip,
                     const rig::RigProfile& profile, int frame);

}  // namespace stirrup::scene
