// Golden images. Two small frames of a fixed trot side camera (tests/golden/trot_side.json, the
// scene the sensitivity tests perturb), and the golden set of the shipped scenes: every movement in
// every view at its telling frames (tests/golden/scenes.json), rendered by the program and compared
// with the references checked in under tests/golden/. Rendering is deterministic (per-pixel random
// sequences, fixed BVH quality), so on the machine that made the references the difference is 0;
// the tolerance (tests/cli/golden_support.h: no more than 0.01% of pixels off by more than 4/255)
// leaves room for another CPU's floating-point paths without letting a moved limb or camera through
// (tests/cli/golden_sensitivity_test.cpp proves it). On failure an HTML report with the reference,
// the new image, the diff and the numbers is written next to the new image.
// The tests only compare; the references are updated after an intended change by a separate command,
// scripts/update-goldens (update_goldens.cpp), which refuses to run in CI.
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "render/review/image_diff.h"
#include "tests/cli/golden_support.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// Renders `r` and compares every file it names with its reference. Only compares: the references are
// updated by the separate update_goldens command (scripts/update-goldens), never by a test.
void renderAndCompare(const GoldenRender& r) {
  fs::remove_all(r.out);
  const CommandResult run = runStirrup(r.args);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const GoldenRender::File& f : r.files) {
    const fs::path reference = kGoldenDir / f.reference;
    ASSERT_TRUE(fs::exists(f.image)) << f.image << " was not written";
    ASSERT_TRUE(fs::exists(reference)) << reference << " is missing: run scripts/update-goldens";
    const GoldenComparison c = compareWithGolden(reference, f.image);
    EXPECT_FALSE(c.failed()) << r.why << "\n" << c.message();
  }
}

class Golden : public ::testing::TestWithParam<int> {};

TEST_P(Golden, TrotSideMatchesTheReference) { renderAndCompare(fixedTrotRender(GetParam())); }

INSTANTIATE_TEST_SUITE_P(Frames, Golden, ::testing::ValuesIn(kGoldenFrames));

class SceneGolden : public ::testing::TestWithParam<GoldenShot> {};

// One shot of the set: scenes/SCENE.json through CAMERA, its telling frames at the set's resolution
// and preset, each compared with its reference. The scene is the shipped one, so a change to a
// default scene, clip, character, rig profile or view framing shows here as well as a change to the
// renderer.
TEST_P(SceneGolden, MatchesTheReference) { renderAndCompare(shotRender(loadGoldenSet(), GetParam())); }

INSTANTIATE_TEST_SUITE_P(Shots, SceneGolden, ::testing::ValuesIn(loadGoldenSet().shots),
                         [](const ::testing::TestParamInfo<GoldenShot>& info) { return info.param.name(); });

class MovieGolden : public ::testing::TestWithParam<GoldenMovie> {};

// A review movie as `stirrup movies` makes it, at the set's resolution and preset with a fixed slate
// date: the burnt-in frames, the slate and the plot, compared file by file.
TEST_P(MovieGolden, MatchesTheReference) { renderAndCompare(movieRender(loadGoldenSet(), GetParam())); }

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

// Every file under `dir`, relative, with its bytes.
std::map<std::string, std::string> filesUnder(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = readText(e.path());
  return files;
}

// The update is a separate command (update_goldens, run by scripts/update-goldens), and it refuses
// to run in CI: a one-line refusal, nothing rendered, not a byte of tests/golden changed.
TEST(GoldenUpdate, RefusesToRunInCI) {
  const std::map<std::string, std::string> before = filesUnder(kGoldenDir);
  for (const char* ci : {"true", "1", "TRUE"}) {
    const CommandResult r = runCommand(std::string("CI=") + ci + " " + quote(STIRRUP_UPDATE_GOLDENS_EXE) + " --only fixed:4");
    EXPECT_EQ(r.exit_code, 2) << ci;
    EXPECT_EQ(r.err.rfind(std::string("update-goldens: refused: CI=") + ci + ": golden references are updated by hand", 0), 0u) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.out, "");
  }
  EXPECT_TRUE(filesUnder(kGoldenDir) == before) << "tests/golden changed";
}

// Outside CI it renders what the golden tests render and writes the references where it is told
// (here a scratch folder laid out as tests/golden/): rendering is deterministic, so the fixed trot's
// frame 4 comes out pixel for pixel as checked in (the file's bytes are the PNG writer's: the
// references checked in before the writer moved to libdeflate hold the same pixels in other bytes),
// and it says so.
TEST(GoldenUpdate, WritesTheReferencesItIsAskedForAndSaysHowFarEachMoved) {
  const fs::path into = fs::path(STIRRUP_BINARY_DIR) / "golden_update_test";
  fs::remove_all(into);
  const std::string exe = "env -u CI " + quote(STIRRUP_UPDATE_GOLDENS_EXE);
  const CommandResult r = runCommand(exe + " --only fixed:4 --into " + quote(into.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "trot_side.0004.png: new\n");  // new to that folder
  const render::DiffResult d =
      render::compareImageFiles(kGoldenDir / "trot_side.0004.png", into / "trot_side.0004.png", goldenThresholds());
  EXPECT_EQ(d.width, 320);
  EXPECT_EQ(d.max_error, 0.0) << d.summary();
  const CommandResult again = runCommand(exe + " --only fixed:4 --into " + quote(into.string()));
  EXPECT_EQ(again.out, "trot_side.0004.png: unchanged\n");
  const CommandResult bad = runCommand(exe + " --only fixed:5");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "update-goldens: --only: no golden render \"fixed:5\" (expected fixed:FRAME, shot:SCENE_CAMERA or movie:NAME)\n");
  fs::remove_all(into);
}

}  // namespace
}  // namespace stirrup::test
