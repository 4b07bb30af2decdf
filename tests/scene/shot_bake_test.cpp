// A shot baked for another tool (scene/shot_bake.h): the frames sorted and each once, every pair named
// and posed at each, every camera keyed at each; a crowd's pairs each where their own clip puts them.
#include "scene/profile_resolver.h"
#include "scene/shot_bake.h"

#include <gtest/gtest.h>

#include "rig/motion/crowd.h"
#include "scene/scene.h"
#include "tests/render/crowd_of_four.h"

namespace stirrup::scene {
namespace {

TEST(ShotBake, EveryPairAndCameraAtEveryFrameOnce) {
  const SceneSpec scene = render::test::crowdOfFour();
  ShotEvaluator characters(scene, resolveProfile(scene), 2);
  const rig::BakedShot shot = bakeShot(characters, {5, 1, 5, 3});
  EXPECT_EQ(shot.name, "crowd4");
  EXPECT_EQ(shot.seconds, (std::vector<float>{0.0f, float(2 / 24.0), float(4 / 24.0)}));
  ASSERT_EQ(shot.pairs.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(shot.pairs[i].name, "pair0" + std::to_string(i));
    ASSERT_EQ(shot.pairs[i].poses.size(), 3u);
    ASSERT_NE(shot.pairs[i].horse, nullptr);
    EXPECT_EQ(shot.pairs[i].poses[0].horse.size(), shot.pairs[i].horse->skeleton.size());
    // The horse's root is near its own path (z = -300 or 300), at its own place along it.
    const auto clip = rig::makePairClip(scene.pairs[i], nullptr, "test");
    const rig::HorseFrame h = clip->sample(4 / 24.0 + scene.pairs[i].clip_offset_s);
    const glm::vec3 root(shot.pairs[i].poses[2].horse[std::size_t(shot.pairs[i].horse->role("root"))][3]);
    EXPECT_NEAR(root.z, h.travel_z_cm, 20.0) << i;
    EXPECT_NEAR(root.x, h.travel_cm, 150.0) << i;
  }
  ASSERT_EQ(shot.cameras.size(), scene.cameras.size());
  for (const rig::BakedCamera& c : shot.cameras) EXPECT_EQ(c.world.size(), 3u);
  EXPECT_TRUE(shot.ground_indices.empty()) << "flat ground";
}

}  // namespace
}  // namespace stirrup::scene
