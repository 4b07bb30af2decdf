// Golden images. Two small frames of a fixed trot side camera (tests/golden/trot_side.json, the
// scene the sensitivity tests perturb), and the golden set of the shipped scenes: every movement in
// every view at its telling frames (tests/golden/scenes.json), rendered by the program and compared
// with the references checked in under tests/golden/. Rendering is deterministic (per-pixel random
// sequences, fixed BVH quality), so on the machine that made the references the difference is 0;
// the tolerance (tests/render/cli/golden_support.h: no more than 0.01% of pixels off by more than 4/255)
// leaves room for another CPU's floating-point paths without letting a moved limb or camera through
// (tests/render/cli/golden_sensitivity_test.cpp proves it). On failure an HTML report with the reference,
// the new image, the diff and the numbers is written next to the new image.
// Update the references after an intended change with scripts/update-goldens.
#include <filesystem>
#include <iostream>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "render/review/image_diff.h"
#include "tests/render/cli/golden_support.h"
#include "tests/render/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

class Golden : public ::testing::TestWithParam<int> {};

TEST_P(Golden, TrotSideMatchesTheReference) {
  const int frame = GetParam();
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "golden_out" / ("frame" + std::to_string(frame));
  fs::remove_all(out);
  const CommandResult r = runStirrup("render " + quote((kGoldenDir / "trot_side.json").string()) +
                                     " --frames " + std::to_string(frame) + " --out " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string name = goldenName(frame);
  const fs::path reference = kGoldenDir / name;
  if (updatingGoldens()) {
    std::cout << "[ update ] " << replaceGolden(reference, out / name) << std::endl;
    return;
  }
  ASSERT_TRUE(fs::exists(reference)) << reference << " is missing: run scripts/update-goldens";
  const GoldenComparison c = compareWithGolden(reference, out / name);
  EXPECT_FALSE(c.failed()) << c.message();
}

INSTANTIATE_TEST_SUITE_P(Frames, Golden, ::testing::ValuesIn(kGoldenFrames));

class SceneGolden : public ::testing::TestWithParam<GoldenShot> {};

// One shot of the set: scenes/SCENE.json through CAMERA, its telling frames at the set's resolution
// and preset, each compared with its reference. The scene is the shipped one, so a change to a
// default scene, clip, character, rig profile or view framing shows here as well as a change to the
// renderer.
TEST_P(SceneGolden, MatchesTheReference) {
  const GoldenShot& shot = GetParam();
  const GoldenSet set = loadGoldenSet();
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "golden_out" / shot.name();
  fs::remove_all(out);
  std::string frames;
  for (int f : shot.frames) {
    if (!frames.empty()) frames += ',';
    frames += std::to_string(f);
  }
  const fs::path scene = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / (shot.scene + ".json");
  const CommandResult r = runStirrup("render " + quote(scene.string()) + " --camera " + quote(shot.camera) +
                                     " --frames " + frames + " --resolution " + set.resolution + " --preset " +
                                     set.preset + " --out " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int frame : shot.frames) {
    const std::string name = frameFileName(shot.name(), frame);
    const fs::path reference = kSceneGoldenDir / name;
    ASSERT_TRUE(fs::exists(out / name)) << out / name << " was not rendered";
    if (updatingGoldens()) {
      std::cout << "[ update ] " << replaceGolden(reference, out / name) << std::endl;
      continue;
    }
    ASSERT_TRUE(fs::exists(reference)) << reference << " is missing: run scripts/update-goldens";
    const GoldenComparison c = compareWithGolden(reference, out / name);
    EXPECT_FALSE(c.failed()) << shot.why << "\n" << c.message();
  }
}

INSTANTIATE_TEST_SUITE_P(Shots, SceneGolden, ::testing::ValuesIn(loadGoldenSet().shots),
                         [](const ::testing::TestParamInfo<GoldenShot>& info) { return info.param.name(); });

class MovieGolden : public ::testing::TestWithParam<GoldenMovie> {};

// A review movie as `stirrup movies` makes it, at the set's resolution and preset with a fixed slate
// date: the burnt-in frames, the slate and the plot, compared file by file.
TEST_P(MovieGolden, MatchesTheReference) {
  const GoldenMovie& movie = GetParam();
  const GoldenSet set = loadGoldenSet();
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "golden_out" / ("movie_" + movie.movie);
  fs::remove_all(out);
  const CommandResult r = runStirrup("movies --only " + quote(movie.movie) + " --frames-limit " +
                                     std::to_string(movie.frames_limit) + " --resolution " + set.resolution +
                                     " --preset " + set.preset + " --date " + quote(movie.date) +
                                     " --keep-frames --out " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& file : movie.files) {
    const fs::path image = out / file;
    const fs::path reference = kMovieGoldenDir / image.filename();
    ASSERT_TRUE(fs::exists(image)) << image << " was not written";
    if (updatingGoldens()) {
      std::cout << "[ update ] movies/" << replaceGolden(reference, image) << std::endl;
      continue;
    }
    ASSERT_TRUE(fs::exists(reference)) << reference << " is missing: run scripts/update-goldens";
    const GoldenComparison c = compareWithGolden(reference, image);
    EXPECT_FALSE(c.failed()) << movie.why << "\n" << c.message();
  }
}

INSTANTIATE_TEST_SUITE_P(Movies, MovieGolden, ::testing::ValuesIn(loadGoldenSet().movies),
                         [](const ::testing::TestParamInfo<GoldenMovie>& info) { return info.param.movie; });

// Every shipped scene and every view of the review movies is in the set, so a new movement or view
// cannot go unguarded.
TEST(SceneGoldenSet, CoversEveryMovementAndView) {
  const GoldenSet set = loadGoldenSet();
  std::set<std::string> scenes, views;
  for (const GoldenShot& s : set.shots) {
    scenes.insert(s.scene);
    views.insert(s.camera);
  }
  for (const char* scene : {"walk", "trot", "canter", "gallop", "stop", "jump", "rear", "buck"})
    EXPECT_TRUE(scenes.count(scene)) << scene << " has no golden shot";
  for (const char* view : {"side", "persp", "close", "turntable", "turntable_pose"})
    EXPECT_TRUE(views.count(view)) << view << " has no golden shot";
  for (const char* crowd : {"cavalry", "ride_out"})  // issue 19's crowds
    EXPECT_TRUE(scenes.count(crowd)) << crowd << " has no golden shot";
  bool layered = false;
  for (const GoldenMovie& m : set.movies) layered = layered || m.movie.find("_layered") != std::string::npos;
  EXPECT_TRUE(layered) << "no layered movie in the golden set";
  EXPECT_EQ(set.resolution, "320x180");
}

// A fresh folder holding a copy of the checked-in golden `name`, as if just rendered there.
fs::path copyGoldenInto(const std::string& folder, const std::string& name) {
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "golden_out" / folder;
  fs::remove_all(out);
  fs::create_directories(out);
  fs::copy_file(kGoldenDir / name, out / name);
  return out / name;
}

TEST(GoldenDiff, ADifferentImageFailsWithAReport) {
  // The comparison itself must be able to fail: the two golden frames differ from each other. The
  // failure writes the report next to the new image, with the three images beside it.
  const fs::path image = copyGoldenInto("different", "trot_side.0009.png");
  const fs::path out = image.parent_path();
  const GoldenComparison c = compareWithGolden(kGoldenDir / "trot_side.0004.png", image);
  ASSERT_TRUE(c.failed()) << c.diff.summary();
  EXPECT_EQ(c.report, out / "trot_side.0009.report.html");
  EXPECT_NE(c.message().find(c.report.string()), std::string::npos) << c.message();
  const std::string report = readText(c.report);
  for (const char* file : {"trot_side.0009.reference.png", "trot_side.0009.png", "trot_side.0009.png.diff.png"}) {
    EXPECT_NE(report.find(std::string("src=\"") + file + "\""), std::string::npos) << file << " not linked";
    EXPECT_TRUE(fs::exists(out / file)) << file << " not next to the report";
  }
  EXPECT_NE(report.find("PSNR"), std::string::npos);
  EXPECT_NE(report.find(std::to_string(c.diff.pixels_over_fail)), std::string::npos);
}

TEST(GoldenDiff, AMatchWritesNoReport) {
  const fs::path image = copyGoldenInto("same", "trot_side.0004.png");
  const fs::path out = image.parent_path();
  const GoldenComparison c = compareWithGolden(kGoldenDir / "trot_side.0004.png", image);
  EXPECT_FALSE(c.failed()) << c.message();
  EXPECT_EQ(c.diff.max_error, 0.0);
  EXPECT_TRUE(c.report.empty());
  EXPECT_FALSE(fs::exists(out / "trot_side.0004.report.html"));
}

}  // namespace
}  // namespace stirrup::test
