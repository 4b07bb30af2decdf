// One camera of a shot, resolved against the shot's characters: a view (scene/view.h) framed from
// their skinned vertices over every frame it shows, evaluated by the shot's evaluator
// (scene/shot_evaluator.h); the clip a follow camera travels with (a single pair's clip, a crowd's
// followed pair at its start phase, or the crowd's middle: rig/motion/crowd_middle_clip.h) and the
// profile it reads the rider's seat with. Both the renderer's shot (render/shot.h) and the bake
// (stirrup bake) take their cameras from here, so a baked camera is the rendered one.
#pragma once

#include <memory>

#include "rig/clip.h"
#include "rig/rig_profile.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/shot_evaluator.h"

namespace stirrup::scene {

class ShotCamera {
 public:
  // Checks the camera against the scene (a crowd's follow_pair in range, no treadmill in a crowd:
  // one-line InputErrors naming the scene file and the camera's field) and frames a view from the
  // characters. `characters` is used only while constructing; it must outlive this (its clips do).
  ShotCamera(ShotEvaluator& characters, const CameraSpec& camera);
  ~ShotCamera();

  // The camera as resolved (a view's position, target and size framed).
  const CameraSpec& spec() const { return spec_; }
  // What it follows and the profile it reads the seat with: the followed pair's (the first pair's for a
  // crowd's middle, whose controls are at rest, so only its rider_unit_cm matters).
  const rig::Clip& clip() const { return *clip_; }
  const rig::RigProfile& profile() const { return *profile_; }
  // The render camera at a frame (scene/camera_motion.h).
  Camera at(int frame) const;

 private:
  const SceneSpec& scene_;
  CameraSpec spec_;
  std::unique_ptr<rig::Clip> owned_clip_;  // the crowd's middle, when it follows no pair
  const rig::Clip* clip_ = nullptr;
  const rig::RigProfile* profile_ = nullptr;
};

}  // namespace stirrup::scene
