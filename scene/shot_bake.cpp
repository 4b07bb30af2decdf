#include "scene/shot_bake.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "scene/camera.h"
#include "scene/shot_camera.h"

namespace stirrup::scene {
namespace {

// The camera node's transform as glTF wants it (looks down -Z, +Y up): the render camera's own basis,
// so the file sees exactly what CameraFrame traces, in the same centimetres.
glm::dmat4 cameraToWorld(const Camera& camera, const SceneSpec& scene) {
  const CameraFrame f(camera, scene.width, scene.height);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(f.right(), 0.0);
  m[1] = glm::dvec4(f.upward(), 0.0);
  m[2] = glm::dvec4(-f.forward(), 0.0);
  m[3] = glm::dvec4(camera.position, 1.0);
  return m;
}

// A baked terrain: 50 cm cells (the hooves sit on it to a few millimetres on rolling hills) over the
// track and 20 m around it, coarser past 600 cells a side (a few MB at most).
constexpr double kBakedGroundCellCm = 50.0;
constexpr double kBakedGroundMarginCm = 2000.0;
constexpr int kBakedGroundMaxCells = 600;

}  // namespace

rig::BakedShot bakeShot(ShotEvaluator& characters, std::vector<int> frames, int level) {
  if (level < 0 || level >= characters.levelCount())
    throw std::invalid_argument("bakeShot: no level " + std::to_string(level) + " (the shot has " +
                                std::to_string(characters.levelCount()) + ")");
  const SceneSpec& scene = characters.scene();
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  rig::BakedShot shot;
  shot.name = scene.name;
  shot.fps = scene.fps;
  for (int i = 0; i < characters.pairCount(); ++i) {
    rig::BakedPair pair;
    pair.name = characters.pairName(i);
    pair.horse = &characters.horseAt(i, level);
    pair.rider = &characters.riderAt(i, level);
    pair.seat = characters.seat(i);
    shot.pairs.push_back(std::move(pair));
  }
  // The first pair's baked frames, for a treadmill camera (a crowd has none).
  std::vector<rig::BakedFrame> first;
  glm::dvec2 lo(1e300), hi(-1e300);  // the horses' travel, for the ground
  ShotFrame evaluated;
  for (int frame : frames) {
    FrameRequest request;
    request.frame = frame;
    request.until = EvalStage::Pose;
    characters.evaluate(request, evaluated);
    shot.seconds.push_back(static_cast<float>(evaluated.pairs[0].baked.seconds));
    for (std::size_t i = 0; i < evaluated.pairs.size(); ++i) {
      const rig::BakedFrame& b = evaluated.pairs[i].baked;
      shot.pairs[i].poses.push_back(std::move(evaluated.pairs[i].pose));
      shot.pairs[i].hoof_sliding.push_back(b.horse.hoof_sliding);
      lo = glm::min(lo, glm::dvec2(b.horse.travel_cm, b.horse.travel_z_cm));
      hi = glm::max(hi, glm::dvec2(b.horse.travel_cm, b.horse.travel_z_cm));
    }
    first.push_back(evaluated.pairs[0].baked);
  }
  for (rig::BakedPair& pair : shot.pairs)  // most clips slide no hoof: nothing to write
    if (std::none_of(pair.hoof_sliding.begin(), pair.hoof_sliding.end(), [](const std::array<bool, 4>& s) { return s[0] || s[1] || s[2] || s[3]; }))
      pair.hoof_sliding.clear();
  if (scene.terrain && !scene.terrain->flat()) {
    // The ground under the baked frames' tracks and well around them (kBakedGroundMarginCm).
    scene.terrain->triangulate(lo - kBakedGroundMarginCm, hi + kBakedGroundMarginCm, kBakedGroundCellCm,
                               kBakedGroundMaxCells, shot.ground_vertices, shot.ground_indices);
  }
  for (const CameraSpec& spec : scene.cameras) {
    const ShotCamera view(characters, spec);
    const CameraSpec& c = view.spec();
    rig::BakedCamera bc;
    bc.name = c.name;
    bc.orthographic = c.orthographic;
    bc.fov_deg = c.fov_deg;
    bc.ortho_height_cm = c.ortho_height_cm;
    bc.width = scene.width;
    bc.height = scene.height;
    bc.view = c.view;
    bc.hold_frame = c.hold_frame;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      Camera cam = view.at(frames[i]);
      // A treadmill render takes the travel out of the horse; the file's horse travels, so the camera
      // travels with it instead (the same picture: both move by the same vector).
      if (c.treadmill) {
        const glm::dvec3 travel(first[i].horse.travel_cm, 0.0, first[i].horse.travel_z_cm);
        cam.position += travel;
        cam.target += travel;
      }
      bc.world.push_back(cameraToWorld(cam, scene));
    }
    shot.cameras.push_back(bc);
  }
  return shot;
}


}  // namespace stirrup::scene
