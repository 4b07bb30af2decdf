// Named camera views a scene can use without writing positions ("view": "side" in a camera block):
//   side      - orthographic, square to the horse's right side, travelling with the horse.
//   persp     - a three-quarter perspective from the front right (50 mm), following the horse.
//   close     - 85 mm on the rider's upper body and the saddle, following the rider's seat (its height damped),
//               so the rider's bounce reads against a steady frame.
//   turntable - 50 mm orbiting 360 degrees over orbit_frames (default 96) around horse and rider;
//               with `treadmill` the horse moves in place, with `hold_frame` it holds one pose.
//   top       - orthographic, fixed, straight down (image right = world +X, image up = world -Z), over
//               the whole ground track of the scene's frames: the travel and the characters, bounded
//               in (x, z), with frame_margin free at each border.
// The follow views (side, persp, close) turn with the horse's heading (scene/camera_motion.h).
// Each view is framed from the characters' skinned vertices over every frame it will show, seen
// through the camera's own motion: the camera is trucked so the extents are centred and then sized
// (orthographic height, or dollied back at a fixed lens) so that every point stays frame_margin inside
// every border. The horse and rider are then fully in frame for the whole movement (jumps and rears
// included); `close` frames only the rider above the saddle.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/clip.h"
#include "rig/rig_profile.h"
#include "scene/scene.h"

namespace stirrup::scene {

// Sets projection, lens, motion, up and direction of `spec` from its view (no-op when view is empty).
void applyViewPreset(CameraSpec& spec);

// The frames a view is framed over: the scene's frames, and 1..orbit_frames for an orbit.
std::vector<int> framingFrames(const CameraSpec& spec, const SceneSpec& scene);

// A frame's world positions of (a subset of) the horse's and the rider's skinned vertices, as shown,
// held by the caller (a PointArena: scene/point_arena.h) until frameView returns.
struct CharacterFramePoints {
  std::span<const glm::vec3> horse, rider;
};
// The points of each of `frames`: points (resized to one a frame) [k] is frames[k]'s.
using CharacterPoints = std::function<void(const std::vector<int>& frames, std::vector<CharacterFramePoints>& points)>;

// The view camera framed over `frames`: position, target and size resolved. `spec` must have a view.
CameraSpec frameView(CameraSpec spec, const SceneSpec& scene, const rig::Clip& clip,
                     const rig::RigProfile& profile, const std::vector<int>& frames,
                     const CharacterPoints& points);

}  // namespace stirrup::scene
