// A shot: one scene seen through one of its cameras. Renders any frame on its own, running the whole
// pipeline for that frame: the characters evaluated (scene/shot_evaluator.h: sample clip -> evaluate
// rider controls -> pose -> skin, for every pair of the scene, a single pair being a crowd of one), then
// traced. Each pair's two meshes are their own geometries in the one Embree scene; a crowd's pairs each
// at the level of detail its size on screen asks for. The camera (scene/shot_camera.h) follows the
// pair CameraSpec::follow_pair names exactly as a single pair's camera follows its horse, or with none,
// the crowd's middle (rig/motion/crowd_middle_clip.h), and a view then frames every pair.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "render/tracer/renderer.h"
#include "rig/bake.h"
#include "rig/character.h"
#include "rig/motion/procedural_gait.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/shot_camera.h"
#include "scene/shot_evaluator.h"

namespace stirrup::render {

// Uneven ground is meshed finely (TerrainMeshParams::fine_spacing_cm) this far around the box of the
// horses' travel points. The default horse's hooves land within about 1 m of that box (half a body
// length and the stride's reach; Shot.TheFineGroundReachesEveryHoofWithRoomToSpare measures it), so
// every hoof and the ground 1.5 m beyond it stand on the fine grid, and a horse twice as long still
// stands on it. Past it the cells widen by TerrainMeshParams::growth each (31, 39, 49 cm ...), the mesh
// leaving Terrain::height by at most |height''| cell² / 8 where nothing stands. It was 10 m until issue
// 35's seventh pass: half again as many ground quads for Embree to traverse (trail's ground 122 460
// vertices then, 84 660 now; docs/performance-history.md, "Terrain at flat-ground cost") and no visible difference.
inline constexpr double kFineGroundMarginCm = 300.0;

// The box (x, z) the horses' travel frames cross over the scene's frames, grown by kFineGroundMarginCm:
// the region a Shot meshes its terrain finely over (makeTerrainMesh).
GroundRegion fineGroundRegion(const scene::SceneSpec& scene, const std::vector<const rig::Clip*>& clips);

// Timings of the last frame, in milliseconds, for progress reports and benchmarks.
struct FrameTimings {
  double pose_ms = 0, skin_ms = 0, trace_ms = 0;
  // A crowd's levels of detail built during the frame (the first frame that needs each one), part of
  // skin_ms: a one-time cost, like the set-up's.
  double build_ms = 0;
  double bvh_ms = 0;   // the BVH update, part of trace_ms
  // The frame's bake, pose and skinning ran ahead, while the frame before it traced (Shot::renderFrame's
  // next_frame); pose_ms and skin_ms are then their own times on that thread, not time this frame waited.
  bool evaluated_ahead = false;
  // After this frame's trace, the time spent waiting for the next frame's evaluation to finish (part
  // of trace_ms; about 0 when none was asked for or it finished first).
  double wait_ms = 0;
  // renderFrame's wall-clock time, call to return: evaluating (unless done ahead), the BVH update, the
  // trace and any wait. With frames overlapped it is less than the sum of the parts.
  double frame_ms = 0;
  uint64_t rays = 0;   // camera, shadow and sky rays of the frame
  size_t triangles = 0;             // shown (refitted), every pair at its level
  uint64_t skinned_vertices = 0;    // of the horses and riders shown
  std::array<int, 3> pairs_at_level{};  // a crowd's pairs at each level of detail (scene/detail_level.h)
};

// Where a shot's set-up went (ms, wall clock): reading, seating and building the characters and their
// clips (0 for a shot made from an evaluator already built), meshing the terrain with its normals and
// sun horizon, and framing the view camera over every frame it shows. The terrain is built on a thread
// of its own alongside the framing, so the set-up takes the characters plus the longer of the two (at
// one thread, after the framing: their sum).
struct SetupTimings {
  double characters_ms = 0, terrain_ms = 0, framing_ms = 0;
};

class Shot {
 public:
  // threads: 0 = all cores. The profile is resolved by the caller (name, file and overrides).
  // `bvh`: how the BVH follows the characters (the default is the renderer's; others for benchmarks).
  Shot(const scene::SceneSpec& scene, const rig::RigProfile& profile, const scene::CameraSpec& camera, int threads,
       BvhUpdate bvh = RenderSettings{}.bvh_update);
  // A shot of the scene `characters` evaluates, sharing them with the other shots made from them (a
  // layered movie's rigid panel beside the rigged one): the characters are read, seated and built
  // once. The shots must render one after the other, not at once (the evaluator is not reentrant).
  Shot(std::shared_ptr<scene::ShotEvaluator> characters, const scene::CameraSpec& camera, int threads,
       BvhUpdate bvh = RenderSettings{}.bvh_update);
  ~Shot();

  // With `log`, the frame's rays are also kept in it (see Renderer::render).
  Image renderFrame(int frame, RayLog* log = nullptr);
  // Frames overlapped: renders `frame` and, while it traces, evaluates `next_frame` (bake,
  // pose and skin: the frame the caller renders next) as one more task on the renderer's threads
  // (Renderer::render's `alongside`: no more threads than asked for), so that frame's renderFrame
  // starts at its BVH update. Returns once both are done (an evaluation's error is thrown here), so nothing of
  // the shot runs between calls and shots sharing characters may still take turns. The pixels are
  // the same as rendering each frame on its own: the evaluation writes only a frame the renderer does
  // not read (it is handed to the renderer, as before, when its frame renders), and every stage is a
  // pure function of the frame. A next frame that is not the one rendered next is evaluated again.
  Image renderFrame(int frame, std::optional<int> next_frame, RayLog* log = nullptr);
  Renderer& renderer() { return *renderer_; }
  // Frames with the passes (depth, matte, normal, object id: EXR frames, a matte layer; the default) or
  // the colour alone (PNG frames): Renderer::setPasses.
  void setPasses(bool passes) { renderer_->setPasses(passes); }
  // The characters it evaluates (every pair of the scene).
  scene::ShotEvaluator& characters() { return *characters_; }
  const std::shared_ptr<scene::ShotEvaluator>& sharedCharacters() const { return characters_; }
  // The bake at a frame of what the camera follows (a single pair's clip; in a crowd the followed
  // pair's, or the crowd's middle) with its profile; every pair's is characters().evaluate's.
  rig::BakedFrame bake(int frame) const;
  const FrameTimings& lastTimings() const { return timings_; }
  const SetupTimings& setupTimings() const { return setup_; }

  // The render camera at a frame (follow cameras travel with the horse; scene/camera_motion.h).
  scene::Camera cameraAt(const rig::BakedFrame& baked) const;
  scene::Camera cameraAtFrame(int frame) const;
  // The camera as resolved: a view camera (scene/view.h) framed from the characters' bounds over
  // the clip when the Shot was made.
  const scene::CameraSpec& camera() const { return camera_->spec(); }
  // World positions of every `stride`-th skinned vertex of the horse and the rider at a frame, as it
  // is shown (a treadmill camera removes the travel, a held pose holds its frame). In a crowd: of
  // every pair's horse and rider.
  void characterPoints(int frame, int stride, std::vector<glm::dvec3>& horse, std::vector<glm::dvec3>& rider);
  // A crowd scene's pairs (0 for a single pair), and one pair's points as characterPoints gives them.
  int pairCount() const;
  void pairPoints(int pair, int frame, int stride, std::vector<glm::dvec3>& horse, std::vector<glm::dvec3>& rider);
  // The rider rigidly fixed to the saddle (every rider channel at rest): what the rig adds, for the
  // layered comparison (render/review/layer.h).
  void setRigidRider(bool rigid) {
    rigid_rider_ = rigid;
    ahead_frame_.reset();
  }
  // A crowd's levels of detail (scene/detail_level.h): -1 (the default) picks each pair's level from
  // its size on screen; 0 to 2 draws every pair at that level (benchmarks, the switch's test).
  void setDetailLevel(int level);

 private:
  // The scene's characters built, with the time they took (SetupTimings::characters_ms).
  struct BuiltCharacters {
    std::shared_ptr<scene::ShotEvaluator> characters;
    double ms = 0;
  };
  static BuiltCharacters buildCharacters(const scene::SceneSpec& scene, const rig::RigProfile& profile, int threads);
  Shot(BuiltCharacters built, const scene::CameraSpec& camera, int threads, BvhUpdate bvh);
  void addObstacles();
  // Adds the meshes of each pair's level shown in frame_ that the renderer does not hold yet, shows
  // those levels and hides the others, and updates the shown meshes' vertices.
  void showMeshes();
  // The characters at a frame as this shot shows them (its camera's hold and treadmill, the rigid
  // rider), every pair at full detail or only `pair`.
  void evaluatePoints(int frame, int pair);
  // The request renderFrame evaluates a frame with, seen through `camera` (its levels of detail).
  scene::FrameRequest frameRequest(int frame, const scene::Camera& camera) const;

  scene::SceneSpec scene_;
  std::shared_ptr<scene::ShotEvaluator> characters_;
  std::unique_ptr<scene::ShotCamera> camera_;
  std::unique_ptr<Renderer> renderer_;
  scene::ShotFrame frame_;  // the characters' last evaluated frame
  // The frame evaluated ahead (renderFrame's next_frame), its number and its evaluation's timings;
  // cleared when anything that changes a frame's request changes.
  scene::ShotFrame ahead_;
  std::optional<int> ahead_frame_;
  scene::EvalTimings ahead_timings_;
  // Each pair's meshes in the renderer, per level (horse, rider; -1 until first shown).
  std::vector<std::vector<std::array<int, 2>>> meshes_;
  FrameTimings timings_;
  SetupTimings setup_;
  bool rigid_rider_ = false;
  int detail_level_ = -1;
};

}  // namespace stirrup::render
