// The rider kept on a horse keyed live in another tool (scene/live_rider.h). The horse is the default
// horse trotting in a file stirrup baked (tests/rig/io/baked_trot.h), read back as a user's keyed horse;
// the oracles are the path `stirrup bake` takes for a horse playing its own animation (KeyedHorseClip,
// bakeFrame, poseMounted) and what a rigid move of the whole horse must do to her (move her with it).
// The add-on's use of it through `stirrup live` is tested in tests/cli/blender_addon_test.cpp.
#include "rig/io/gltf_mapping.h"
#include "scene/live_rider.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/bake.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_skin_joints.h"
#include "rig/io/keyed_horse_clip.h"
#include "rig/mapping/mapping_skeleton.h"
#include "rig/pose.h"
#include "scene/ridden_pair.h"
#include "tests/input_error.h"
#include "tests/rig/io/baked_trot.h"

namespace stirrup::scene {
namespace {

using rig::test::bakedTrot;
using rig::test::kFps;
using rig::test::kFrames;

// The tool's frames 0..47 are the file's keys at F / fps (the bake keys its frame 1 at 0 s).
constexpr int kFirst = 0, kLast = kFrames - 1;

struct Trot {
  RiddenPair pair;
  LiveRiderSetup setup;
};
const Trot& trot() {
  static const Trot t = [] {
    Trot out;
    const rig::RigProfile profile;
    out.pair = resolveRiddenPair(bakedTrot().file.string(), "", "default", "", profile);
    out.setup.horse_file = bakedTrot().file;
    out.setup.horse = std::make_shared<const rig::Character>(out.pair.horse);
    out.setup.rider = std::make_shared<const rig::Character>(out.pair.rider);
    out.setup.profile = profile;
    out.setup.fps = kFps;
    out.setup.first_frame = kFirst;
    out.setup.last_frame = kLast;
    return out;
  }();
  return t;
}

double worstEntry(const std::vector<glm::dmat4>& a, const std::vector<glm::dmat4>& b) {
  double worst = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) worst = std::max(worst, std::abs(a[j][c][r] - b[j][c][r]));
  return worst;
}

// The horse's joints at the tool's frame as the file keys them: each joint's world times its inverse bind.
std::vector<glm::dmat4> fileDeformations(int frame) {
  const std::string file = bakedTrot().file.string();
  static const tinygltf::Model model = rig::readGltfFile(bakedTrot().file, file);
  static const rig::GltfAnimation animation = rig::GltfAnimation::together(model, file);
  const std::vector<glm::dmat4> worlds = animation.worlds(frame / kFps);
  const std::vector<glm::mat4> ibm = rig::gltfInverseBinds(model, file, 0);
  std::vector<glm::dmat4> out;
  for (std::size_t k = 0; k < model.skins[0].joints.size(); ++k)
    out.push_back(worlds[std::size_t(model.skins[0].joints[k])] * glm::dmat4(ibm[k]));
  return out;
}

// Before any frame comes in, the rider at a frame is the bake's: the horse's own animation through the
// keyed clip, the frame baked and posed, her skin matrices taken to the horse's file.
TEST(LiveRider, BeforeAnyEditSheIsWhereTheBakeOfTheHorsesOwnAnimationPutsHer) {
  const Trot& t = trot();
  LiveRider live(t.setup);
  EXPECT_EQ(live.firstFrame(), kFirst);
  EXPECT_EQ(live.lastFrame(), kLast);
  const rig::Character& horse = *t.setup.horse;
  const rig::Character& rider = *t.setup.rider;
  const rig::KeyedHorseClip clip(bakedTrot().file.string(), "", rig::keyedHorseMapping(horse), &horse);
  // Out in the horse's file's world: the bake's is in metres, its joints bound in centimetres.
  const std::string file = bakedTrot().file.string();
  const tinygltf::Model model = rig::readGltfFile(bakedTrot().file, file);
  const std::vector<std::string> names = rig::gltfJointNames(model, 0);
  const int root = int(std::find(names.begin(), names.end(), rig::keyedHorseMapping(horse).roles.at("root")) - names.begin());
  const double units = rig::gltfSkinUnits(model, file, 0, root, rig::GltfAnimation::together(model, file));
  EXPECT_DOUBLE_EQ(units, 0.01);
  const glm::dmat4 from_horse_rig = glm::inverse(rig::GltfSkinJoints(model, file, 0, rig::keyedHorseMapping(horse).to_rig, units).worldToRig());
  for (const int frame : {0, 11, 30, kLast}) {
    const rig::BakedFrame baked = rig::bakeFrame(clip, t.setup.profile, frame, frame / kFps);
    const rig::MountedPose pose = rig::poseMounted(horse, rider, baked.horse, baked.rider, t.setup.profile);
    std::vector<glm::dmat4> expected;
    for (std::size_t j = 0; j < rider.skeleton.size(); ++j)
      if (!rider.skeleton.joints[j].rig_point)
        expected.push_back(from_horse_rig * glm::dmat4(pose.rider[j]) * glm::dmat4(rider.skeleton.skinBind(int(j))) * rider.source.to_rig);
    const std::vector<glm::dmat4> got = live.rider(frame);
    ASSERT_EQ(got.size(), live.riderJoints().size());
    ASSERT_EQ(got.size(), expected.size());
    EXPECT_LT(worstEntry(got, expected), 1e-4) << "frame " << frame;
  }
}

// Every frame of the horse handed in as the file keys it changes nothing; the whole horse handed in moved
// 30 cm to one side and 20 cm ahead at every frame moves her by exactly that; one frame edited changes her
// at that frame and leaves a frame two seconds away alone.
TEST(LiveRider, SheMovesWithTheHorseHandedIn) {
  const Trot& t = trot();
  LiveRider live(t.setup);
  const std::vector<glm::dmat4> at20 = live.rider(20);
  for (int f = kFirst; f <= kLast; ++f) live.setHorse(f, fileDeformations(f));
  EXPECT_LT(worstEntry(live.rider(20), at20), 1e-5) << "the file's own pose handed in";

  // The bake's file is in metres: 0.3 and 0.2 are 30 and 20 cm, whatever its axes.
  const glm::dmat4 shift = glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, 0.0, 0.2));
  for (int f = kFirst; f <= kLast; ++f) {
    std::vector<glm::dmat4> moved = fileDeformations(f);
    for (glm::dmat4& d : moved) d = shift * d;
    live.setHorse(f, moved);
  }
  std::vector<glm::dmat4> expected = at20;
  for (glm::dmat4& d : expected) d = shift * d;
  EXPECT_LT(worstEntry(live.rider(20), expected), 1e-4);

  LiveRider edited(t.setup);
  const std::vector<glm::dmat4> at5 = edited.rider(5), at47 = edited.rider(kLast);
  std::vector<glm::dmat4> raised = fileDeformations(5);
  for (glm::dmat4& d : raised) d = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.1, 0.0)) * d;
  edited.setHorse(5, raised);
  EXPECT_GT(worstEntry(edited.rider(5), at5), 0.02) << "the horse 10 cm higher at frame 5 moves her there";
  EXPECT_LT(worstEntry(edited.rider(kLast), at47), 1e-6) << "frame 47 reads the horse a second around it, not frame 5";
}

// With her, the horse's tack as stirrup poses it under her: its five joints, each a deformation from its
// rest in the horse's file to where it is, as the rider's (H^-1 T H); a point at the rein joint's rest goes
// to her hand and one at a tread's rest to the place placeStirrups hangs it, at every frame asked for.
TEST(LiveRider, TheTackComesWithHerStirrupsAtHerFeetReinsInHerHands) {
  const Trot& t = trot();
  LiveRider live(t.setup);
  EXPECT_EQ(live.tackJoints(), (std::vector<std::string>{"saddle", "lStirrup", "rStirrup", "lRein", "rRein"}));
  const rig::Character& horse = *t.setup.horse;
  const rig::Character& rider = *t.setup.rider;
  const rig::KeyedHorseClip clip(bakedTrot().file.string(), "", rig::keyedHorseMapping(horse), &horse);
  const std::string file = bakedTrot().file.string();
  const tinygltf::Model model = rig::readGltfFile(bakedTrot().file, file);
  const glm::dmat4 from_horse_rig = glm::inverse(rig::GltfSkinJoints(model, file, 0, rig::keyedHorseMapping(horse).to_rig, 0.01).worldToRig());
  const glm::dmat4 to_rig = horse.source.to_rig;
  const auto inFile = [&](glm::vec3 rig) { return glm::dvec3(glm::inverse(to_rig) * glm::dvec4(rig, 1.0)); };
  double hands = 0.0, treads = 0.0;
  for (const int frame : {0, 17, kLast}) {
    std::vector<glm::dmat4> tack;
    live.rider(frame, &tack);
    ASSERT_EQ(tack.size(), 5u);
    const rig::BakedFrame baked = rig::bakeFrame(clip, t.setup.profile, frame, frame / kFps);
    const rig::MountedPose pose = rig::poseMounted(horse, rider, baked.horse, baked.rider, t.setup.profile);
    const auto moved = [&](int k, const char* role) { return glm::dvec3(tack[std::size_t(k)] * glm::dvec4(inFile(horse.skeleton.restPosition(horse.role(role))), 1.0)); };
    const auto world = [&](glm::vec3 rig) { return glm::dvec3(from_horse_rig * glm::dvec4(rig, 1.0)); };
    for (int side = 0; side < 2; ++side) {
      const char* rein = side == 0 ? "lRein" : "rRein";
      hands = std::max(hands, glm::length(moved(3 + side, rein) - world(glm::vec3(pose.rider[std::size_t(rider.role(side == 0 ? "lHand" : "rHand"))][3]))));
      // Where poseMounted hangs the tread (placeStirrups, from her foot channels after the posing limits;
      // the tread from her raw channels, rig::stirrupTarget, stands 0.18 mm off it in the trot).
      const glm::vec3 tread = pose.horse[std::size_t(horse.role(side == 0 ? "lStirrup" : "rStirrup"))][3];
      treads = std::max(treads, glm::length(moved(1 + side, side == 0 ? "lStirrup" : "rStirrup") - world(tread)));
    }
    EXPECT_LT(glm::length(moved(0, "saddle") - world(glm::vec3(pose.horse[std::size_t(horse.role("saddle"))][3]))), 1e-6);
  }
  EXPECT_LT(hands, 1e-6) << "file units (metres)";
  EXPECT_LT(treads, 1e-6) << "file units (metres)";
}

TEST(LiveRider, BadFramesAreOneLineErrors) {
  const Trot& t = trot();
  LiveRiderSetup none = t.setup;
  none.last_frame = none.first_frame - 1;
  EXPECT_EQ(stirrup::test::errorOf([&] { LiveRider bad(none); }), "live: frames 0 to -1: expected 1 to 14400 frames");
  LiveRider live(t.setup);
  const std::vector<glm::dmat4> horse = fileDeformations(3);
  EXPECT_EQ(stirrup::test::errorOf([&] { live.setHorse(kLast + 1, horse); }), "live: frame 48: expected a frame from 0 to 47");
  EXPECT_EQ(stirrup::test::errorOf([&] { live.setHorse(3, {horse.begin(), horse.end() - 1}); }),
            "live: frame 3: expected " + std::to_string(horse.size()) + " horse joints, got " + std::to_string(horse.size() - 1));
  EXPECT_EQ(live.horseJoints().size(), horse.size());
}

}  // namespace
}  // namespace stirrup::scene
