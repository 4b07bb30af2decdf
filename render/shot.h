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
#include "rig/motion/procedural_gait.h"

namespace stirrup::render {

// Timings of the last frame, in milliseconds, for progress reports and benchmarks.
struct FrameTimings {
  double pose_ms = 0, skin_ms = 0, trace_ms = 0;
  double bvh_ms = 0;   // the BVH update, part of trace_ms
  uint64_t rays = 0;   // camera, shadow and sky rays of the frame
};

class Shot {
 public:
  // threads: 0 = all cores. The profile is resolved by the caller (name, file and overrides).
  // `bvh`: how the BVH follows the characters (the default is the renderer's; others for benchmarks).
  Shot(const SceneSpec& scene, const rig::RigProfile& profile, const CameraSpec& camera, int threads,
       BvhUpdate bvh = RenderSettings{}.bvh_update);
  ~Shot();

  // With `log`, the frame's rays are also kept in it (see Renderer::render).
  Image renderFrame(int frame, RayLog* log = nullptr);
  Renderer& renderer() { return *renderer_; }
  rig::BakedFrame bake(int frame) const;
  const FrameTimings& lastTimings() const { return timings_; }

  // The render camera at a frame (follow cameras travel with the horse; render/camera_motion.h).
  Camera cameraAt(const rig::BakedFrame& baked) const;
  Camera cameraAtFrame(int frame) const;
  // The camera as resolved: a view camera (render/view.h) framed from the characters' bounds over
  // the clip when the Shot was made.
  const CameraSpec& camera() const { return camera_; }
  // World positions of every `stride`-th skinned vertex of the horse and the rider at a frame, as it
  // is shown (a treadmill camera removes the travel, a held pose holds its frame).
  void characterPoints(int frame, int stride, std::vector<glm::dvec3>& horse, std::vector<glm::dvec3>& rider);
  // The rider rigidly fixed to the saddle (every rider channel at rest): what the rig adds, for the
  // layered comparison (render/review/layer.h).
  void setRigidRider(bool rigid) { rigid_rider_ = rigid; }

 private:
  void addObstacles();

  SceneSpec scene_;
  rig::RigProfile profile_;
  CameraSpec camera_;
  std::unique_ptr<rig::Clip> clip_;  // from scene.clip (rig::makeClip)
  rig::Character horse_, rider_;
  std::unique_ptr<Renderer> renderer_;
  int horse_mesh_ = -1, rider_mesh_ = -1;
  std::vector<glm::vec3> positions_, normals_;
  FrameTimings timings_;
  bool rigid_rider_ = false;
  // The profile posing uses: the scene's, or with the rigid rider the same marked rigid (her channels
  // at rest and no balance stage either: she rides like a statue).
  const rig::RigProfile& poseProfile() const;
  rig::RigProfile rigid_profile_;
  // The baked frame shown at `frame`: the held pose, and no travel on a treadmill.
  rig::BakedFrame bakeShown(int frame) const;
};

}  // namespace stirrup::render
