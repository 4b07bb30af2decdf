// A horse playing its own keyed animation (rig/io/keyed_horse_clip.h). The horse here is the default
// horse in a baked trot written by stirrup's own bake (rig/io/gltf_bake.h), read back as a user's file
// would be: the file's joints at every frame are the oracle (the trot's own poses), not anything the clip
// computes. Blender's Rigify horse keyed in Blender is tested end to end in tests/cli/keyed_horse_test.cpp.
#include "rig/io/keyed_horse_clip.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <tuple>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/bake.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/motion/procedural_gait.h"
#include "rig/pose.h"
#include "rig/rider_rig.h"
#include "tests/input_error.h"
#include "tests/rig/io/baked_trot.h"
#include "tests/rig/default_characters.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
using test::bakedTrot;
using test::kFps;
using test::kFrames;

struct LoadedHorse {
  Character horse;
  std::unique_ptr<KeyedHorseClip> clip;
};
const LoadedHorse& ownHorse() {
  static const LoadedHorse h = [] {
    LoadedHorse l;
    l.horse = loadCharacterGltf(bakedTrot().file, CharacterKind::Horse);
    l.clip = std::make_unique<KeyedHorseClip>(bakedTrot().file, "", keyedHorseMapping(l.horse), &l.horse);
    return l;
  }();
  return h;
}

TEST(KeyedHorseClip, TheHorsesOwnTrotTravelsAndKeysTheHorse) {
  const KeyedHorseClip& clip = *ownHorse().clip;
  EXPECT_FALSE(clip.inPlace());
  EXPECT_TRUE(clip.keysTheHorse());
  EXPECT_NEAR(clip.trunkSpeedCmS(), trotParams().speed_cm_s, 0.05 * trotParams().speed_cm_s);
  EXPECT_NEAR(clip.duration(), (kFrames - 1) / kFps, 1e-4);
}

// Every joint of the horse, posed from the clip, where the file keys it (the trot's own pose), at every
// frame: the file holds the horse's world joints, and stirrup plays them as they are.
TEST(KeyedHorseClip, EveryJointWhereTheFileKeysItAtEveryFrame) {
  const LoadedHorse& own = ownHorse();
  const Character& horse = own.horse;
  ASSERT_EQ(horse.skeleton.size(), test::defaultHorse().skeleton.size());
  double worst = 0.0;
  for (int f = 0; f < kFrames; ++f) {
    const HorseFrame frame = own.clip->sample(f / kFps);
    ASSERT_TRUE(frame.keyed_pose);
    const std::vector<glm::mat4> world = poseHorse(horse, frame);
    const std::vector<glm::mat4>& baked = bakedTrot().poses[std::size_t(f)].horse;
    // The bake writes the joints in the skeleton's order and the loader keeps it (parents come first).
    for (std::size_t j = 0; j < world.size(); ++j) {
      const double d = glm::length(glm::vec3(world[j][3]) - glm::vec3(baked[j][3]));
      if (d > 0.01) ADD_FAILURE() << horse.skeleton.joints[j].name << " frame " << f + 1 << ": " << d << " cm";
      worst = std::max(worst, d);
    }
  }
  EXPECT_LT(worst, 0.01) << "cm, the worst joint over the trot";
}

// The controls measured from the keyed joints, in the travel frame fitted to the trunk, are the trot's
// own: a steady trot's travel is a straight line at its speed, so each hoof's lift and reach, the body's
// bounce and pitch come back as the posed horse had them (the hooves where its legs put them: where a
// landing hoof fell short of its target, where it was, not the target).
TEST(KeyedHorseClip, ControlsMeasuredFromTheJointsAreTheGaitsOwn) {
  using H = HorseChannel;
  const Character& horse = test::defaultHorse();
  double lift = 0, reach = 0, bounce = 0, pitch = 0;
  for (int f = 6; f < kFrames - 6; ++f) {  // a half-second from each end, where the fit's window is whole
    const HorseFrame keyed = ownHorse().clip->sample(f / kFps);
    const HorseFrame& made = bakedTrot().frames[std::size_t(f)];
    const std::vector<glm::mat4>& posed = bakedTrot().poses[std::size_t(f)].horse;
    for (const auto& [role, tx, ty] : {std::tuple{"lfHoof", H::lfHoofTx, H::lfHoofTy}, std::tuple{"rbHoof", H::rbHoofTx, H::rbHoofTy}}) {
      // The posed hoof in the generator's travel frame (along +X at its speed), from its rest.
      const glm::vec3 p = glm::vec3(posed[std::size_t(horse.role(role))][3]) - horse.skeleton.restPosition(horse.role(role));
      lift = std::max(lift, std::abs(keyed.controls[ty] - std::max(0.0, double(p.y))));
      reach = std::max(reach, std::abs(keyed.controls[tx] - (p.x - made.travel_cm)));
    }
    bounce = std::max(bounce, std::abs(keyed.controls[H::rearPivotTy] - made.controls[H::rearPivotTy]));
    pitch = std::max(pitch, std::abs(keyed.controls[H::rearPivotRz] - made.controls[H::rearPivotRz]));
    EXPECT_NEAR(keyed.heading_deg, 0.0, 0.5);
  }
  EXPECT_LT(lift, 0.5) << "cm";
  EXPECT_LT(reach, 1.0) << "cm";
  EXPECT_LT(bounce, 0.5) << "cm";
  EXPECT_LT(pitch, 0.2) << "degrees";
  std::printf("keyed trot against the posed trot: hooves %.2f cm in height, %.2f cm along; pivot %.2f cm, %.3f degrees\n", lift,
              reach, bounce, pitch);
}

// Read without the horse (another horse's animation on the scene's horse), the frames carry the controls
// alone and the horse is posed from them.
TEST(KeyedHorseClip, AnotherHorsesAnimationCarriesControlsOnly) {
  const KeyedHorseClip clip(bakedTrot().file, "", keyedHorseMapping(ownHorse().horse), nullptr);
  EXPECT_FALSE(clip.keysTheHorse());
  EXPECT_FALSE(clip.sample(0.5).keyed_pose);
  EXPECT_NEAR(clip.sample(0.5).controls[HorseChannel::lfHoofTy], ownHorse().clip->sample(0.5).controls[HorseChannel::lfHoofTy], 1e-9);
}

TEST(KeyedHorseClip, ErrorsNameTheFileAndTheRole) {
  KeyedHorseMapping m = keyedHorseMapping(ownHorse().horse);
  m.where = "my-horse-map.json";
  m.roles.erase("neck1");
  EXPECT_EQ(stirrup::test::errorOf([&] { KeyedHorseClip(bakedTrot().file, "", m, nullptr); }),
            "my-horse-map.json: roles.neck1: missing (expected the horse's neck1 joint to read its animation)");
  m = keyedHorseMapping(ownHorse().horse);
  m.where = "my-horse-map.json";
  m.roles["lfHoof"] = "LeftFrontHoof";
  EXPECT_EQ(stirrup::test::errorOf([&] { KeyedHorseClip(bakedTrot().file, "", m, nullptr); }),
            "my-horse-map.json: roles.lfHoof: no joint named \"LeftFrontHoof\" in " + bakedTrot().file.string());
  EXPECT_EQ(stirrup::test::errorOf([&] { KeyedHorseClip(bakedTrot().file, "Walk", keyedHorseMapping(ownHorse().horse), nullptr); }),
            bakedTrot().file.string() + ": no animation named \"Walk\" (the file has \"trot\")");
}

}  // namespace
}  // namespace stirrup::rig
