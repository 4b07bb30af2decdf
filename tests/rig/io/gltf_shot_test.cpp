// A baked shot read back (rig/io/gltf_shot.cpp) from shots baked here, by the same writer `stirrup bake`
// uses (rig/io/gltf_bake.h): the default pair at the generated trot, posed by rig::poseMounted, is the
// oracle. Read back, every joint of both characters stands where the rig posed it, the hooves the clip
// plants are down and those it lifts are not, and rig::PairCheck measures the same frame the same way;
// a shot's own ground comes back.
// A crowd's pairs come back by their names; a file that is no shot is left to the clip reader. The
// command (`stirrup check SHOT.glb`, Blender's re-export) is tests/cli/check_test.cpp.
#include "rig/io/atomic_file.h"
#include "rig/io/gltf_shot.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "rig/bake.h"
#include "rig/frame_check.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_clip.h"
#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "tests/input_error.h"
#include "tests/rig/default_characters.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
using test::defaultHorse;
using test::defaultRider;

fs::path tempDir(const std::string& name) { return stirrup::test::freshTestDir("test_gltf_shot", name); }

constexpr int kFrames = 24;
constexpr double kFps = 24.0;

// The default pair at the generated trot, frames 1..kFrames, as the shot's evaluator poses it; in a
// crowd pair k rides 300 cm to the right of the one before (a place the file must keep).
struct Trot {
  std::unique_ptr<Clip> clip = scene::makeClip(scene::ClipSpec{});
  RigProfile profile = RigProfile::thesis();
  std::vector<BakedFrame> frames;
  std::vector<MountedPose> poses;
  Trot() {
    for (int f = 1; f <= kFrames; ++f) {
      frames.push_back(bakeFrame(*clip, profile, f, (f - 1) / kFps));
      poses.push_back(poseMounted(defaultHorse(), defaultRider(), frames.back().horse, frames.back().rider, profile));
    }
  }
};

const Trot& trot() {
  static const Trot t;
  return t;
}

MountedPose shifted(MountedPose p, double z_cm) {
  const glm::mat4 by = glm::translate(glm::mat4(1.0f), {0.0f, 0.0f, float(z_cm)});
  for (glm::mat4& m : p.horse) m = by * m;
  for (glm::mat4& m : p.rider) m = by * m;
  return p;
}

fs::path writeShot(const fs::path& file, const std::vector<std::string>& pair_names) {
  BakedShot shot;
  shot.name = "trot";
  shot.fps = kFps;
  for (int f = 0; f < kFrames; ++f) shot.seconds.push_back(float(f / kFps));
  for (std::size_t k = 0; k < pair_names.size(); ++k) {
    BakedPair pair;
    pair.name = pair_names[k];
    pair.horse = &defaultHorse();
    pair.rider = &defaultRider();
    for (const MountedPose& p : trot().poses) pair.poses.push_back(shifted(p, 300.0 * double(k)));
    shot.pairs.push_back(pair);
  }
  writeFileAtomically(file, bakedShotGlb(shot));
  return file;
}

double worstDistance(const std::vector<glm::mat4>& a, const std::vector<glm::mat4>& b) {
  double worst = 0;
  for (std::size_t j = 0; j < a.size(); ++j) worst = std::max(worst, double(glm::length(glm::vec3(a[j][3]) - glm::vec3(b[j][3]))));
  return worst;
}

const auto kFlat = [](double, double) { return 0.0; };
constexpr std::array<const char*, 4> kHooves = {"lfHoof", "rfHoof", "lbHoof", "rbHoof"};
constexpr std::array<HorseChannel, 4> kLift = {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy, HorseChannel::lbHoofTy,
                                               HorseChannel::rbHoofTy};

TEST(GltfShot, ABakeReadBackStandsEveryJointWhereTheRigPosedIt) {
  const fs::path file = writeShot(tempDir("trot") / "trot.glb", {""});
  const std::unique_ptr<GltfShot> shot = GltfShot::read(file);
  ASSERT_TRUE(shot);
  ASSERT_EQ(shot->pairs().size(), 1u);
  EXPECT_EQ(shot->pairs()[0].name, "");
  EXPECT_EQ(shot->pairs()[0].horse_armature, "horse");
  EXPECT_EQ(shot->pairs()[0].rider_armature, "rider");
  EXPECT_EQ(shot->frameCount(), kFrames);
  EXPECT_EQ(shot->fps(), kFps);
  EXPECT_EQ(shot->animationName(), "trot");
  const GltfShot::Pair& read = shot->pairs()[0];
  ASSERT_EQ(read.horse.skeleton.size(), defaultHorse().skeleton.size());
  ASSERT_EQ(read.rider.skeleton.size(), defaultRider().skeleton.size());
  // The same triangles (the tack's parts written apart repeat their seams' vertices).
  ASSERT_EQ(read.horse.mesh.triangleCount(), defaultHorse().mesh.triangleCount());
  ASSERT_GE(read.horse.mesh.vertexCount(), defaultHorse().mesh.vertexCount());

  const PairCheck oracle(defaultHorse(), defaultRider(), trot().profile.balance);
  const PairCheck checker(read.horse, read.rider, trot().profile.balance);
  EXPECT_EQ(checker.unmeasured(), oracle.unmeasured());
  double worst_joint = 0, worst_depth = 0, deepest = 0;
  int planted = 0, rolling = 0;
  for (int f = 1; f <= kFrames; ++f) {
    const MountedPose& want = trot().poses[std::size_t(f - 1)];
    const MountedPose got = shot->pose(0, f);
    worst_joint = std::max({worst_joint, worstDistance(got.horse, want.horse), worstDistance(got.rider, want.rider)});
    const FrameMeasures a = oracle.measure(f, 0, trot().frames[std::size_t(f - 1)].horse, want, kFlat);
    const FrameMeasures b = checker.measure(f, 0, HorseFrame{}, got, kFlat);
    // Down by the one contact test (the sole on the ground), the same in both: every hoof the clip plants
    // is down, those rolling over the toe at the end of a stance too (the hoof joint raised past the
    // contact band, the toe still on the ground); a hoof the clip lifts a centimetre or more never is.
    for (std::size_t leg = 0; leg < 4; ++leg) {
      EXPECT_EQ(a.down[leg], b.down[leg]) << "frame " << f << " leg " << leg;
      const double ty = trot().frames[std::size_t(f - 1)].horse.controls[kLift[leg]];
      const int hoof = defaultHorse().role(kHooves[leg]);
      const double raised = want.horse[std::size_t(hoof)][3].y - defaultHorse().skeleton.restPosition(hoof).y;
      if (ty >= 1.0) {
        EXPECT_FALSE(b.down[leg]) << "frame " << f << " leg " << leg << " lifted " << ty;
      }
      if (ty == 0.0) {
        EXPECT_TRUE(b.down[leg]) << "frame " << f << " leg " << leg << " planted, its joint raised " << raised;
        ++planted, rolling += raised > kHoofContactCm;
      }
    }
    worst_depth = std::max(worst_depth, double(std::abs(a.rider_depth_cm - b.rider_depth_cm)));
    deepest = std::max(deepest, double(b.rider_depth_cm));
    for (std::size_t side = 0; side < 2; ++side) {
      EXPECT_NEAR(a.hand_off_cm[side], b.hand_off_cm[side], 0.01) << "frame " << f;
      EXPECT_NEAR(a.foot_off_cm[side], b.foot_off_cm[side], 0.01) << "frame " << f;
    }
    EXPECT_NEAR(a.trunk_lean_deg, b.trunk_lean_deg, 0.01) << "frame " << f;
    for (std::size_t leg = 0; leg < 4; ++leg) EXPECT_NEAR(a.below_ground_cm[leg], b.below_ground_cm[leg], 0.01) << "frame " << f;
  }
  EXPECT_LT(worst_joint, 0.01);  // cm: float keys in metres
  EXPECT_LT(worst_depth, 0.01);
  EXPECT_GT(rolling, 0);  // the trot's landings roll over the toe: the case is exercised
  EXPECT_EQ(shot->ground(), nullptr);  // baked on flat ground: no ground mesh
  std::printf("a bake read back: joints within %.5f cm, rider depth within %.5f cm (deepest %.2f cm); of %d planted hoof-frames %d "
              "roll over the toe, all down\n", worst_joint, worst_depth, deepest, planted, rolling);
}

// A crowd's pairs by their names, each where its ride is (pair01 300 cm to the right of pair00's).
TEST(GltfShot, ACrowdsPairsComeBackByTheirNames) {
  const fs::path file = writeShot(tempDir("crowd") / "crowd.glb", {"pair00", "pair01"});
  const std::unique_ptr<GltfShot> shot = GltfShot::read(file);
  ASSERT_TRUE(shot);
  ASSERT_EQ(shot->pairs().size(), 2u);
  EXPECT_EQ(shot->pairs()[1].name, "pair01");
  EXPECT_EQ(shot->pairs()[1].index, 1);
  EXPECT_EQ(shot->pairs()[1].horse_armature, "pair01_horse");
  const MountedPose want = shifted(trot().poses[5], 300.0);
  const MountedPose got = shot->pose(1, 6);
  EXPECT_LT(worstDistance(got.horse, want.horse), 0.01);
  EXPECT_LT(worstDistance(got.rider, want.rider), 0.01);
}

// The shot's own ground: a bake over a terrain writes it (node "ground"), and it comes back in stirrup's
// world, heights where the writer put them; a node another tool names "Ground.001" is ground too, one
// named "groundhog" is not. A hoof is down over the ground it stands on and not over one 10 cm lower.
TEST(GltfShot, ItsOwnGroundComesBackAndTheHoovesAreDownOnIt) {
  const fs::path dir = tempDir("ground");
  BakedShot shot;
  shot.name = "trot";
  shot.fps = kFps;
  for (int f = 0; f < 2; ++f) shot.seconds.push_back(float(f / kFps));
  BakedPair pair;
  pair.horse = &defaultHorse();
  pair.rider = &defaultRider();
  pair.poses = {trot().poses[0], trot().poses[1]};
  shot.pairs.push_back(pair);
  // A slope 10 cm up a metre across z, under the horse from x = -500 to 500 cm.
  shot.ground_vertices = {{-500, -50, -500}, {500, -50, -500}, {500, 50, 500}, {-500, 50, 500}};
  shot.ground_indices = {0, 2, 1, 0, 3, 2};
  const fs::path file = dir / "sloped.glb";
  writeFileAtomically(file, bakedShotGlb(shot));
  const std::unique_ptr<GltfShot> read = GltfShot::read(file);
  ASSERT_TRUE(read);
  ASSERT_TRUE(read->ground());
  EXPECT_EQ(read->ground()->triangleCount(), 2u);
  for (const glm::dvec2 at : {glm::dvec2(0, 0), glm::dvec2(120, -300), glm::dvec2(-400, 250)}) {
    const auto hit = read->ground()->at(at.x, at.y);
    ASSERT_TRUE(hit) << at.x << ", " << at.y;
    EXPECT_NEAR(hit->height_cm, 0.1 * at.y, 1e-3) << at.x << ", " << at.y;
  }

  // Another tool's names: "Ground.001" is the ground, "groundhog" a prop.
  tinygltf::Model model = stirrup::test::readGlbModel(file);
  for (tinygltf::Node& n : model.nodes)
    if (n.name == "ground") n.name = "Ground.001";
  stirrup::test::writeGlbModel(model, dir / "renamed.glb");
  const std::unique_ptr<GltfShot> renamed = GltfShot::read(dir / "renamed.glb");
  ASSERT_TRUE(renamed && renamed->ground());
  EXPECT_EQ(renamed->ground()->triangleCount(), 2u);
  for (tinygltf::Node& n : model.nodes)
    if (n.name == "Ground.001" || n.name == "ground_mesh") n.name = n.name == "ground_mesh" ? "groundhog_mesh" : "groundhog";
  stirrup::test::writeGlbModel(model, dir / "prop.glb");
  const std::unique_ptr<GltfShot> prop = GltfShot::read(dir / "prop.glb");
  ASSERT_TRUE(prop);
  EXPECT_EQ(prop->ground(), nullptr);

  // The trot's first frame keyed on flat ground: down there, never over a ground 10 cm lower.
  const std::unique_ptr<GltfShot> flat = GltfShot::read(writeShot(dir / "trot.glb", {""}));
  const PairCheck checker(flat->pairs()[0].horse, flat->pairs()[0].rider, trot().profile.balance);
  const MountedPose pose = flat->pose(0, 1);
  const FrameMeasures on = checker.measure(1, 0, HorseFrame{}, pose, kFlat);
  const FrameMeasures above = checker.measure(1, 0, HorseFrame{}, pose, [](double, double) { return -10.0; });
  EXPECT_EQ(std::count(above.down.begin(), above.down.end(), true), 0);
  EXPECT_GT(std::count(on.down.begin(), on.down.end(), true), 0);
}

// The hooves the clip slides on purpose (a sliding stop's hinds) are recorded by the bake on the horse's
// armature and come back at their frames, so the file's check does not count them as the scene's does not.
TEST(GltfShot, TheHoovesSlidOnPurposeComeBackAtTheirFrames) {
  BakedShot shot;
  shot.name = "stop";
  shot.fps = kFps;
  BakedPair pair;
  pair.name = "pair00";
  pair.horse = &defaultHorse();
  pair.rider = &defaultRider();
  for (int f = 0; f < 6; ++f) {
    shot.seconds.push_back(float(f / kFps));
    pair.poses.push_back(trot().poses[std::size_t(f)]);
    pair.hoof_sliding.push_back({false, false, f >= 2, f >= 3});  // lb from frame 3, rb from frame 4
  }
  shot.pairs.push_back(pair);
  const fs::path file = tempDir("sliding") / "stop.glb";
  writeFileAtomically(file, bakedShotGlb(shot));
  const std::unique_ptr<GltfShot> read = GltfShot::read(file);
  ASSERT_TRUE(read);
  for (int f = 1; f <= 6; ++f) {
    const std::array<bool, 4> want = {false, false, f >= 3, f >= 4};
    EXPECT_EQ(read->hoofSliding(0, f), want) << "frame " << f;
  }
  // Without the record (another tool's file, or a bake of a clip that slides nothing): none.
  const std::unique_ptr<GltfShot> plain = GltfShot::read(writeShot(tempDir("sliding") / "trot.glb", {""}));
  EXPECT_EQ(plain->hoofSliding(0, 2), (std::array<bool, 4>{}));
}

// A tool's world that is not stirrup's (the Blender add-on's: the user's horse facing where it does) is
// named by the scene's extras "stirrup_world", a mapping from it to stirrup's: the bake moved into a world
// turned a quarter about +Y and 2 m, 3 m off, with the mapping back, stands every joint where the rig
// posed it. A mapping that is no frame (up along forward, a scale of 0) is a one-line error naming it.
TEST(GltfShot, AWorldNamedInTheScenesExtrasIsTakenToStirrups) {
  const fs::path dir = tempDir("world");
  tinygltf::Model model = stirrup::test::readGlbModel(writeShot(dir / "trot.glb", {""}));
  tinygltf::Node world;
  world.name = "tool_world";
  world.rotation = {0.0, std::sin(std::numbers::pi / 4.0), 0.0, std::cos(std::numbers::pi / 4.0)};  // +X to -Z
  world.translation = {2.0, 0.0, 3.0};
  tinygltf::Scene& scene = model.scenes[std::size_t(std::max(0, model.defaultScene))];
  world.children = scene.nodes;
  model.nodes.push_back(world);
  scene.nodes = {int(model.nodes.size()) - 1};
  const auto vec = [](double x, double y, double z) { return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(x), tinygltf::Value(y), tinygltf::Value(z)}); };
  const auto withWorld = [&](tinygltf::Value::Object mapping, const std::string& name) {
    tinygltf::Value::Object extras = scene.extras.IsObject() ? scene.extras.Get<tinygltf::Value::Object>() : tinygltf::Value::Object{};
    extras["stirrup_world"] = tinygltf::Value(mapping);
    scene.extras = tinygltf::Value(extras);
    stirrup::test::writeGlbModel(model, dir / name);
    return dir / name;
  };
  // Stirrup's cm = 100 R^T (p - t): forward, up and their cross product are R's columns.
  const fs::path turned = withWorld({{"scale_cm", tinygltf::Value(100.0)}, {"forward", vec(0, 0, -1)}, {"up", vec(0, 1, 0)},
                                     {"offset_cm", vec(300, 0, -200)}},
                                    "turned.glb");
  const std::unique_ptr<GltfShot> shot = GltfShot::read(turned);
  ASSERT_TRUE(shot);
  for (const int f : {1, 12}) {
    const MountedPose got = shot->pose(0, f);
    const MountedPose& want = trot().poses[std::size_t(f - 1)];
    EXPECT_LT(worstDistance(got.horse, want.horse), 0.01) << "frame " << f;
    EXPECT_LT(worstDistance(got.rider, want.rider), 0.01) << "frame " << f;
  }
  const fs::path flat = withWorld({{"scale_cm", tinygltf::Value(100.0)}, {"forward", vec(0, 1, 0)}, {"up", vec(0, 1, 0)},
                                   {"offset_cm", vec(0, 0, 0)}},
                                  "flat.glb");
  EXPECT_EQ(stirrup::test::errorOf([&] { GltfShot::read(flat); }),
            flat.string() + ": scenes[0].extras.stirrup_world.up: expected a direction across forward");
  const fs::path unscaled = withWorld({{"scale_cm", tinygltf::Value(0.0)}}, "unscaled.glb");
  EXPECT_EQ(stirrup::test::errorOf([&] { GltfShot::read(unscaled); }),
            unscaled.string() + ": scenes[0].extras.stirrup_world.scale_cm: expected centimetres a unit from 0.001 to 100000");
}

// A horse clip (one animated skeleton, no skin) is not a shot: the clip reader takes it.
TEST(GltfShot, AClipIsNoShot) {
  const fs::path file = tempDir("clip") / "clip.glb";
  writeClipGltf(*scene::makeClip(scene::ClipSpec{}), file);
  EXPECT_EQ(GltfShot::read(file), nullptr);
}

}  // namespace
}  // namespace stirrup::rig
