#include "render/shot.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <tuple>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "render/camera_motion.h"
#include "render/detail_level.h"
#include "render/fence.h"
#include "render/profile_resolver.h"
#include "render/view.h"
#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/crowd_bake.h"
#include "rig/error.h"
#include "rig/motion/clip_factory.h"
#include "rig/motion/crowd.h"
#include "rig/motion/crowd_middle_clip.h"
#include "rig/motion/shifted_clip.h"
#include "rig/io/frame_range.h"
#include "rig/io/gltf_character.h"
#include "rig/io/ridden_pair.h"
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

// The box (x, z) the horses' travel frames cross over the scene's frames, grown by the margin.
GroundRegion trackRegion(const SceneSpec& scene, const std::vector<const rig::Clip*>& clips) {
  GroundRegion r{1e300, 1e300, -1e300, -1e300};
  for (int f : rig::parseFrameList(scene.frames, "frames")) {
    for (const rig::Clip* clip : clips) {
      const rig::HorseFrame h = clip->sample(frameTime(scene, f));
      r.x0 = std::min(r.x0, h.travel_cm), r.x1 = std::max(r.x1, h.travel_cm);
      r.z0 = std::min(r.z0, h.travel_z_cm), r.z1 = std::max(r.z1, h.travel_z_cm);
    }
  }
  return {r.x0 - kFineGroundMarginCm, r.z0 - kFineGroundMarginCm, r.x1 + kFineGroundMarginCm,
          r.z1 + kFineGroundMarginCm};
}

MeshDesc meshOf(ObjectId id, const rig::Character& c) {
  MeshDesc desc{id, c.mesh.indices, c.mesh.colors, c.mesh.positions.size(), c.mesh.positions};
  desc.uvs = c.mesh.uvs;
  desc.triangle_textures = c.mesh.triangle_textures;
  desc.textures = c.mesh.textures;
  return desc;
}

}  // namespace

// A crowd scene's pairs, the pair its camera follows, and the threads they are made, baked and skinned on.
struct Shot::Crowd {
  // One level of detail of a pair: its characters (shared by every pair of the same proportions and
  // colours), null until the level is first needed, and their meshes' handles in the renderer (-1 until
  // the renderer first shows it).
  struct Level {
    std::shared_ptr<const rig::Character> horse, rider;
    int horse_mesh = -1, rider_mesh = -1;
  };
  // One pair: its levels, clip and profiles, and skinning buffers.
  struct Pair {
    std::array<Level, kDetailLevels> levels;
    std::array<std::size_t, kDetailLevels> builds{};  // each level's entry in Crowd::builds
    std::unique_ptr<rig::Clip> clip;           // rig::makePairClip
    std::unique_ptr<rig::ShiftedClip> shown;   // the clip at the pair's start phase, as the shot plays it
    rig::RigProfile profile, rigid_profile;
    double clip_offset_s = 0;
    double horse_cell_cm = 0;                  // level 0's polygonisation cell, for choosing a level
    int level = 0;                             // the level skinned last
    rig::MountedPose pose;                     // posed last
    std::vector<glm::vec3> horse_positions, horse_normals, rider_positions, rider_normals;
    // The characters posing uses: every level has the same skeleton (buildLevels checks it), so the
    // coarsest level's, which every pair builds first (it frames the views).
    const rig::Character& horse() const { return *levels[kDetailLevels - 1].horse; }
    const rig::Character& rider() const { return *levels[kDetailLevels - 1].rider; }
  };
  // A distinct horse and rider: proportions, colours and level. Built once, when a pair first needs it.
  struct Build {
    rig::HorseParams horse;
    rig::RiderParams rider;
    std::shared_ptr<const rig::Character> built_horse, built_rider;
  };
  // How skin() picks each pair's level: a fixed one, or from the camera (render/detail_level.h).
  struct LevelChoice {
    int fixed = 0;                    // >= 0: every pair at this level
    const Camera* camera = nullptr;   // fixed < 0: from each pair's size through this camera
    int width = 0, height = 0;        // the film's, in pixels
  };
  explicit Crowd(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
  std::vector<Pair> pairs;
  std::vector<Build> builds;
  double build_ms = 0;     // building levels, since the caller last cleared it
  int follow = -1;         // CameraSpec::follow_pair
  tbb::task_arena arena;   // the shot's threads, for building, baking and skinning the pairs

  // Builds the characters of every (pair, level) in `needed` that has none yet, in parallel. Pure
  // functions of their parameters, so when they are built changes nothing.
  void buildLevels(const std::vector<std::pair<std::size_t, int>>& needed) {
    std::vector<std::size_t> todo;
    for (const auto& [i, k] : needed) {
      const std::size_t b = pairs[i].builds[std::size_t(k)];
      if (!builds[b].built_horse && std::find(todo.begin(), todo.end(), b) == todo.end()) todo.push_back(b);
    }
    if (!todo.empty()) {
      const auto t0 = Clock::now();
      arena.execute([&] {
        tbb::parallel_for(std::size_t(0), 2 * todo.size(), [&](std::size_t j) {
          Build& b = builds[todo[j / 2]];
          if (j % 2 == 0)
            b.built_horse = std::make_shared<const rig::Character>(rig::buildHorse(b.horse));
          else
            b.built_rider = std::make_shared<const rig::Character>(rig::buildRider(b.rider, b.horse.mount));
        });
      });
      build_ms += msSince(t0);
    }
    for (const auto& [i, k] : needed) {
      Level& l = pairs[i].levels[std::size_t(k)];
      if (l.horse) continue;
      const Build& b = builds[pairs[i].builds[std::size_t(k)]];
      l.horse = b.built_horse;
      l.rider = b.built_rider;
      // One pose skins every level: their skeletons must be the same (only the mesh's cell differs).
      const Level& coarsest = pairs[i].levels[kDetailLevels - 1];
      if (coarsest.horse && (!sameSkeleton(*l.horse, *coarsest.horse) || !sameSkeleton(*l.rider, *coarsest.rider)))
        throw std::logic_error("Shot: a level of detail's skeleton differs from the coarsest level's");
    }
  }
  static bool sameSkeleton(const rig::Character& a, const rig::Character& b) {
    if (a.skeleton.size() != b.skeleton.size()) return false;
    for (std::size_t j = 0; j < a.skeleton.size(); ++j)
      if (a.skeleton.joints[j].inverse_bind != b.skeleton.joints[j].inverse_bind ||
          a.skeleton.joints[j].parent != b.skeleton.joints[j].parent)
        return false;
    return true;
  }

  // Every pair's frame as shown (the held pose; the rigid rider), baked in parallel.
  std::vector<rig::BakedFrame> bakeShown(const SceneSpec& scene, const CameraSpec& camera, bool rigid, int frame) {
    const int shown = camera.hold_frame > 0 ? camera.hold_frame : frame;
    std::vector<rig::CrowdPair> list;
    for (const Pair& p : pairs) list.push_back({p.clip.get(), rigid ? &p.rigid_profile : &p.profile, p.clip_offset_s});
    std::vector<rig::BakedFrame> baked;
    arena.execute([&] { baked = rig::bakeCrowdFrame(list, shown, frameTime(scene, shown)); });
    for (rig::BakedFrame& b : baked) {
      b.frame = frame;
      if (rigid) b.rider = rig::RiderChannels{};
    }
    return baked;
  }
  // Poses the pairs of `baked` (all, or only `only`) and picks each one's level, in parallel; builds
  // the levels picked that are not built yet; skins each pair's level into its buffers, in parallel.
  void skin(const std::vector<rig::BakedFrame>& baked, bool rigid, const LevelChoice& choice, int only = -1) {
    const auto each = [&](const std::function<void(Pair&, std::size_t)>& f) {
      arena.execute([&] {
        tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t i) {
          if (only < 0 || int(i) == only) f(pairs[i], i);
        });
      });
    };
    each([&](Pair& p, std::size_t i) {
      p.pose = rig::poseMounted(p.horse(), p.rider(), baked[i].horse, baked[i].rider, rigid ? p.rigid_profile : p.profile);
      if (choice.fixed >= 0) {
        p.level = choice.fixed;
      } else {
        const glm::dvec3 root(p.pose.horse[std::size_t(p.horse().role("root"))][3]);
        p.level = pairDetailLevel(*choice.camera, choice.width, choice.height, root, p.horse_cell_cm);
      }
    });
    std::vector<std::pair<std::size_t, int>> needed;
    for (std::size_t i = 0; i < pairs.size(); ++i)
      if (only < 0 || int(i) == only) needed.emplace_back(i, pairs[i].level);
    buildLevels(needed);
    each([&](Pair& p, std::size_t) {
      const Level& l = p.levels[std::size_t(p.level)];
      rig::skinMesh(l.horse->mesh, l.horse->skeleton, p.pose.horse, p.horse_positions, p.horse_normals);
      rig::skinMesh(l.rider->mesh, l.rider->skeleton, p.pose.rider, p.rider_positions, p.rider_normals);
    });
  }
};

Shot::Shot(const SceneSpec& scene, const rig::RigProfile& profile, const CameraSpec& camera, int threads,
           BvhUpdate bvh)
    : scene_(scene),
      profile_(profile),
      camera_(camera) {
  if (scene.pairs.empty()) {
    // A crowd's characters are its pairs' own (setUpCrowd).
    rig::RiddenPair pair = rig::resolveRiddenPair(scene.horse, scene.horse_mapping, scene.rider, scene.rider_mapping, profile);
    horse_ = std::move(pair.horse);
    rider_ = std::move(pair.rider);
    clip_ = rig::makeClip(scene.clip, horse_);  // a path clip turns hooves about this horse's rest places
  } else {
    setUpCrowd(threads);
  }
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
  settings.open_ground_shortcuts = scene.pairs.size() < 2;
  renderer_ = std::make_unique<Renderer>(settings);
  if (scene.terrain && !scene.terrain->flat()) {
    std::vector<const rig::Clip*> tracks;
    if (crowd_)
      for (const Crowd::Pair& p : crowd_->pairs) tracks.push_back(p.shown.get());
    else
      tracks.push_back(clip_.get());
    renderer_->setTerrain(scene.terrain, trackRegion(scene_, tracks));
  }
  if (crowd_) {
    // A pair's levels join the renderer when first shown (renderCrowdMeshes).
  } else {
    horse_mesh_ = renderer_->addMesh(meshOf(ObjectId::Horse, horse_));
    rider_mesh_ = renderer_->addMesh(meshOf(ObjectId::Rider, rider_));
  }
  rigid_profile_ = profile_;
  rigid_profile_.rigid = true;
  addObstacles();
  if (!camera_.view.empty()) {
    // A named view: framed from the characters' vertices over every frame it shows (render/view.h);
    // in a crowd, the followed pair's, or with none the corners of every pair's horse's and rider's
    // boxes (they hold every vertex; every third vertex of 30 pairs over a whole ride took gigabytes).
    CameraSpec preset = camera_;
    applyViewPreset(preset);
    const rig::Character& horse = cameraHorse();
    const glm::vec3 lever = horse.skeleton.restPosition(horse.role("saddle")) -
                            horse.skeleton.restPosition(horse.role("root"));
    preset.seat_from_pivot_cm = {lever.x, lever.y, lever.z};
    camera_ = preset;  // treadmill / hold apply while sampling the points
    const int follow = crowd_ ? crowd_->follow : -1;
    camera_ = frameView(preset, scene_, *clip_, cameraProfile(), framingFrames(preset, scene_),
                        [this, follow](int f, std::vector<glm::dvec3>& h, std::vector<glm::dvec3>& r) {
                          if (follow >= 0)
                            pairPoints(follow, f, 3, h, r);
                          else if (crowd_)
                            crowdCorners(f, h, r);
                          else
                            characterPoints(f, 3, h, r);
                        });
  }
}

void Shot::setUpCrowd(int threads) {
  const std::string source = scene_.file.string();
  if (camera_.follow_pair >= int(scene_.pairs.size()))
    throw InputError(source + ": cameras." + camera_.name + ".follow_pair: expected a pair index from 0 to " +
                     std::to_string(scene_.pairs.size() - 1) + ", got " + std::to_string(camera_.follow_pair));
  if (camera_.treadmill) throw InputError(source + ": cameras." + camera_.name + ".treadmill: expected false in a crowd scene");
  crowd_ = std::make_unique<Crowd>(threads);
  crowd_->follow = camera_.follow_pair;
  // Each profile name resolved once, as the scene's own is (profiles/NAME.json beside the scene, then
  // the data folder; the scene's profile_overrides applied).
  std::map<std::string, rig::RigProfile> profiles;
  for (const rig::PairSpec& spec : scene_.pairs) {
    if (profiles.count(spec.profile)) continue;
    SceneSpec named = scene_;
    named.profile = spec.profile;
    profiles.emplace(spec.profile, resolveProfile(named));
  }
  crowd_->pairs.resize(scene_.pairs.size());
  for (std::size_t i = 0; i < scene_.pairs.size(); ++i) {
    const rig::PairSpec& spec = scene_.pairs[i];
    Crowd::Pair& p = crowd_->pairs[i];
    p.clip = rig::makePairClip(spec, scene_.terrain, source + ": pairs[" + std::to_string(i) + "]");
    p.clip_offset_s = spec.clip_offset_s;
    p.shown = std::make_unique<rig::ShiftedClip>(*p.clip, spec.clip_offset_s);
    p.profile = profiles.at(spec.profile);
    p.rigid_profile = p.profile;
    p.rigid_profile.rigid = true;
  }
  buildCrowdCharacters();
  if (crowd_->follow >= 0) {
    clip_ = std::make_unique<rig::ShiftedClip>(*crowd_->pairs[std::size_t(crowd_->follow)].clip,
                                               crowd_->pairs[std::size_t(crowd_->follow)].clip_offset_s);
  } else {
    std::vector<const rig::Clip*> shown;
    for (const Crowd::Pair& p : crowd_->pairs) shown.push_back(p.shown.get());
    clip_ = std::make_unique<rig::CrowdMiddleClip>(shown);
  }
}

// Every pair's characters at every level of detail, as builds: pairs of the same proportions and
// colours share theirs (a `riders` list often repeats them). Each is built when a frame first needs it
// (a wide view of a troop never needs full detail); the coarsest level of every pair now, as the views
// are framed from it and every pair is posed with it.
void Shot::buildCrowdCharacters() {
  // A pair's proportions, colours and level -> its build.
  using Key = std::tuple<double, double, double, std::string, std::string, std::string, std::string, int>;
  std::map<Key, std::size_t> build_of;
  for (std::size_t i = 0; i < scene_.pairs.size(); ++i) {
    const rig::PairSpec& spec = scene_.pairs[i];
    Crowd::Pair& p = crowd_->pairs[i];
    for (int k = 0; k < kDetailLevels; ++k) {
      const Key key{spec.withers_height_cm, spec.rider_height_cm, spec.rider_build, spec.coat, spec.jacket, spec.hair,
                    spec.skin, k};
      auto [it, inserted] = build_of.emplace(key, crowd_->builds.size());
      if (inserted) {
        Crowd::Build b{spec.horse(), spec.rider(), nullptr, nullptr};
        b.horse.cell *= kDetailCellFactor[k];
        b.rider.cell *= kDetailCellFactor[k];
        crowd_->builds.push_back(std::move(b));
      }
      p.builds[std::size_t(k)] = it->second;
    }
    p.horse_cell_cm = crowd_->builds[p.builds[0]].horse.cell;
  }
  std::vector<std::pair<std::size_t, int>> coarsest;
  for (std::size_t i = 0; i < crowd_->pairs.size(); ++i) coarsest.emplace_back(i, kDetailLevels - 1);
  crowd_->buildLevels(coarsest);
}

const rig::Character& Shot::cameraHorse() const {
  if (!crowd_) return horse_;
  return crowd_->pairs[std::size_t(std::max(0, crowd_->follow))].horse();
}

const rig::RigProfile& Shot::cameraProfile() const {
  if (!crowd_) return profile_;
  // The middle clip's controls are at rest, so its profile only sets the seat's rest (rider_unit_cm).
  return crowd_->pairs[std::size_t(std::max(0, crowd_->follow))].profile;
}

void Shot::setDetailLevel(int level) {
  if (level < -1 || level >= kDetailLevels)
    throw std::invalid_argument("Shot::setDetailLevel: expected -1 to " + std::to_string(kDetailLevels - 1));
  detail_level_ = level;
}

int Shot::pairCount() const { return crowd_ ? int(crowd_->pairs.size()) : 0; }

Shot::~Shot() = default;

const rig::RigProfile& Shot::poseProfile() const { return rigid_rider_ ? rigid_profile_ : profile_; }

// The clip's fences, standing in the world: each under the middle of the horse (halfway between its
// rest fore and hind hooves) where the clip says, in the travel frame. A treadmill shot, which takes
// the travel out, has nothing to stand still against, so it shows no fence. Props are ground-like in
// the passes (object id 0, outside the characters' matte) and never move, so they are set once.
void Shot::addObstacles() {
  // A crowd's pairs ride path clips, which have no fences.
  if (camera_.treadmill || crowd_) return;
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
  return rig::bakeFrame(*clip_, cameraProfile(), frame, frameTime(scene_, frame));
}

Camera Shot::cameraAt(const rig::BakedFrame& baked) const { return cameraAtFrame(baked.frame); }

Camera Shot::cameraAtFrame(int frame) const {
  return render::cameraAtFrame(camera_, scene_, *clip_, cameraProfile(), frame);
}

rig::BakedFrame Shot::bakeShown(int frame) const {
  rig::BakedFrame baked = bake(camera_.hold_frame > 0 ? camera_.hold_frame : frame);
  baked.frame = frame;
  if (camera_.treadmill) baked.horse.travel_cm = baked.horse.travel_z_cm = 0.0;
  if (rigid_rider_) baked.rider = rig::RiderChannels{};
  return baked;
}

void Shot::pairPoints(int pair, int frame, int stride, std::vector<glm::dvec3>& horse,
                      std::vector<glm::dvec3>& rider) {
  if (!crowd_ || pair < 0 || pair >= pairCount())
    throw std::invalid_argument("Shot::pairPoints: no pair " + std::to_string(pair));
  crowd_->skin(crowd_->bakeShown(scene_, camera_, rigid_rider_, frame), rigid_rider_, {}, pair);
  const Crowd::Pair& p = crowd_->pairs[std::size_t(pair)];
  const std::size_t step = static_cast<std::size_t>(std::max(1, stride));
  horse.clear();
  rider.clear();
  for (std::size_t i = 0; i < p.horse_positions.size(); i += step) horse.emplace_back(p.horse_positions[i]);
  for (std::size_t i = 0; i < p.rider_positions.size(); i += step) rider.emplace_back(p.rider_positions[i]);
}

void Shot::crowdCorners(int frame, std::vector<glm::dvec3>& horse, std::vector<glm::dvec3>& rider) {
  // The coarsest level: its boxes are the full level's within a cell (a few cm against a view's 12%
  // margin), at a sixteenth of the skinning.
  crowd_->skin(crowd_->bakeShown(scene_, camera_, rigid_rider_, frame), rigid_rider_, {kDetailLevels - 1});
  horse.clear();
  rider.clear();
  const auto corners = [](const std::vector<glm::vec3>& points, std::vector<glm::dvec3>& out) {
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const glm::vec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (int c = 0; c < 8; ++c) out.emplace_back(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
  };
  for (const Crowd::Pair& p : crowd_->pairs) {
    corners(p.horse_positions, horse);
    corners(p.rider_positions, rider);
  }
}

void Shot::characterPoints(int frame, int stride, std::vector<glm::dvec3>& horse,
                           std::vector<glm::dvec3>& rider) {
  if (crowd_) {
    crowd_->skin(crowd_->bakeShown(scene_, camera_, rigid_rider_, frame), rigid_rider_, {});
    const std::size_t step = static_cast<std::size_t>(std::max(1, stride));
    horse.clear();
    rider.clear();
    for (const Crowd::Pair& p : crowd_->pairs) {
      for (std::size_t i = 0; i < p.horse_positions.size(); i += step) horse.emplace_back(p.horse_positions[i]);
      for (std::size_t i = 0; i < p.rider_positions.size(); i += step) rider.emplace_back(p.rider_positions[i]);
    }
    return;
  }
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

void Shot::renderCrowdMeshes(int frame, const Camera& camera) {
  auto t0 = Clock::now();
  const std::vector<rig::BakedFrame> baked = crowd_->bakeShown(scene_, camera_, rigid_rider_, frame);
  timings_.pose_ms = msSince(t0);
  // Posing is inside the skinning loop here (each pair posed and skinned by one task).
  t0 = Clock::now();
  crowd_->build_ms = 0.0;
  crowd_->skin(baked, rigid_rider_, {detail_level_, &camera, scene_.width, scene_.height});
  timings_.build_ms = crowd_->build_ms;
  // Levels shown for the first time join the renderer, each with its own fixed geometry ids (pair,
  // level, horse or rider), so the scene is the same whichever frames were rendered before.
  for (std::size_t i = 0; i < crowd_->pairs.size(); ++i) {
    Crowd::Pair& p = crowd_->pairs[i];
    Crowd::Level& l = p.levels[std::size_t(p.level)];
    if (l.horse_mesh >= 0) continue;
    const int id = 2 * (int(i) * kDetailLevels + p.level);
    MeshDesc horse = meshOf(ObjectId::Horse, *l.horse), rider = meshOf(ObjectId::Rider, *l.rider);
    horse.geometry_id = id;
    rider.geometry_id = id + 1;
    l.horse_mesh = renderer_->addMesh(horse);
    l.rider_mesh = renderer_->addMesh(rider);
  }
  timings_.pairs_at_level = {};
  timings_.skinned_vertices = 0;
  for (const Crowd::Pair& p : crowd_->pairs) {
    for (int k = 0; k < kDetailLevels; ++k) {
      const Crowd::Level& l = p.levels[std::size_t(k)];
      if (l.horse_mesh < 0) continue;
      renderer_->setMeshEnabled(l.horse_mesh, k == p.level);
      renderer_->setMeshEnabled(l.rider_mesh, k == p.level);
    }
    const Crowd::Level& shown = p.levels[std::size_t(p.level)];
    renderer_->updateMesh(shown.horse_mesh, p.horse_positions, p.horse_normals);
    renderer_->updateMesh(shown.rider_mesh, p.rider_positions, p.rider_normals);
    ++timings_.pairs_at_level[std::size_t(p.level)];
    timings_.skinned_vertices += p.horse_positions.size() + p.rider_positions.size();
  }
  timings_.skin_ms = msSince(t0);
}

Image Shot::renderFrame(int frame, RayLog* log) {
  if (crowd_) {
    const Camera camera = cameraAtFrame(frame);
    renderCrowdMeshes(frame, camera);
    auto t0 = Clock::now();
    Image image = renderer_->render(camera, frame, log);
    timings_.trace_ms = msSince(t0);
    timings_.bvh_ms = renderer_->lastStats().commit_ms;
    timings_.rays = renderer_->lastStats().rays;
    timings_.triangles = renderer_->lastStats().triangles;
    return image;
  }
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
  timings_.triangles = renderer_->lastStats().triangles;
  timings_.skinned_vertices = positions_.size() + horse_.mesh.positions.size();
  return image;
}

}  // namespace stirrup::render
