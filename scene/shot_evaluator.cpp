#include "scene/shot_evaluator.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <tuple>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/crowd_bake.h"
#include "rig/motion/crowd.h"
#include "rig/motion/shifted_clip.h"
#include "rig/parallel_first_error.h"
#include "rig/skin.h"
#include "scene/clip_factory.h"
#include "scene/detail_level.h"
#include "scene/profile_resolver.h"
#include "scene/ridden_pair.h"

namespace stirrup::scene {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

bool sameSkeleton(const rig::Character& a, const rig::Character& b) {
  if (a.skeleton.size() != b.skeleton.size()) return false;
  for (std::size_t j = 0; j < a.skeleton.size(); ++j)
    if (a.skeleton.joints[j].inverse_bind != b.skeleton.joints[j].inverse_bind ||
        a.skeleton.joints[j].parent != b.skeleton.joints[j].parent)
      return false;
  return true;
}

}  // namespace

ShownAs shownAs(const CameraSpec& camera, bool rigid_rider) {
  return {camera.hold_frame, camera.treadmill, rigid_rider};
}

// The pairs: each one's clip, profiles and levels; the distinct characters the levels share; the threads.
struct ShotEvaluator::Pairs {
  // A distinct horse and rider: a crowd pair's proportions, colours and level, built when first needed;
  // or a single pair's, as read and seated (built from the start).
  struct Build {
    rig::HorseParams horse;
    rig::RiderParams rider;
    std::shared_ptr<const rig::Character> built_horse, built_rider;
  };
  struct Pair {
    std::shared_ptr<const rig::Clip> clip;    // the scene's clip, or the pair's (made as the scene loaded)
    std::unique_ptr<rig::ShiftedClip> shown;  // a crowd pair's clip at its start phase
    double clip_offset_s = 0;
    rig::RigProfile profile, rigid_profile;
    std::vector<std::size_t> builds;          // each level's entry in `builds`
    rig::SeatReport seat;
    const rig::Clip& shownClip() const { return shown ? *shown : *clip; }
  };
  explicit Pairs(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
  std::vector<Pair> pairs;
  std::vector<Build> builds;
  int levels = 1;
  double build_ms = 0;
  tbb::task_arena arena;

  const Build& build(std::size_t pair, int level) const { return builds[pairs[pair].builds[std::size_t(level)]]; }
  // The characters posing uses: every level has the same skeleton (buildLevels checks it), so the
  // coarsest level's, which is built from the start.
  const rig::Character& poseHorse(std::size_t pair) const { return *build(pair, levels - 1).built_horse; }
  const rig::Character& poseRider(std::size_t pair) const { return *build(pair, levels - 1).built_rider; }

  // Builds the characters of every (pair, level) in `needed` that has none yet, and each such pair's
  // coarsest level, in parallel.
  void buildLevels(std::vector<std::pair<std::size_t, int>> needed) {
    const std::size_t asked = needed.size();
    for (std::size_t k = 0; k < asked; ++k) needed.emplace_back(needed[k].first, levels - 1);
    std::vector<std::size_t> todo;
    for (const auto& [i, k] : needed) {
      const std::size_t b = pairs[i].builds[std::size_t(k)];
      if (!builds[b].built_horse && std::find(todo.begin(), todo.end(), b) == todo.end()) todo.push_back(b);
    }
    if (todo.empty()) return;
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
    // One pose skins every level: their skeletons must be the same (only the mesh's cell differs).
    for (const auto& [i, k] : needed) {
      const Build& b = build(i, k);
      if (!sameSkeleton(*b.built_horse, poseHorse(i)) || !sameSkeleton(*b.built_rider, poseRider(i)))
        throw std::logic_error("ShotEvaluator: a level of detail's skeleton differs from the coarsest level's");
    }
  }
  // A pair's coarsest level, which it is posed with.
  void buildCoarsest(const std::vector<std::size_t>& which) {
    std::vector<std::pair<std::size_t, int>> needed;
    for (std::size_t i : which) needed.emplace_back(i, levels - 1);
    buildLevels(needed);
  }
};

ShotEvaluator::ShotEvaluator(const SceneSpec& scene, const rig::RigProfile& profile, int threads)
    : scene_(scene), pairs_(std::make_unique<Pairs>(threads)) {
  Pairs& ps = *pairs_;
  if (scene.pairs.empty()) {
    // The one pair: the scene's characters (as read or built, seated by the rig) on the scene's clip,
    // on the shot's threads (building a character meshes it in parallel).
    Pairs::Pair p;
    scene::RiddenPair pair;
    ps.arena.execute([&] {
      pair = scene::resolveRiddenPair(scene.horse, scene.horse_mapping, scene.rider, scene.rider_mapping, profile);
      p.clip = scene::makeClip(scene.clip, pair.horse);  // a path clip turns hooves about this horse's rest places
    });
    p.profile = profile;
    p.seat = pair.seat;
    p.builds = {0};
    ps.builds.push_back({rig::HorseParams{}, rig::RiderParams{}, std::make_shared<const rig::Character>(std::move(pair.horse)),
                         std::make_shared<const rig::Character>(std::move(pair.rider))});
    ps.pairs.push_back(std::move(p));
  } else {
    const std::string source = scene.file.string();
    ps.levels = kDetailLevels;
    // Each profile name resolved once, as the scene's own is (profiles/NAME.json beside the scene, then
    // the data folder; the scene's profile_overrides applied).
    std::map<std::string, rig::RigProfile> profiles;
    for (const rig::PairSpec& spec : scene.pairs) {
      if (profiles.count(spec.profile)) continue;
      SceneSpec named = scene;
      named.profile = spec.profile;
      profiles.emplace(spec.profile, resolveProfile(named));
    }
    // Pairs of the same proportions and colours share their characters (a `riders` list often repeats
    // them): a pair's proportions, colours and level -> its build.
    using Key = std::tuple<double, double, double, std::string, std::string, std::string, std::string, int>;
    std::map<Key, std::size_t> build_of;
    ps.pairs.resize(scene.pairs.size());
    // Each pair's clip (a path clip: its footfalls scanned, a few ms a second of ride): the ones the
    // scene made as it loaded, unless its ground has changed since; else made here, the pairs in
    // parallel, a bad pair's error the first bad pair's whatever the threads.
    if (scene.pair_clips.size() == scene.pairs.size() && scene.pair_clips_terrain == scene.terrain) {
      for (std::size_t i = 0; i < scene.pairs.size(); ++i) ps.pairs[i].clip = scene.pair_clips[i];
    } else {
      ps.arena.execute([&] {
        rig::parallelForFirstError(scene.pairs.size(), [&](std::size_t i) {
          ps.pairs[i].clip = rig::pairClip(scene.pairs[i], scene.terrain, source + ": pairs[" + std::to_string(i) + "]");
        });
      });
    }
    for (std::size_t i = 0; i < scene.pairs.size(); ++i) {
      const rig::PairSpec& spec = scene.pairs[i];
      Pairs::Pair& p = ps.pairs[i];
      p.clip_offset_s = spec.clip_offset_s;
      p.shown = std::make_unique<rig::ShiftedClip>(*p.clip, spec.clip_offset_s);
      p.profile = profiles.at(spec.profile);
      if (spec.characters) {
        // The user's characters (scene/crowd_characters.h), read and seated as the scene loaded: one
        // build at every level (a file's mesh has one detail).
        const rig::PairCharacters& own = *spec.characters;
        p.seat = own.seat;
        p.builds.assign(std::size_t(kDetailLevels), ps.builds.size());
        ps.builds.push_back({rig::HorseParams{}, rig::RiderParams{}, own.horse, own.rider});
        continue;
      }
      for (int k = 0; k < kDetailLevels; ++k) {
        const Key key{spec.withers_height_cm, spec.rider_height_cm, spec.rider_build, spec.coat, spec.jacket, spec.hair,
                      spec.skin, k};
        auto [it, inserted] = build_of.emplace(key, ps.builds.size());
        if (inserted) {
          Pairs::Build b{spec.horse(), spec.rider(), nullptr, nullptr};
          b.horse.cell *= kDetailCellFactor[k];
          b.rider.cell *= kDetailCellFactor[k];
          ps.builds.push_back(std::move(b));
        }
        p.builds.push_back(it->second);
      }
    }
    // Each pair's characters are built when first needed (posing needs the coarsest level; a wide view
    // of a troop never needs full detail; a bake of the channels needs none).
  }
  for (Pairs::Pair& p : ps.pairs) {
    p.rigid_profile = p.profile;
    p.rigid_profile.rigid = true;
  }
}

ShotEvaluator::ShotEvaluator(const FileShot& shot, const rig::RigProfile& profile, int threads)
    : scene_(shot.scene), pairs_(std::make_unique<Pairs>(threads)), file_(shot.shot) {
  Pairs& ps = *pairs_;
  for (std::size_t i = 0; i < file_->pairs().size(); ++i) {
    const rig::GltfShot::Pair& sp = file_->pairs()[i];
    Pairs::Pair p;
    p.clip = fileShotTravel(shot, i);
    p.profile = p.rigid_profile = profile;
    p.builds = {ps.builds.size()};
    ps.builds.push_back({rig::HorseParams{}, rig::RiderParams{}, std::make_shared<const rig::Character>(sp.horse),
                         std::make_shared<const rig::Character>(sp.rider)});
    ps.pairs.push_back(std::move(p));
  }
}

ShotEvaluator::~ShotEvaluator() = default;

int ShotEvaluator::pairCount() const { return int(pairs_->pairs.size()); }
int ShotEvaluator::levelCount() const { return pairs_->levels; }

namespace {
void checkPair(int pair, int count, const char* what) {
  if (pair < 0 || pair >= count)
    throw std::invalid_argument(std::string("ShotEvaluator::") + what + ": no pair " + std::to_string(pair));
}
}  // namespace

const rig::Clip& ShotEvaluator::shownClip(int pair) const {
  checkPair(pair, pairCount(), "shownClip");
  return pairs_->pairs[std::size_t(pair)].shownClip();
}
const rig::Clip& ShotEvaluator::clip(int pair) const {
  checkPair(pair, pairCount(), "clip");
  return *pairs_->pairs[std::size_t(pair)].clip;
}
double ShotEvaluator::clipOffsetS(int pair) const {
  checkPair(pair, pairCount(), "clipOffsetS");
  return pairs_->pairs[std::size_t(pair)].clip_offset_s;
}
const rig::RigProfile& ShotEvaluator::profile(int pair) const {
  checkPair(pair, pairCount(), "profile");
  return pairs_->pairs[std::size_t(pair)].profile;
}
const rig::Character& ShotEvaluator::horse(int pair) {
  checkPair(pair, pairCount(), "horse");
  pairs_->buildCoarsest({std::size_t(pair)});
  return pairs_->poseHorse(std::size_t(pair));
}
const rig::Character& ShotEvaluator::rider(int pair) {
  checkPair(pair, pairCount(), "rider");
  pairs_->buildCoarsest({std::size_t(pair)});
  return pairs_->poseRider(std::size_t(pair));
}
const rig::Character& ShotEvaluator::horseAt(int pair, int level) {
  checkPair(pair, pairCount(), "horseAt");
  if (level < 0 || level >= levelCount()) throw std::invalid_argument("ShotEvaluator::horseAt: no level " + std::to_string(level));
  pairs_->buildLevels({{std::size_t(pair), level}});
  return *pairs_->build(std::size_t(pair), level).built_horse;
}
const rig::Character& ShotEvaluator::riderAt(int pair, int level) {
  checkPair(pair, pairCount(), "riderAt");
  if (level < 0 || level >= levelCount()) throw std::invalid_argument("ShotEvaluator::riderAt: no level " + std::to_string(level));
  pairs_->buildLevels({{std::size_t(pair), level}});
  return *pairs_->build(std::size_t(pair), level).built_rider;
}
const rig::SeatReport& ShotEvaluator::seat(int pair) const {
  checkPair(pair, pairCount(), "seat");
  return pairs_->pairs[std::size_t(pair)].seat;
}
double ShotEvaluator::horseCellCm(int pair) const {
  checkPair(pair, pairCount(), "horseCellCm");
  return pairs_->build(std::size_t(pair), 0).horse.cell;
}

std::string ShotEvaluator::pairName(int pair) const {
  checkPair(pair, pairCount(), "pairName");
  return isCrowd() ? crowdPairName(pair, pairCount()) : "";
}

std::string crowdPairName(int pair, int pair_count) {
  const std::size_t digits = std::max<std::size_t>(2, std::to_string(std::max(0, pair_count - 1)).size());
  const std::string index = std::to_string(pair);
  return "pair" + std::string(digits > index.size() ? digits - index.size() : 0, '0') + index;
}

namespace {

// The pairs a request asks for, in the scene's order.
std::vector<std::size_t> pairsAsked(const FrameRequest& request, std::size_t pair_count) {
  std::vector<std::size_t> which;
  for (std::size_t i = 0; i < pair_count; ++i)
    if (request.only_pair < 0 || int(i) == request.only_pair) which.push_back(i);
  return which;
}

}  // namespace

// The three stages of a frame, each for the pairs `which`, writing only their own PairFrames: evaluate
// runs them stage by stage over the pairs (timing each), evaluateEach frame by frame; both through
// these, so a frame is the same either way.
void ShotEvaluator::bakeStage(const FrameRequest& request, const std::vector<std::size_t>& which, ShotFrame& out) const {
  const Pairs& ps = *pairs_;
  const bool rigid = request.shown.rigid_rider;
  // Every pair's clip and profile at the frame shown (the held pose's), its time the shot's.
  const int shown = request.shown.hold_frame > 0 ? request.shown.hold_frame : request.frame;
  if (file_) {
    // A glTF shot has nothing to bake: its poses are the file's. The travel is kept for the treadmill.
    for (std::size_t i : which) {
      rig::BakedFrame& b = out.pairs[i].baked;
      b = {};
      b.frame = request.frame;
      b.seconds = frameTime(scene_, shown);
      b.horse = ps.pairs[i].clip->sampleTravel(b.seconds);
    }
    return;
  }
  std::vector<rig::CrowdPair> list;
  for (std::size_t i : which)
    list.push_back({ps.pairs[i].clip.get(), rigid ? &ps.pairs[i].rigid_profile : &ps.pairs[i].profile, ps.pairs[i].clip_offset_s});
  std::vector<rig::BakedFrame> baked = rig::bakeCrowdFrame(list, shown, frameTime(scene_, shown));
  for (std::size_t k = 0; k < which.size(); ++k) {
    rig::BakedFrame& b = out.pairs[which[k]].baked;
    b = std::move(baked[k]);
    b.frame = request.frame;
    if (request.shown.treadmill) b.horse.travel_cm = b.horse.travel_z_cm = 0.0;
    if (rigid) b.rider = rig::RiderChannels{};
  }
}

void ShotEvaluator::poseStage(const FrameRequest& request, std::size_t i, PairFrame& f) const {
  const Pairs& ps = *pairs_;
  const Pairs::Pair& p = ps.pairs[i];
  const rig::Character& horse = ps.poseHorse(i);
  const bool rigid = request.shown.rigid_rider;
  if (file_) {
    f.pose = filePose(request, i, f.baked);
  } else {
    f.pose = rig::poseMounted(horse, ps.poseRider(i), f.baked.horse, f.baked.rider, rigid ? p.rigid_profile : p.profile);
  }
  const LevelChoice& choice = request.level;
  if (choice.fixed >= 0 || ps.levels == 1) {
    f.level = std::clamp(choice.fixed, 0, ps.levels - 1);
  } else {
    const glm::dvec3 root(f.pose.horse[std::size_t(horse.role("root"))][3]);
    f.level = std::min(pairDetailLevel(*choice.camera, choice.width, choice.height, root, ps.build(i, 0).horse.cell),
                       ps.levels - 1);
  }
}

// A glTF shot's pair as its file keys it at the frame shown; on a treadmill its travel taken out (the file's joints moved back by the travel frame's origin).
rig::MountedPose ShotEvaluator::filePose(const FrameRequest& request, std::size_t i, const rig::BakedFrame& baked) const {
  const int shown = request.shown.hold_frame > 0 ? request.shown.hold_frame : request.frame;
  rig::MountedPose pose = file_->pose(i, shown);
  if (request.shown.treadmill) {
    const glm::vec3 back(-float(baked.horse.travel_cm), 0.0f, -float(baked.horse.travel_z_cm));
    for (std::vector<glm::mat4>* joints : {&pose.horse, &pose.rider})
      for (glm::mat4& m : *joints) m[3] += glm::vec4(back, 0.0f);
  }
  return pose;
}

void ShotEvaluator::skinStage(const FrameRequest& request, std::size_t i, PairFrame& f) const {
  const Pairs::Build& b = pairs_->build(i, f.level);
  if (request.until == EvalStage::Points) {
    rig::skinPositions(b.built_horse->mesh, b.built_horse->skeleton, f.pose.horse, request.point_stride, f.horse_positions);
    rig::skinPositions(b.built_rider->mesh, b.built_rider->skeleton, f.pose.rider, request.point_stride, f.rider_positions);
    f.horse_normals.clear();
    f.rider_normals.clear();
    return;
  }
  rig::skinMesh(b.built_horse->mesh, b.built_horse->skeleton, f.pose.horse, f.horse_positions, f.horse_normals);
  rig::skinMesh(b.built_rider->mesh, b.built_rider->skeleton, f.pose.rider, f.rider_positions, f.rider_normals);
}

void ShotEvaluator::evaluate(const FrameRequest& request, ShotFrame& out) {
  Pairs& ps = *pairs_;
  if (request.only_pair >= pairCount()) throw std::invalid_argument("ShotEvaluator::evaluate: no pair " + std::to_string(request.only_pair));
  out.pairs.resize(ps.pairs.size());
  timings_ = {};
  const std::vector<std::size_t> which = pairsAsked(request, ps.pairs.size());
  const auto each = [&](const std::function<void(std::size_t)>& f) {
    ps.arena.execute([&] { tbb::parallel_for(std::size_t(0), which.size(), [&](std::size_t k) { f(which[k]); }); });
  };

  auto t0 = Clock::now();
  ps.arena.execute([&] { bakeStage(request, which, out); });
  timings_.bake_ms = msSince(t0);
  if (request.until == EvalStage::Bake) return;

  // Pose, and pick each pair's level.
  t0 = Clock::now();
  ps.build_ms = 0;
  ps.buildCoarsest(which);
  each([&](std::size_t i) { poseStage(request, i, out.pairs[i]); });
  timings_.pose_ms = msSince(t0) - ps.build_ms;  // building is counted apart (a one-time cost)
  timings_.build_ms = ps.build_ms;
  if (request.until == EvalStage::Pose) return;

  // Skin each pair's level, building the levels no frame needed before.
  t0 = Clock::now();
  ps.build_ms = 0;
  std::vector<std::pair<std::size_t, int>> needed;
  for (std::size_t i : which) needed.emplace_back(i, out.pairs[i].level);
  ps.buildLevels(needed);
  timings_.build_ms += ps.build_ms;
  each([&](std::size_t i) { skinStage(request, i, out.pairs[i]); });
  timings_.skin_ms = msSince(t0);
}

void ShotEvaluator::run(const std::function<void()>& job) { pairs_->arena.execute(job); }

namespace {

// Frames whose buffers can be used again: one a frame in flight at most.
class FramePool {
 public:
  std::unique_ptr<ShotFrame> take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (spare_.empty()) return std::make_unique<ShotFrame>();
    std::unique_ptr<ShotFrame> f = std::move(spare_.back());
    spare_.pop_back();
    return f;
  }
  void give(std::unique_ptr<ShotFrame> f) {
    const std::lock_guard<std::mutex> lock(mutex_);
    spare_.push_back(std::move(f));
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<ShotFrame>> spare_;
};

}  // namespace

void ShotEvaluator::evaluateEach(const std::vector<FrameRequest>& requests,
                                 const std::function<void(std::size_t, ShotFrame&)>& use) {
  Pairs& ps = *pairs_;
  // Every character the requests need, built first (building is the one thing that changes the
  // evaluator), so the frames below only read it.
  std::set<std::pair<std::size_t, int>> needed;
  for (const FrameRequest& r : requests) {
    if (r.only_pair >= pairCount()) throw std::invalid_argument("ShotEvaluator::evaluateEach: no pair " + std::to_string(r.only_pair));
    if (r.level.fixed < 0) throw std::invalid_argument("ShotEvaluator::evaluateEach: expected every request's level fixed");
    if (r.until == EvalStage::Bake) continue;
    for (std::size_t i : pairsAsked(r, ps.pairs.size()))
      needed.emplace(i, r.until == EvalStage::Pose ? ps.levels - 1 : std::clamp(r.level.fixed, 0, ps.levels - 1));
  }
  ps.buildLevels({needed.begin(), needed.end()});
  FramePool spare_frames;
  ps.arena.execute([&] {
    tbb::parallel_for(std::size_t(0), requests.size(), [&](std::size_t k) {
      const FrameRequest& request = requests[k];
      const std::vector<std::size_t> which = pairsAsked(request, ps.pairs.size());
      // A frame whose buffers an earlier frame used (its points' vectors keep their capacity), so
      // skinning does not fault in fresh memory for every frame; taken from a pool, not per thread,
      // since a thread waiting in the pairs' loop below may start another frame.
      std::unique_ptr<ShotFrame> reused = spare_frames.take();
      ShotFrame& frame = *reused;
      frame.pairs.resize(ps.pairs.size());
      // Every pair as a fresh frame has it, its vectors emptied with their capacity kept: a pair not
      // asked for, or a stage that does not write a vector, leaves it as a fresh frame's.
      for (PairFrame& f : frame.pairs) {
        f.level = 0, f.baked = {}, f.pose = {};
        f.horse_positions.clear(), f.horse_normals.clear(), f.rider_positions.clear(), f.rider_normals.clear();
      }
      bakeStage(request, which, frame);
      if (request.until != EvalStage::Bake) {
        tbb::parallel_for(std::size_t(0), which.size(), [&](std::size_t j) {
          PairFrame& f = frame.pairs[which[j]];
          poseStage(request, which[j], f);
          if (request.until != EvalStage::Pose) skinStage(request, which[j], f);
        });
      }
      use(k, frame);
      spare_frames.give(std::move(reused));
    });
  });
}

void appendPoints(const PairFrame& pair, int stride, std::vector<glm::dvec3>& horse, std::vector<glm::dvec3>& rider) {
  const std::size_t step = static_cast<std::size_t>(std::max(1, stride));
  for (std::size_t i = 0; i < pair.horse_positions.size(); i += step) horse.emplace_back(pair.horse_positions[i]);
  for (std::size_t i = 0; i < pair.rider_positions.size(); i += step) rider.emplace_back(pair.rider_positions[i]);
}

void appendCorners(const PairFrame& pair, std::vector<glm::vec3>& horse, std::vector<glm::vec3>& rider) {
  const auto corners = [](const std::vector<glm::vec3>& points, std::vector<glm::vec3>& out) {
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const glm::vec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (int c = 0; c < 8; ++c) out.emplace_back(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
  };
  corners(pair.horse_positions, horse);
  corners(pair.rider_positions, rider);
}

}  // namespace stirrup::scene
