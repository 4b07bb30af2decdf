// A shot: one scene seen through one of its cameras. Renders any frame on its own, running the whole
// pipeline for that frame: sample clip -> evaluate rider controls -> pose -> skin -> trace.
#pragma once

#include <memory>
#include <vector>

#include "render/camera.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "rig/bake.h"
#include "rig/character.h"
#include "rig/procedural_gait.h"

namespace stirrup::render {

// Timings of the last frame, in milliseconds, for progress reports and benchmarks.
struct FrameTimings {
  double pose_ms = 0, skin_ms = 0, trace_ms = 0;
};

class Shot {
 public:
  // threads: 0 = all cores. The profile is resolved by the caller (name, file and overrides).
  Shot(const SceneSpec& scene, const rig::RigProfile& profile, const CameraSpec& camera, int threads);
  ~Shot();

  Image renderFrame(int frame);
  rig::BakedFrame bake(int frame) const;
  const FrameTimings& lastTimings() const { return timings_; }

  // The render camera at a frame (follow cameras travel with the horse).
  Camera cameraAt(const rig::BakedFrame& baked) const;

 private:
  SceneSpec scene_;
  rig::RigProfile profile_;
  CameraSpec camera_;
  std::unique_ptr<rig::Clip> clip_;  // from scene.clip (rig::makeClip)
  rig::Character horse_, rider_;
  std::unique_ptr<Renderer> renderer_;
  int horse_mesh_ = -1, rider_mesh_ = -1;
  std::vector<glm::vec3> positions_, normals_;
  FrameTimings timings_;
};

}  // namespace stirrup::render
