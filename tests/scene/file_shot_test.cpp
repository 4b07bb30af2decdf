// A glTF shot rendered as it is (scene/file_shot.h): the default pair's trot written by stirrup's
// own bake writer from poses posed here (tests/rig/io/baked_trot.h), read back as a shot. The oracle is
// those poses and the trot's own travel, not anything the file shot computes.
#include "scene/file_shot.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "rig/motion/procedural_gait.h"
#include "rig/skin.h"
#include "scene/shot_evaluator.h"
#include "tests/input_error.h"
#include "tests/rig/io/baked_trot.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;
using rig::test::bakedTrot;

TEST(FileShot, ABakeIsAShotOfItsFramesSeenThroughTheNamedViews) {
  EXPECT_TRUE(isGltfFile("a/b.GLB"));
  EXPECT_TRUE(isGltfFile("b.gltf"));
  EXPECT_FALSE(isGltfFile("scenes/trot.json"));
  const FileShot shot = loadFileShot(bakedTrot().file);
  EXPECT_EQ(shot.scene.frames, "1-" + std::to_string(rig::test::kFrames));
  EXPECT_DOUBLE_EQ(shot.scene.fps, rig::test::kFps);
  EXPECT_EQ(shot.scene.name, bakedTrot().file.stem().string());
  std::string views;
  for (const CameraSpec& c : shot.scene.cameras) views += c.name + (c.view == c.name ? " " : "? ");
  EXPECT_EQ(views, "side persp close turntable top ");
  ASSERT_EQ(shot.shot->pairs().size(), 1u);
}

// Every joint of both characters at every frame as the trot posed them (the bake stores float TRS keys:
// 1e-3 cm is far below a pixel and above the float rounding), and the skin the evaluator draws is the
// characters' own skinned by those joints.
TEST(FileShot, TheEvaluatorPosesEachFrameAsTheFileKeysIt) {
  const FileShot shot = loadFileShot(bakedTrot().file);
  ShotEvaluator eval(shot, rig::RigProfile{}, 2);
  ASSERT_EQ(eval.pairCount(), 1);
  double worst = 0.0;
  ShotFrame frame;
  for (int f = 1; f <= rig::test::kFrames; f += 7) {
    FrameRequest request;
    request.frame = f;
    eval.evaluate(request, frame);
    const rig::MountedPose& want = bakedTrot().poses[std::size_t(f - 1)];
    const rig::MountedPose& got = frame.pairs[0].pose;
    ASSERT_EQ(got.horse.size(), want.horse.size());
    ASSERT_EQ(got.rider.size(), want.rider.size());
    for (std::size_t j = 0; j < want.horse.size(); ++j) worst = std::max(worst, double(glm::length(glm::vec3(got.horse[j][3] - want.horse[j][3]))));
    for (std::size_t j = 0; j < want.rider.size(); ++j) worst = std::max(worst, double(glm::length(glm::vec3(got.rider[j][3] - want.rider[j][3]))));
    std::vector<glm::vec3> positions, normals;
    rig::skinMesh(eval.rider(0).mesh, eval.rider(0).skeleton, got.rider, positions, normals);
    EXPECT_EQ(positions, frame.pairs[0].rider_positions);
  }
  EXPECT_LT(worst, 1e-3) << "cm";
}

// The cameras follow the horse's travel: the trunk's fitted travel runs with the trot's own (a steady
// 360 cm/s along +X) within the stride's surge, a few centimetres, and the heading stays straight ahead.
TEST(FileShot, TheViewsFollowTheHorsesKeyedTravel) {
  const FileShot shot = loadFileShot(bakedTrot().file);
  const std::unique_ptr<rig::Clip> travel = fileShotTravel(shot, 0);
  const rig::ProceduralGait trot(rig::trotParams());
  double worst = 0.0, heading = 0.0;
  for (int f = 1; f <= rig::test::kFrames; ++f) {
    const double t = (f - 1) / rig::test::kFps;
    const rig::HorseFrame a = travel->sampleTravel(t), b = trot.sampleTravel(t);
    worst = std::max(worst, std::hypot(a.travel_cm - b.travel_cm, a.travel_z_cm - b.travel_z_cm));
    heading = std::max(heading, std::abs(a.heading_deg));
  }
  EXPECT_LT(worst, 5.0) << "cm from the trot's travel";
  EXPECT_LT(heading, 1.0) << "degrees";
}

TEST(FileShot, AFileThatIsNoShotIsAOneLineError) {
  const fs::path dir = fs::temp_directory_path() / "stirrup-file-shot-test";
  fs::create_directories(dir);
  EXPECT_EQ(test::errorOf([&] { loadFileShot(dir / "missing.glb"); }),
            (dir / "missing.glb").string() + ": no such file (expected a glTF file)");
  const fs::path text = dir / "text.glb";
  std::ofstream(text) << "not glTF";
  EXPECT_NE(test::errorOf([&] { loadFileShot(text); }).find(text.string() + ": "), std::string::npos);
}

// A scene gives the shot its look (cameras, size, quality) and nothing of what moves.
TEST(FileShot, ASceneGivesItsLookNotItsMotion) {
  const FileShot shot = loadFileShot(bakedTrot().file, 24.0, STIRRUP_SOURCE_DIR "/scenes/jump.json");
  const SceneSpec jump = loadScene(STIRRUP_SOURCE_DIR "/scenes/jump.json");
  EXPECT_EQ(shot.scene.name, jump.name);
  EXPECT_EQ(shot.scene.cameras.size(), jump.cameras.size());
  EXPECT_EQ(shot.scene.width, jump.width);
  EXPECT_EQ(shot.scene.frames, "1-" + std::to_string(rig::test::kFrames));
  EXPECT_EQ(shot.scene.horse, "default");
  EXPECT_EQ(shot.scene.clip.generator, SceneSpec{}.clip.generator);
}

}  // namespace
}  // namespace stirrup::scene
