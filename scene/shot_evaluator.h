// A shot's characters at a frame, for every pair of any scene: the bake (clip sampled, rider channels
// evaluated), the mounted pose and the skinned meshes. A single-pair scene is a crowd of one: its pair
// is the scene's horse and rider (as read or built, seated by the rig) on the scene's clip with the
// scene's profile; a crowd scene's pairs (SceneSpec::pairs, issue 19) are each built at their own
// proportions and colours, ride their own clip at their own start phase with their own profile. One
// code path evaluates both.
//
// Explicit inputs and outputs, as an ozz job: evaluate(FrameRequest) writes a ShotFrame the caller owns,
// one PairFrame a pair. The pairs are baked, posed and skinned in parallel on the evaluator's threads,
// each writing only its own PairFrame, so the frame is the same at any thread count. The only state
// kept between frames is the cache of built characters: a crowd pair's characters, at each level of
// detail (scene/detail_level.h), are built when first needed (a bake of channels needs none), and
// building is a pure function of the pair's parameters, so when they are built changes nothing.
//
// Nothing here traces rays: the renderer (render/shot.h) and the bake (stirrup bake) both sit on it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/bake.h"
#include "rig/character.h"
#include "rig/characters/seating.h"
#include "rig/clip.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "scene/camera.h"
#include "scene/file_shot.h"
#include "scene/scene.h"

namespace stirrup::scene {

// How a camera shows the characters (not where it is): what the frame's bake is changed by.
struct ShownAs {
  int hold_frame = 0;        // > 0: every frame shows this frame's pose (CameraSpec::hold_frame)
  bool treadmill = false;    // the travel taken out (CameraSpec::treadmill)
  bool rigid_rider = false;  // every rider channel at rest and no balance stage (render/review/layer.h)
};
ShownAs shownAs(const CameraSpec& camera, bool rigid_rider = false);

// Which level of detail each pair is skinned at (a single pair has one level, 0).
struct LevelChoice {
  int fixed = 0;                   // >= 0: every pair at this level (at most its coarsest)
  const Camera* camera = nullptr;  // fixed < 0: from each pair's size through this camera (pairDetailLevel)
  int width = 0, height = 0;       // the film's, in pixels
};

// How far a frame is evaluated: baked only, posed too, or skinned too. Points skins the positions of
// every FrameRequest::point_stride-th vertex alone (rig::skinPositions: the same bits as Skin's, no
// normals): what framing a view needs.
enum class EvalStage { Bake, Pose, Points, Skin };

struct FrameRequest {
  int frame = 1;
  ShownAs shown;
  EvalStage until = EvalStage::Skin;
  LevelChoice level;
  int only_pair = -1;  // >= 0: this pair alone (the others' PairFrames are left as they were)
  int point_stride = 1;  // EvalStage::Points: every this-many-th vertex (vertex 0, stride, 2 stride, ...)
};

// One pair at a frame, as shown.
struct PairFrame {
  rig::BakedFrame baked;  // frame: the frame asked for; seconds: the shot's time of the frame shown
  rig::MountedPose pose;  // world matrices of both skeletons (EvalStage::Pose and on)
  int level = 0;          // the level skinned (EvalStage::Points and Skin)
  // EvalStage::Skin: every vertex; EvalStage::Points: every point_stride-th vertex's position, no normals.
  std::vector<glm::vec3> horse_positions, horse_normals, rider_positions, rider_normals;
};

struct ShotFrame {
  std::vector<PairFrame> pairs;  // one a pair, in the scene's order
};

// Milliseconds spent in the last evaluate(), stage by stage (for progress reports and benchmarks).
struct EvalTimings {
  double bake_ms = 0, pose_ms = 0, skin_ms = 0;
  double build_ms = 0;  // building characters first needed in that frame: part of skin_ms, not of pose_ms
};

class ShotEvaluator {
 public:
  // The scene's characters, clips and profiles: `profile` is the scene's, resolved by the caller (name,
  // file and overrides); a crowd's pairs resolve each profile name they ride with the same way.
  // threads: 0 = all cores.
  ShotEvaluator(const SceneSpec& scene, const rig::RigProfile& profile, int threads);
  // A glTF shot's pairs (scene/file_shot.h) as the file keys them: posed from the file, never
  // re-posed or baked (a frame's `baked` holds its time and its horse's travel alone), each pair's
  // clip its horse's keyed travel (fileShotTravel), which cameras follow. `profile` is what a camera
  // following the rider's seat reads it with. The scene is `shot.scene` as the caller set it.
  ShotEvaluator(const FileShot& shot, const rig::RigProfile& profile, int threads);
  ~ShotEvaluator();
  ShotEvaluator(const ShotEvaluator&) = delete;
  ShotEvaluator& operator=(const ShotEvaluator&) = delete;

  const SceneSpec& scene() const { return scene_; }
  int pairCount() const;
  bool isCrowd() const { return !scene_.pairs.empty(); }
  // A pair's levels of detail: 1 for a single pair (its characters as they are), kDetailLevels in a crowd.
  int levelCount() const;

  // A pair's clip as the shot plays it (a crowd pair's at its start phase: the shot's time is its clip's).
  const rig::Clip& shownClip(int pair) const;
  // A pair's own clip, from the start of its ride, and how far into it the shot starts (0 for a
  // single pair): the shot's time t plays the clip at t + clipOffsetS.
  const rig::Clip& clip(int pair) const;
  double clipOffsetS(int pair) const;
  const rig::RigProfile& profile(int pair) const;
  // The characters a pair is posed with: every level shares their skeleton (the coarsest level's),
  // built now if no frame has needed them yet.
  const rig::Character& horse(int pair);
  const rig::Character& rider(int pair);
  // A pair's characters at a level, built now if no frame has needed them yet.
  const rig::Character& horseAt(int pair, int level);
  const rig::Character& riderAt(int pair, int level);
  // How the rig seated a pair's rider (a crowd's generated pairs: as built, nothing recorded).
  const rig::SeatReport& seat(int pair) const;
  // A pair's name in files and reports: crowdPairName in a crowd, "" for a single-pair scene.
  std::string pairName(int pair) const;
  // The pair's full-detail horse polygonisation cell (cm), which its size on screen is measured in.
  double horseCellCm(int pair) const;

  // Evaluates `request` into `out` (resized to one PairFrame a pair).
  void evaluate(const FrameRequest& request, ShotFrame& out);
  const EvalTimings& lastTimings() const { return timings_; }
  // Evaluates every one of `requests` (each one's level fixed: LevelChoice::fixed >= 0), the frames in
  // parallel on the evaluator's threads, and hands each to use(k, frame) for requests[k]: called
  // concurrently for different k, the frame is the caller's to take from and is dropped after the
  // call. Each frame is what evaluate()
  // gives for its request, to the bit, at any thread count (framing a view over a whole shot:
  // scene/shot_camera.h). Builds the characters the requests need first; lastTimings() is left.
  void evaluateEach(const std::vector<FrameRequest>& requests, const std::function<void(std::size_t, ShotFrame&)>& use);
  // Runs `job` on the evaluator's threads (the thread count it was made with): parallel work of the
  // shot's, such as framing its view, stays within it.
  void run(const std::function<void()>& job);

 private:
  struct Pairs;  // the pairs, their builds and the threads (shot_evaluator.cpp)
  // A frame's stages for the pairs `which` (bake) or pair i, reading the built characters only.
  void bakeStage(const FrameRequest& request, const std::vector<std::size_t>& which, ShotFrame& out) const;
  void poseStage(const FrameRequest& request, std::size_t i, PairFrame& f) const;
  void skinStage(const FrameRequest& request, std::size_t i, PairFrame& f) const;
  rig::MountedPose filePose(const FrameRequest& request, std::size_t i, const rig::BakedFrame& baked) const;
  SceneSpec scene_;
  std::unique_ptr<Pairs> pairs_;
  std::shared_ptr<const rig::GltfShot> file_;  // a glTF shot's pairs, posed as keyed (null for a scene)
  EvalTimings timings_;
};

// A crowd pair's name in files and reports: "pair" and its index from 0, in at least two digits and as
// many as the crowd's last index needs (so the names sort in the scene's order): pair03 of 30.
std::string crowdPairName(int pair, int pair_count);

// Every `stride`-th skinned vertex of a pair's horse and rider, appended as world points.
void appendPoints(const PairFrame& pair, int stride, std::vector<glm::dvec3>& horse, std::vector<glm::dvec3>& rider);
// The 8 corners of a pair's horse's and rider's bounding boxes, appended.
void appendCorners(const PairFrame& pair, std::vector<glm::vec3>& horse, std::vector<glm::vec3>& rider);

}  // namespace stirrup::scene
