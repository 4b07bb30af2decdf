#include "scene/shot_camera.h"

#include <algorithm>

#include "rig/error.h"
#include "rig/motion/crowd_middle_clip.h"
#include "scene/camera_motion.h"
#include "scene/detail_level.h"
#include "scene/point_arena.h"
#include "scene/view.h"

namespace stirrup::scene {
namespace {

// A pair's view is framed from every third skinned vertex (our choice: a third of a mesh whose
// vertices stand a few cm apart bounds it to well within a view's margin).
constexpr int kFramingPointStride = 3;

}  // namespace

ShotCamera::ShotCamera(ShotEvaluator& characters, const CameraSpec& camera)
    : scene_(characters.scene()), spec_(camera) {
  const int follow = characters.isCrowd() ? camera.follow_pair : -1;
  if (characters.isCrowd()) {
    const std::string at = scene_.file.string() + ": cameras." + camera.name + ".";
    if (camera.follow_pair >= characters.pairCount())
      throw rig::InputError(at + "follow_pair: expected a pair index from 0 to " + std::to_string(characters.pairCount() - 1) +
                       ", got " + std::to_string(camera.follow_pair));
    if (camera.treadmill) throw rig::InputError(at + "treadmill: expected false in a crowd scene");
  }
  if (follow >= 0 || !characters.isCrowd()) {
    clip_ = &characters.shownClip(std::max(0, follow));
  } else {
    std::vector<const rig::Clip*> shown;
    for (int i = 0; i < characters.pairCount(); ++i) shown.push_back(&characters.shownClip(i));
    owned_clip_ = std::make_unique<rig::CrowdMiddleClip>(shown);
    clip_ = owned_clip_.get();
  }
  const int seat_pair = std::max(0, follow);
  profile_ = &characters.profile(seat_pair);
  if (spec_.view.empty()) return;
  // A named view: framed from the characters' vertices over every frame it shows (scene/view.h): the
  // followed pair's (a single pair's), every third vertex at full detail; or with none, the corners of
  // every pair's horse's and rider's boxes at the coarsest level (they hold every vertex within a cell,
  // a few cm against a view's 12% margin; every third vertex of 30 pairs over a whole ride took
  // gigabytes).
  CameraSpec preset = spec_;
  applyViewPreset(preset);
  const rig::Character& horse = characters.horse(seat_pair);
  const glm::vec3 lever = horse.skeleton.restPosition(horse.role("saddle")) - horse.skeleton.restPosition(horse.role("root"));
  preset.seat_from_pivot_cm = {lever.x, lever.y, lever.z};
  const bool whole_crowd = characters.isCrowd() && follow < 0;
  PointArena arena;  // every frame's points, until the view is framed
  const auto points = [&](const std::vector<int>& frames, std::vector<CharacterFramePoints>& out) {
    std::vector<FrameRequest> requests(frames.size());
    for (std::size_t k = 0; k < frames.size(); ++k) {
      FrameRequest& request = requests[k];
      request.frame = frames[k];
      request.shown = shownAs(preset);  // a treadmill or a held pose as the view shows them
      request.level.fixed = whole_crowd ? kDetailLevels - 1 : 0;
      request.only_pair = whole_crowd ? -1 : seat_pair;
      // Positions alone, and of a pair only the vertices the view reads.
      request.until = EvalStage::Points;
      request.point_stride = whole_crowd ? 1 : kFramingPointStride;
    }
    out.assign(frames.size(), {});
    // The frames in parallel, each writing only its own slot.
    characters.evaluateEach(requests, [&](std::size_t k, ShotFrame& frame) {
      if (whole_crowd) {
        std::vector<glm::vec3> horse, rider;
        for (const PairFrame& p : frame.pairs) appendCorners(p, horse, rider);
        out[k] = {arena.keep(horse), arena.keep(rider)};
        return;
      }
      const PairFrame& p = frame.pairs[std::size_t(seat_pair)];
      out[k] = {arena.keep(p.horse_positions), arena.keep(p.rider_positions)};
    });
  };
  // The follow filter of every frame runs in parallel too, on the evaluator's threads.
  characters.run([&] { spec_ = frameView(preset, scene_, *clip_, *profile_, framingFrames(preset, scene_), points); });
}

ShotCamera::~ShotCamera() = default;

Camera ShotCamera::at(int frame) const { return cameraAtFrame(spec_, scene_, *clip_, *profile_, frame); }

}  // namespace stirrup::scene
