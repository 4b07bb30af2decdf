#include "render/shot.h"

#include <algorithm>
#include <chrono>

#include "render/camera_motion.h"
#include "render/fence.h"
#include "render/view.h"
#include "rig/motion/clip_factory.h"
#include "rig/io/frame_range.h"
#include "rig/io/gltf_character.h"
#include "rig/pose.h"
#include "rig/skin.h"

namespace stirrup::render {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

glm::dvec3 toVec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// Uneven ground is meshed finely this far around the horse's track: the horse's length and more, so
// its hooves and the ground around it in every view stand on the fine grid.
constexpr double kFineGroundMarginCm = 1000.0;

// The box (x, z) the horse's travel frame crosses over the scene's frames, grown by the margin.
GroundRegion trackRegion(const SceneSpec& scene, const rig::Clip& clip) {
  GroundRegion r{1e300, 1e300, -1e300, -1e300};
  for (int f : rig::parseFrameList(scene.frames, "frames")) {
    const rig::HorseFrame h = clip.sample(frameTime(scene, f));
    r.x0 = std::min(r.x0, h.travel_cm), r.x1 = std::max(r.x1, h.travel_cm);
    r.z0 = std::min(r.z0, h.travel_z_cm), r.z1 = std::max(r.z1, h.travel_z_cm);
  }
  return {r.x0 - kFineGroundMarginCm, r.z0 - kFineGroundMarginCm, r.x1 + kFineGroundMarginCm,
          r.z1 + kFineGroundMarginCm};
}

}  // namespace

Shot::Shot(const SceneSpec& scene, const rig::RigProfile& profile, const CameraSpec& camera, int threads,
           BvhUpdate bvh)
    : scene_(scene),
      profile_(profile),
      camera_(camera),
      horse_(rig::resolveCharacter(rig::CharacterKind::Horse, scene.horse, scene.horse_mapping)),
      rider_(rig::resolveCharacter(rig::CharacterKind::Rider, scene.rider, scene.rider_mapping)) {
  clip_ = rig::makeClip(scene.clip, horse_);  // a path clip turns hooves about this horse's rest places
  RenderSettings settings;
  settings.width = scene.width;
  settings.height = scene.height;
  settings.samples_per_pixel = scene.samples;
  settings.light_samples = scene.light_samples;
  settings.ao_samples = scene.ao_samples;
  settings.threads = threads;
  settings.bvh_update = bvh;
  settings.sun_direction = glm::normalize(toVec(scene.sun_direction));
  settings.sun_angular_radius_deg = scene.sun_angular_radius_deg;
  settings.haze.visibility_cm = float(scene.haze_visibility_cm);
  settings.haze.ortho_depth_cm = float(scene.haze_ortho_depth_cm);
  renderer_ = std::make_unique<Renderer>(settings);
  if (scene.terrain && !scene.terrain->flat()) renderer_->setTerrain(scene.terrain, trackRegion(scene_, *clip_));
  horse_mesh_ = renderer_->addMesh(MeshDesc{ObjectId::Horse, horse_.mesh.indices, horse_.mesh.colors,
                                            horse_.mesh.positions.size(), horse_.mesh.positions});
  rider_mesh_ = renderer_->addMesh(MeshDesc{ObjectId::Rider, rider_.mesh.indices, rider_.mesh.colors,
                                            rider_.mesh.positions.size(), rider_.mesh.positions});
  rigid_profile_ = profile_;
  rigid_profile_.rigid = true;
  addObstacles();
  if (!camera_.view.empty()) {
    // A named view: framed from the characters' vertices over every frame it shows (render/view.h).
    CameraSpec preset = camera_;
    applyViewPreset(preset);
    const glm::vec3 lever = horse_.skeleton.restPosition(horse_.role("saddle")) -
                            horse_.skeleton.restPosition(horse_.role("root"));
    preset.seat_from_pivot_cm = {lever.x, lever.y, lever.z};
    camera_ = preset;  // treadmill / hold apply while sampling the points
    camera_ = frameView(preset, scene_, *clip_, profile_, framingFrames(preset, scene_),
                        [this](int f, std::vector<glm::dvec3>& h, std::vector<glm::dvec3>& r) {
                          characterPoints(f, 3, h, r);
                        });
  }
}

Shot::~Shot() = default;

const rig::RigProfile& Shot::poseProfile() const { return rigid_rider_ ? rigid_profile_ : profile_; }

// The clip's fences, standing in the world: each under the middle of the horse (halfway between its
// rest fore and hind hooves) where the clip says, in the travel frame. A treadmill shot, which takes
// the travel out, has nothing to stand still against, so it shows no fence. Props are ground-like in
// the passes (object id 0, outside the characters' matte) and never move, so they are set once.
void Shot::addObstacles() {
  if (camera_.treadmill) return;
  const std::vector<rig::Obstacle> obstacles = clip_->obstacles();
  if (obstacles.empty()) return;
  double middle = 0.0;
  for (const char* hoof : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"})
    middle += 0.25 * horse_.skeleton.restPosition(horse_.role(hoof)).x;
  for (const rig::Obstacle& o : obstacles) {
    const PropMesh fence = makeFence(o, o.travel_cm + middle);
    const int mesh = renderer_->addMesh(
        MeshDesc{ObjectId::Ground, fence.indices, fence.colors, fence.positions.size(), fence.positions});
    renderer_->updateMesh(mesh, fence.positions, fence.normals);
  }
}

rig::BakedFrame Shot::bake(int frame) const {
  return rig::bakeFrame(*clip_, profile_, frame, frameTime(scene_, frame));
}

Camera Shot::cameraAt(const rig::BakedFrame& baked) const { return cameraAtFrame(baked.frame); }

Camera Shot::cameraAtFrame(int frame) const {
  return render::cameraAtFrame(camera_, scene_, *clip_, profile_, frame);
}

rig::BakedFrame Shot::bakeShown(int frame) const {
  rig::BakedFrame baked = bake(camera_.hold_frame > 0 ? camera_.hold_frame : frame);
  baked.frame = frame;
  if (camera_.treadmill) baked.horse.travel_cm = baked.horse.travel_z_cm = 0.0;
  if (rigid_rider_) baked.rider = rig::RiderChannels{};
  return baked;
}

void Shot::characterPoints(int frame, int stride, std::vector<glm::dvec3>& horse,
                           std::vector<glm::dvec3>& rider) {
  const rig::BakedFrame baked = bakeShown(frame);
  const rig::MountedPose pose = rig::poseMounted(horse_, rider_, baked.horse, baked.rider, poseProfile());
  const std::vector<glm::mat4>& horse_world = pose.horse;
  const std::vector<glm::mat4>& rider_world = pose.rider;
  const std::size_t step = static_cast<std::size_t>(std::max(1, stride));
  horse.clear();
  rider.clear();
  rig::skinMesh(horse_.mesh, horse_.skeleton, horse_world, positions_, normals_);
  for (std::size_t i = 0; i < positions_.size(); i += step) horse.emplace_back(positions_[i]);
  rig::skinMesh(rider_.mesh, rider_.skeleton, rider_world, positions_, normals_);
  for (std::size_t i = 0; i < positions_.size(); i += step) rider.emplace_back(positions_[i]);
}

Image Shot::renderFrame(int frame, RayLog* log) {
  const rig::BakedFrame baked = bakeShown(frame);

  auto t0 = Clock::now();
  const rig::MountedPose pose = rig::poseMounted(horse_, rider_, baked.horse, baked.rider, poseProfile());
  const std::vector<glm::mat4>& horse_world = pose.horse;
  const std::vector<glm::mat4>& rider_world = pose.rider;
  timings_.pose_ms = msSince(t0);

  t0 = Clock::now();
  rig::skinMesh(horse_.mesh, horse_.skeleton, horse_world, positions_, normals_);
  renderer_->updateMesh(horse_mesh_, positions_, normals_);
  rig::skinMesh(rider_.mesh, rider_.skeleton, rider_world, positions_, normals_);
  renderer_->updateMesh(rider_mesh_, positions_, normals_);
  timings_.skin_ms = msSince(t0);

  t0 = Clock::now();
  Image image = renderer_->render(cameraAtFrame(frame), frame, log);
  timings_.trace_ms = msSince(t0);
  timings_.bvh_ms = renderer_->lastStats().commit_ms;
  timings_.rays = renderer_->lastStats().rays;
  return image;
}

}  // namespace stirrup::render
