#include "render/shot.h"

#include <chrono>

#include "rig/clip_factory.h"
#include "rig/pose.h"
#include "rig/skin.h"

namespace stirrup::render {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

glm::dvec3 toVec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

Shot::Shot(const SceneSpec& scene, const rig::RigProfile& profile, const CameraSpec& camera, int threads)
    : scene_(scene),
      profile_(profile),
      camera_(camera),
      clip_(rig::makeClip(scene.clip)),
      horse_(rig::buildDefaultHorse()),
      rider_(rig::buildDefaultRider()) {
  RenderSettings settings;
  settings.width = scene.width;
  settings.height = scene.height;
  settings.samples_per_pixel = scene.samples;
  settings.light_samples = scene.light_samples;
  settings.ao_samples = scene.ao_samples;
  settings.threads = threads;
  settings.sun_direction = glm::normalize(toVec(scene.sun_direction));
  settings.sun_angular_radius_deg = scene.sun_angular_radius_deg;
  renderer_ = std::make_unique<Renderer>(settings);
  horse_mesh_ = renderer_->addMesh(MeshDesc{ObjectId::Horse, horse_.mesh.indices, horse_.mesh.colors,
                                            horse_.mesh.positions.size()});
  rider_mesh_ = renderer_->addMesh(MeshDesc{ObjectId::Rider, rider_.mesh.indices, rider_.mesh.colors,
                                            rider_.mesh.positions.size()});
}

Shot::~Shot() = default;

rig::BakedFrame Shot::bake(int frame) const {
  return rig::bakeFrame(*clip_, profile_, frame, frameTime(scene_, frame));
}

Camera Shot::cameraAt(const rig::BakedFrame& baked) const {
  Camera c;
  c.projection = camera_.orthographic ? Camera::Projection::Orthographic : Camera::Projection::Perspective;
  c.fov_deg = camera_.fov_deg;
  c.ortho_height_cm = camera_.ortho_height_cm;
  const glm::dvec3 offset = camera_.follow ? glm::dvec3(baked.horse.travel_cm, 0.0, 0.0) : glm::dvec3(0.0);
  c.position = toVec(camera_.position) + offset;
  c.target = toVec(camera_.target) + offset;
  c.up = {0.0, 1.0, 0.0};
  return c;
}

Image Shot::renderFrame(int frame) {
  const rig::BakedFrame baked = bake(frame);

  auto t0 = Clock::now();
  std::vector<glm::mat4> horse_world = rig::poseHorse(horse_, baked.horse);
  rig::placeStirrups(horse_, horse_world, baked.rider, profile_.rider_unit_cm);
  const std::vector<glm::mat4> rider_world =
      rig::poseRider(rider_, horse_, horse_world, baked.rider, profile_.rider_unit_cm);
  timings_.pose_ms = msSince(t0);

  t0 = Clock::now();
  rig::skinMesh(horse_.mesh, horse_.skeleton, horse_world, positions_, normals_);
  renderer_->updateMesh(horse_mesh_, positions_, normals_);
  rig::skinMesh(rider_.mesh, rider_.skeleton, rider_world, positions_, normals_);
  renderer_->updateMesh(rider_mesh_, positions_, normals_);
  timings_.skin_ms = msSince(t0);

  t0 = Clock::now();
  Image image = renderer_->render(cameraAt(baked), frame);
  timings_.trace_ms = msSince(t0);
  return image;
}

}  // namespace stirrup::render
