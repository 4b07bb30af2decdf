#include "render/shot.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <future>
#include <stdexcept>

#include "render/tracer/stopwatch.h"
#include "scene/detail_level.h"
#include "scene/fence.h"
#include "scene/frame_range.h"

namespace stirrup::render {
namespace {

glm::dvec3 toVec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

MeshDesc meshOf(ObjectId id, const rig::Character& c) {
  MeshDesc desc{id, c.mesh.indices, c.mesh.colors, c.mesh.positions.size(), c.mesh.positions};
  desc.uvs = c.mesh.uvs;
  desc.triangle_textures = c.mesh.triangle_textures;
  desc.textures = c.mesh.textures;
  return desc;
}

}  // namespace

GroundRegion fineGroundRegion(const scene::SceneSpec& scene, const std::vector<const rig::Clip*>& clips) {
  GroundRegion r{1e300, 1e300, -1e300, -1e300};
  for (int f : scene::parseFrameList(scene.frames, "frames")) {
    for (const rig::Clip* clip : clips) {
      const rig::HorseFrame h = clip->sampleTravel(scene::frameTime(scene, f));
      r.x0 = std::min(r.x0, h.travel_cm), r.x1 = std::max(r.x1, h.travel_cm);
      r.z0 = std::min(r.z0, h.travel_z_cm), r.z1 = std::max(r.z1, h.travel_z_cm);
    }
  }
  return {r.x0 - kFineGroundMarginCm, r.z0 - kFineGroundMarginCm, r.x1 + kFineGroundMarginCm,
          r.z1 + kFineGroundMarginCm};
}

Shot::Shot(const scene::SceneSpec& scene, const rig::RigProfile& profile, const scene::CameraSpec& camera, int threads,
           BvhUpdate bvh)
    : Shot(buildCharacters(scene, profile, threads), camera, threads, bvh) {}

Shot::BuiltCharacters Shot::buildCharacters(const scene::SceneSpec& scene, const rig::RigProfile& profile, int threads) {
  const auto t0 = Clock::now();
  BuiltCharacters built{std::make_shared<scene::ShotEvaluator>(scene, profile, threads)};
  built.ms = msSince(t0);
  return built;
}

Shot::Shot(BuiltCharacters built, const scene::CameraSpec& camera, int threads, BvhUpdate bvh)
    : Shot(std::move(built.characters), camera, threads, bvh) {
  setup_.characters_ms = built.ms;
}

Shot::Shot(std::shared_ptr<scene::ShotEvaluator> characters, const scene::CameraSpec& camera, int threads, BvhUpdate bvh)
    : scene_(characters->scene()), characters_(std::move(characters)) {
  const scene::SceneSpec& scene = scene_;
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
  // With two pairs or more the characters' one box would tie each pair's pose to the ground's shading
  // far from it (RenderSettings::open_ground_shortcuts); one pair's box is its own.
  settings.open_ground_shortcuts = characters_->pairCount() < 2;
  renderer_ = std::make_unique<Renderer>(settings);
  // The terrain (its mesh, the ground's BVH, the sun's horizon over the hills) and the view's framing
  // need nothing of each other, so the terrain is built on a thread of its own while the view is framed:
  // neither keeps both cores busy throughout (the BVH's build least), and together they do. The
  // renderer is not touched by the framing, nor the evaluator by the terrain (it only samples clips).
  // Asked for one thread, the shot keeps to one: the terrain waits for the framing.
  std::future<void> terrain;
  if (scene.terrain && !scene.terrain->flat())
    terrain = std::async(threads == 1 ? std::launch::deferred : std::launch::async, [this, &scene] {
      const auto t0 = Clock::now();
      std::vector<const rig::Clip*> tracks;
      for (int i = 0; i < characters_->pairCount(); ++i) tracks.push_back(&characters_->shownClip(i));
      renderer_->setTerrain(scene.terrain, fineGroundRegion(scene_, tracks));
      setup_.terrain_ms = msSince(t0);
    });
  // If the framing throws, `terrain` (a local, gone before the members) waits for its thread in its
  // destructor, as std::async's futures do, so nothing the thread uses is unwound under it.
  const auto t0 = Clock::now();
  camera_ = std::make_unique<scene::ShotCamera>(*characters_, camera);
  setup_.framing_ms = msSince(t0);
  if (terrain.valid()) terrain.get();  // its error, if any, is the shot's
  // A pair of one level (a single pair: its characters as read or built) joins the renderer now, with
  // the renderer's own geometry ids; a crowd's levels join when first shown (showMeshes).
  meshes_.assign(std::size_t(characters_->pairCount()),
                 std::vector<std::array<int, 2>>(std::size_t(characters_->levelCount()), {-1, -1}));
  if (characters_->levelCount() == 1)
    for (int i = 0; i < characters_->pairCount(); ++i)
      meshes_[std::size_t(i)][0] = {renderer_->addMesh(meshOf(ObjectId::Horse, characters_->horse(i))),
                                    renderer_->addMesh(meshOf(ObjectId::Rider, characters_->rider(i)))};
  addObstacles();
}

void Shot::setDetailLevel(int level) {
  if (level < -1 || level >= scene::kDetailLevels)
    throw std::invalid_argument("Shot::setDetailLevel: expected -1 to " + std::to_string(scene::kDetailLevels - 1));
  detail_level_ = level;
  ahead_frame_.reset();
}

int Shot::pairCount() const { return characters_->isCrowd() ? characters_->pairCount() : 0; }

Shot::~Shot() = default;

// Each pair's clip's fences, standing in the world: each under the middle of its horse (halfway between
// its rest fore and hind hooves) where the clip says, in the travel frame (a crowd's path clips have
// none). A treadmill shot, which takes the travel out, has nothing to stand still against, so it shows
// no fence. Props are ground-like in the passes (object id 0, outside the characters' matte) and never
// move, so they are set once.
void Shot::addObstacles() {
  if (camera_->spec().treadmill) return;
  for (int i = 0; i < characters_->pairCount(); ++i) {
    const std::vector<rig::Obstacle> obstacles = characters_->shownClip(i).obstacles();
    if (obstacles.empty()) continue;
    const rig::Character& horse = characters_->horse(i);
    double middle = 0.0;
    for (const char* hoof : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"})
      middle += 0.25 * horse.skeleton.restPosition(horse.role(hoof)).x;
    for (const rig::Obstacle& o : obstacles) {
      const scene::PropMesh fence = scene::makeFence(o, o.travel_cm + middle);
      const int mesh = renderer_->addMesh(
          MeshDesc{ObjectId::Ground, fence.indices, fence.colors, fence.positions.size(), fence.positions});
      renderer_->updateMesh(mesh, fence.positions, fence.normals);
    }
  }
}

rig::BakedFrame Shot::bake(int frame) const {
  return rig::bakeFrame(camera_->clip(), camera_->profile(), frame, scene::frameTime(scene_, frame));
}

scene::Camera Shot::cameraAt(const rig::BakedFrame& baked) const { return cameraAtFrame(baked.frame); }

scene::Camera Shot::cameraAtFrame(int frame) const { return camera_->at(frame); }

void Shot::evaluatePoints(int frame, int pair) {
  scene::FrameRequest request;
  request.frame = frame;
  request.shown = scene::shownAs(camera_->spec(), rigid_rider_);
  request.level.fixed = 0;
  request.only_pair = pair;
  characters_->evaluate(request, frame_);
}

void Shot::pairPoints(int pair, int frame, int stride, std::vector<glm::dvec3>& horse,
                      std::vector<glm::dvec3>& rider) {
  if (pair < 0 || pair >= pairCount()) throw std::invalid_argument("Shot::pairPoints: no pair " + std::to_string(pair));
  evaluatePoints(frame, pair);
  horse.clear();
  rider.clear();
  scene::appendPoints(frame_.pairs[std::size_t(pair)], stride, horse, rider);
}

void Shot::characterPoints(int frame, int stride, std::vector<glm::dvec3>& horse,
                           std::vector<glm::dvec3>& rider) {
  evaluatePoints(frame, -1);
  horse.clear();
  rider.clear();
  for (const scene::PairFrame& p : frame_.pairs) scene::appendPoints(p, stride, horse, rider);
}

// Levels shown for the first time join the renderer, each with its own fixed geometry ids (pair,
// level, horse or rider), so the scene is the same whichever frames were rendered before.
void Shot::showMeshes() {
  const bool levels = characters_->levelCount() > 1;
  timings_.pairs_at_level = {};
  timings_.skinned_vertices = 0;
  for (std::size_t i = 0; i < frame_.pairs.size(); ++i) {
    const scene::PairFrame& p = frame_.pairs[i];
    std::vector<std::array<int, 2>>& pair_meshes = meshes_[i];
    std::array<int, 2>& shown = pair_meshes[std::size_t(p.level)];
    if (shown[0] < 0) {
      const int id = 2 * (int(i) * scene::kDetailLevels + p.level);
      MeshDesc horse = meshOf(ObjectId::Horse, characters_->horseAt(int(i), p.level));
      MeshDesc rider = meshOf(ObjectId::Rider, characters_->riderAt(int(i), p.level));
      horse.geometry_id = id;
      rider.geometry_id = id + 1;
      shown = {renderer_->addMesh(horse), renderer_->addMesh(rider)};
    }
    if (levels)
      for (std::size_t k = 0; k < pair_meshes.size(); ++k)
        for (int m : pair_meshes[k])
          if (m >= 0) renderer_->setMeshEnabled(m, int(k) == p.level);
    renderer_->updateMesh(shown[0], p.horse_positions, p.horse_normals);
    renderer_->updateMesh(shown[1], p.rider_positions, p.rider_normals);
    ++timings_.pairs_at_level[std::size_t(p.level)];
    timings_.skinned_vertices += p.horse_positions.size() + p.rider_positions.size();
  }
}

scene::FrameRequest Shot::frameRequest(int frame, const scene::Camera& camera) const {
  scene::FrameRequest request;
  request.frame = frame;
  request.shown = scene::shownAs(camera_->spec(), rigid_rider_);
  request.level = {detail_level_, &camera, scene_.width, scene_.height};
  return request;
}

Image Shot::renderFrame(int frame, RayLog* log) { return renderFrame(frame, std::nullopt, log); }

Image Shot::renderFrame(int frame, std::optional<int> next_frame, RayLog* log) {
  const auto call0 = Clock::now();
  const scene::Camera camera = cameraAtFrame(frame);
  auto t0 = Clock::now();
  scene::EvalTimings eval;
  timings_.evaluated_ahead = ahead_frame_ == frame;
  if (timings_.evaluated_ahead) {
    std::swap(frame_, ahead_);
    eval = ahead_timings_;
  } else {
    characters_->evaluate(frameRequest(frame, camera), frame_);
    eval = characters_->lastTimings();
  }
  ahead_frame_.reset();
  timings_.pose_ms = eval.bake_ms + eval.pose_ms;
  timings_.build_ms = eval.build_ms;
  const double eval_ms = msSince(t0);
  t0 = Clock::now();
  showMeshes();
  // With any building (build_ms); evaluated ahead, the skinning's own time and the copy into the renderer.
  timings_.skin_ms = (timings_.evaluated_ahead ? eval.skin_ms : eval_ms - timings_.pose_ms) + msSince(t0);

  // The next frame's evaluation, as one more task on the renderer's threads while this one commits and
  // traces. It writes ahead_ and the evaluator (which the renderer never reads); its camera lives here.
  const scene::Camera next_camera = next_frame ? cameraAtFrame(*next_frame) : camera;
  std::function<void()> evaluate_next;
  if (next_frame) {
    evaluate_next = [this, request = frameRequest(*next_frame, next_camera)] {
      characters_->evaluate(request, ahead_);
      ahead_timings_ = characters_->lastTimings();
    };
  }
  t0 = Clock::now();
  Image image = renderer_->render(camera, frame, log, evaluate_next);  // the evaluation's error, if any
  timings_.trace_ms = msSince(t0);
  timings_.bvh_ms = renderer_->lastStats().commit_ms;
  timings_.rays = renderer_->lastStats().rays;
  timings_.triangles = renderer_->lastStats().triangles;
  timings_.wait_ms = renderer_->lastStats().wait_ms;
  if (next_frame) ahead_frame_ = *next_frame;
  timings_.frame_ms = msSince(call0);
  return image;
}

}  // namespace stirrup::render
