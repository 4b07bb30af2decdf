// The shot evaluator (scene/shot_evaluator.h): every pair of a scene baked, posed and skinned as the
// rig's own jobs give them one pair at a time, with a single pair a crowd of one; a held pose, a
// treadmill and the rigid rider as a camera shows them; the same frame at any thread count.
#include "scene/profile_resolver.h"
#include "scene/shot_evaluator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/motion/crowd.h"
#include "rig/pose.h"
#include "rig/skin.h"
#include "scene/detail_level.h"
#include "scene/ridden_pair.h"
#include "scene/scene.h"
#include "tests/render/crowd_of_four.h"

namespace stirrup::scene {
namespace {

using render::test::crowdOfFour;

SceneSpec trot() { return loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json"); }

void expectSameMatrices(const std::vector<glm::mat4>& a, const std::vector<glm::mat4>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t j = 0; j < a.size(); ++j) EXPECT_EQ(a[j], b[j]) << what << " joint " << j;
}

// The one pair of a scene: the scene's clip baked with the scene's profile, the characters as
// resolveRiddenPair seats them, posed by poseMounted and skinned by skinMesh, each called here alone.
TEST(ShotEvaluator, ASinglePairIsACrowdOfOne) {
  const SceneSpec scene = trot();
  const rig::RigProfile profile = resolveProfile(scene);
  ShotEvaluator eval(scene, profile, 1);
  EXPECT_EQ(eval.pairCount(), 1);
  EXPECT_EQ(eval.levelCount(), 1);
  EXPECT_FALSE(eval.isCrowd());
  EXPECT_EQ(eval.pairName(0), "");
  const std::unique_ptr<rig::Clip> clip = makeSceneClip(scene);
  const scene::RiddenPair pair = scene::resolveRiddenPair(scene.horse, scene.horse_mapping, scene.rider, scene.rider_mapping, profile);
  ShotFrame out;
  for (int frame : {1, 9, 30}) {
    FrameRequest request;
    request.frame = frame;
    eval.evaluate(request, out);
    ASSERT_EQ(out.pairs.size(), 1u);
    const PairFrame& p = out.pairs[0];
    const rig::BakedFrame b = rig::bakeFrame(*clip, profile, frame, (frame - 1) / scene.fps);
    EXPECT_EQ(p.baked.frame, frame);
    EXPECT_EQ(p.baked.seconds, (frame - 1) / 24.0);
    EXPECT_EQ(p.baked.horse.controls.value, b.horse.controls.value);
    EXPECT_EQ(p.baked.rider.value, b.rider.value);
    const rig::MountedPose pose = rig::poseMounted(pair.horse, pair.rider, b.horse, b.rider, profile);
    expectSameMatrices(p.pose.horse, pose.horse, "horse");
    expectSameMatrices(p.pose.rider, pose.rider, "rider");
    std::vector<glm::vec3> positions, normals;
    rig::skinMesh(pair.horse.mesh, pair.horse.skeleton, pose.horse, positions, normals);
    EXPECT_EQ(p.horse_positions, positions);
    EXPECT_EQ(p.horse_normals, normals);
    rig::skinMesh(pair.rider.mesh, pair.rider.skeleton, pose.rider, positions, normals);
    EXPECT_EQ(p.rider_positions, positions);
  }
}

// Each pair of a crowd is its own single-pair job: its clip (rig::makePairClip) at the shot's time plus
// its start phase, its own profile, its characters at its proportions (the coarsest level's skeleton,
// which every level shares), skinned at the level asked for; the baked time is the shot's.
TEST(ShotEvaluator, EachPairOfACrowdIsBakedPosedAndSkinnedAsItsOwn) {
  const SceneSpec scene = crowdOfFour();
  ShotEvaluator eval(scene, resolveProfile(scene), 2);
  ASSERT_EQ(eval.pairCount(), 4);
  EXPECT_EQ(eval.levelCount(), kDetailLevels);
  EXPECT_EQ(eval.pairName(0), "pair00");
  EXPECT_EQ(eval.pairName(3), "pair03");
  ShotFrame out;
  FrameRequest request;
  request.frame = 13;
  request.level.fixed = 1;
  eval.evaluate(request, out);
  ASSERT_EQ(out.pairs.size(), 4u);
  const double t = 12.0 / 24.0;
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE("pair " + std::to_string(i));
    const rig::PairSpec& spec = scene.pairs[i];
    SceneSpec named = scene;
    named.profile = spec.profile;
    const rig::RigProfile profile = resolveProfile(named);
    const auto clip = rig::makePairClip(spec, scene.terrain, "test");
    const rig::BakedFrame b = rig::bakeFrame(*clip, profile, 13, t + spec.clip_offset_s);
    const PairFrame& p = out.pairs[i];
    EXPECT_EQ(p.baked.seconds, t);
    EXPECT_EQ(p.baked.horse.controls.value, b.horse.controls.value);
    EXPECT_EQ(p.baked.horse.travel_cm, b.horse.travel_cm);
    EXPECT_EQ(p.baked.rider.value, b.rider.value);
    rig::HorseParams hp = spec.horse();
    rig::RiderParams rp = spec.rider();
    hp.cell *= kDetailCellFactor[1];
    rp.cell *= kDetailCellFactor[1];
    const rig::Character horse = rig::buildHorse(hp), rider = rig::buildRider(rp, hp.mount);
    const rig::MountedPose pose = rig::poseMounted(horse, rider, b.horse, b.rider, profile);
    expectSameMatrices(p.pose.horse, pose.horse, "horse");
    expectSameMatrices(p.pose.rider, pose.rider, "rider");
    EXPECT_EQ(p.level, 1);
    std::vector<glm::vec3> positions, normals;
    rig::skinMesh(horse.mesh, horse.skeleton, pose.horse, positions, normals);
    EXPECT_EQ(p.horse_positions, positions);
    rig::skinMesh(rider.mesh, rider.skeleton, pose.rider, positions, normals);
    EXPECT_EQ(p.rider_positions, positions);
  }
  // No two riders move alike: their rider channels differ pair from pair.
  for (std::size_t i = 1; i < 4; ++i) EXPECT_NE(out.pairs[i].baked.rider.value, out.pairs[0].baked.rider.value);
}

// A scene's pair clips are made once, as it loads (each path's footfalls scanned, its limits checked), and
// a shot takes them; a copy of the scene set on other ground makes its own, on that ground.
TEST(ShotEvaluator, TakesThePairClipsTheSceneMadeUnlessItsGroundChanged) {
  for (const SceneSpec& scene : {crowdOfFour(), loadScene(STIRRUP_SOURCE_DIR "/scenes/ride_out.json")}) {
    SCOPED_TRACE(scene.name);
    ASSERT_EQ(scene.pair_clips.size(), scene.pairs.size());
    EXPECT_EQ(scene.pair_clips_terrain, scene.terrain);
    ShotEvaluator eval(scene, resolveProfile(scene), 2);
    for (int i = 0; i < eval.pairCount(); ++i) EXPECT_EQ(&eval.clip(i), scene.pair_clips[std::size_t(i)].get());
  }
  const SceneSpec hills = loadScene(STIRRUP_SOURCE_DIR "/scenes/ride_out.json");
  ASSERT_TRUE(hills.terrain && !hills.terrain->flat());
  SceneSpec flat = hills;
  flat.terrain.reset();
  ShotEvaluator on_flat(flat, resolveProfile(flat), 2);
  int differ = 0;
  for (int i = 0; i < on_flat.pairCount(); ++i) {
    SCOPED_TRACE("pair " + std::to_string(i));
    EXPECT_NE(&on_flat.clip(i), hills.pair_clips[std::size_t(i)].get());
    const auto own = rig::makePairClip(flat.pairs[std::size_t(i)], nullptr, "test");
    EXPECT_EQ(on_flat.clip(i).sample(2.0).controls.value, own->sample(2.0).controls.value);
    differ += on_flat.clip(i).sample(2.0).controls.value != hills.pair_clips[std::size_t(i)]->sample(2.0).controls.value;
  }
  EXPECT_EQ(differ, on_flat.pairCount());  // the hills move every horse
}

// A held pose shows the held frame's bake at every frame (its frame number the one asked for); a
// treadmill takes the travel out; the rigid rider has every channel at rest and is posed with the
// profile marked rigid; only_pair evaluates that pair and leaves the others as they were.
TEST(ShotEvaluator, ShowsTheFrameAsTheCameraDoes) {
  const SceneSpec scene = trot();
  const rig::RigProfile profile = resolveProfile(scene);
  ShotEvaluator eval(scene, profile, 1);
  ShotFrame held, five;
  FrameRequest request;
  request.frame = 5;
  eval.evaluate(request, five);
  request.frame = 20;
  request.shown.hold_frame = 5;
  eval.evaluate(request, held);
  EXPECT_EQ(held.pairs[0].baked.frame, 20);
  EXPECT_EQ(held.pairs[0].baked.seconds, five.pairs[0].baked.seconds);
  EXPECT_EQ(held.pairs[0].horse_positions, five.pairs[0].horse_positions);

  request = {};
  request.frame = 20;
  request.shown.treadmill = true;
  request.until = EvalStage::Bake;
  ShotFrame still;
  eval.evaluate(request, still);
  const std::unique_ptr<rig::Clip> clip = makeSceneClip(scene);
  ASSERT_GT(clip->sample(19 / 24.0).travel_cm, 100.0);  // the trot has travelled by frame 20
  EXPECT_EQ(still.pairs[0].baked.horse.travel_cm, 0.0);
  EXPECT_EQ(still.pairs[0].baked.horse.travel_z_cm, 0.0);
  EXPECT_TRUE(still.pairs[0].pose.horse.empty()) << "baked only";

  request = {};
  request.frame = 20;
  request.shown.rigid_rider = true;
  request.until = EvalStage::Pose;
  ShotFrame rigid;
  eval.evaluate(request, rigid);
  EXPECT_EQ(rigid.pairs[0].baked.rider.value, rig::RiderChannels{}.value);
  rig::RigProfile statue = profile;
  statue.rigid = true;
  const rig::BakedFrame b = rig::bakeFrame(*clip, profile, 20, 19 / 24.0);
  expectSameMatrices(rigid.pairs[0].pose.rider,
                     rig::poseMounted(eval.horse(0), eval.rider(0), b.horse, rig::RiderChannels{}, statue).rider, "rider");

  const SceneSpec crowd = crowdOfFour();
  ShotEvaluator four(crowd, resolveProfile(crowd), 2);
  ShotFrame out;
  request = {};
  request.frame = 3;
  request.level.fixed = kDetailLevels - 1;
  four.evaluate(request, out);
  const std::vector<glm::vec3> pair0 = out.pairs[0].horse_positions;
  request.frame = 15;
  request.only_pair = 2;
  four.evaluate(request, out);
  EXPECT_EQ(out.pairs[0].horse_positions, pair0) << "pair 0 left as it was";
  EXPECT_EQ(out.pairs[2].baked.frame, 15);
  EXPECT_EQ(out.pairs[0].baked.frame, 3);
}

// The same frame, bit for bit, on one thread and on two, with each pair's level chosen from a camera
// (the pairs nearer it finer) so the levels differ between pairs.
TEST(ShotEvaluator, TheSameFrameAtAnyThreadCount) {
  const SceneSpec scene = crowdOfFour();
  Camera camera;
  camera.projection = Camera::Projection::Perspective;
  camera.fov_deg = 30.0;
  camera.position = {600.0, 200.0, -900.0};
  camera.target = {600.0, 120.0, 0.0};
  std::vector<ShotFrame> frames(2);
  for (int threads : {1, 2}) {
    ShotEvaluator eval(scene, resolveProfile(scene), threads);
    FrameRequest request;
    request.frame = 10;
    request.level = {-1, &camera, scene.width, scene.height};
    eval.evaluate(request, frames[std::size_t(threads - 1)]);
  }
  std::vector<int> levels;
  for (std::size_t i = 0; i < 4; ++i) {
    const PairFrame &a = frames[0].pairs[i], &b = frames[1].pairs[i];
    EXPECT_EQ(a.level, b.level);
    levels.push_back(a.level);
    EXPECT_EQ(a.horse_positions, b.horse_positions) << "pair " << i;
    EXPECT_EQ(a.rider_positions, b.rider_positions) << "pair " << i;
    EXPECT_EQ(a.rider_normals, b.rider_normals) << "pair " << i;
  }
  EXPECT_NE(*std::min_element(levels.begin(), levels.end()), *std::max_element(levels.begin(), levels.end()))
      << "the camera should see the pairs at different levels";
}

// evaluateEach gives every request's frame as evaluate() does, to the bit, whatever the thread count:
// a single pair skinned whole and as positions of every third vertex, and a crowd at a fixed level
// (framing a view evaluates the whole shot this way).
TEST(ShotEvaluator, EachFrameOfABatchIsTheFrameAlone) {
  for (const SceneSpec& scene : {trot(), crowdOfFour()}) {
    const bool crowd = !scene.pairs.empty();
    std::vector<FrameRequest> requests;
    for (int frame : {1, 7, 19, 40}) {
      for (EvalStage until : {EvalStage::Points, EvalStage::Skin}) {
        FrameRequest r;
        r.frame = frame;
        r.until = until;
        r.point_stride = 3;
        r.level.fixed = crowd ? kDetailLevels - 1 : 0;
        r.shown.treadmill = frame == 19;
        requests.push_back(r);
      }
    }
    ShotEvaluator alone(scene, resolveProfile(scene), 1);
    std::vector<ShotFrame> expected(requests.size());
    for (std::size_t k = 0; k < requests.size(); ++k) alone.evaluate(requests[k], expected[k]);
    for (int threads : {1, 2}) {
      ShotEvaluator batch(scene, resolveProfile(scene), threads);
      std::vector<ShotFrame> got(requests.size());
      std::vector<int> calls(requests.size(), 0);
      batch.evaluateEach(requests, [&](std::size_t k, ShotFrame& f) {
        got[k] = f;
        ++calls[k];
      });
      for (std::size_t k = 0; k < requests.size(); ++k) {
        const std::string what = scene.name + " request " + std::to_string(k) + " threads " + std::to_string(threads);
        ASSERT_EQ(calls[k], 1) << what;
        ASSERT_EQ(got[k].pairs.size(), expected[k].pairs.size()) << what;
        for (std::size_t i = 0; i < got[k].pairs.size(); ++i) {
          const PairFrame &a = got[k].pairs[i], &b = expected[k].pairs[i];
          EXPECT_EQ(a.baked.horse.controls.value, b.baked.horse.controls.value) << what;
          EXPECT_EQ(a.baked.horse.travel_cm, b.baked.horse.travel_cm) << what;
          EXPECT_EQ(a.baked.rider.value, b.baked.rider.value) << what;
          EXPECT_EQ(a.level, b.level) << what;
          EXPECT_EQ(a.horse_positions, b.horse_positions) << what;
          EXPECT_EQ(a.rider_positions, b.rider_positions) << what;
          EXPECT_EQ(a.horse_normals, b.horse_normals) << what;
        }
      }
    }
    // Points are every third skinned vertex, without normals.
    const PairFrame &points = expected[0].pairs[0], &skin = expected[1].pairs[0];
    ASSERT_FALSE(points.horse_positions.empty());
    EXPECT_TRUE(points.horse_normals.empty());
    ASSERT_EQ(points.horse_positions.size(), (skin.horse_positions.size() + 2) / 3);
    for (std::size_t k = 0; k < points.horse_positions.size(); ++k)
      ASSERT_EQ(points.horse_positions[k], skin.horse_positions[3 * k]) << k;
  }
  // Levels must be fixed: a level picked by size on screen would build characters mid-batch.
  ShotEvaluator eval(crowdOfFour(), resolveProfile(crowdOfFour()), 1);
  FrameRequest by_size;
  by_size.level.fixed = -1;
  EXPECT_THROW(eval.evaluateEach({by_size}, [](std::size_t, ShotFrame&) {}), std::invalid_argument);
}

}  // namespace
}  // namespace stirrup::scene
