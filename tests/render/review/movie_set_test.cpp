// The movie set (render/review/movie_set.cpp): the default set, each movie's frames, the files its two
// stages write, and stage 1 on a tiny render. The encoded movies themselves are tested end to end by
// tests/cli/movies_test.cpp (they need ffmpeg).
#include "render/review/movie_set.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/input_error.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

const fs::path kScenes = fs::path(STIRRUP_SOURCE_DIR) / "scenes";

MovieJob trotSide(const std::string& frames = "") { return {"trot_side", kScenes / "trot.json", "side", frames, "", {}}; }

class MovieSetFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("stirrup_movie_set_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    o_.out = dir_ / "movies";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  MovieOptions o_;
};

// The list in defaultMovieSet, counted by hand: jump 2, rear 2, stop 4, trot 4, walk 4, buck 2, canter 1,
// gallop 1, turntables 2, paths 4, crowds 4 = 30; Muybridge's plate adds gallop_layered.
TEST_F(MovieSetFiles, TheDefaultSetAddsTheLayeredGallopOnlyWithThePlate) {
  const std::vector<MovieJob> without = defaultMovieSet(kScenes, dir_ / "reference");
  EXPECT_EQ(without.size(), 30u);
  EXPECT_EQ(without.front().name, "jump_side");
  EXPECT_EQ(without.front().scene, kScenes / "jump.json");
  for (const MovieJob& j : without) EXPECT_NE(j.name, "gallop_layered");
  fs::create_directories(dir_ / "reference" / "muybridge");
  std::ofstream(dir_ / "reference" / "muybridge" / "horse-and-rider-gallop-plate.jpg") << "x";
  const std::vector<MovieJob> with = defaultMovieSet(kScenes, dir_ / "reference");
  ASSERT_EQ(with.size(), 31u);
  EXPECT_EQ(with.back().name, "gallop_layered");
  EXPECT_EQ(with.back().layered, "reference");
  EXPECT_EQ(with.back().camera, "side");
}

TEST_F(MovieSetFiles, AMoviesFramesAreTheJobsOrTheScenesCutToTheLimit) {
  EXPECT_EQ(movieFrameList(trotSide("1-10x3"), o_), (std::vector<int>{1, 4, 7, 10}));
  EXPECT_EQ(movieFrameCount(trotSide(), o_), 72);  // scenes/trot.json: "frames": "1-72"
  o_.frames_limit = 3;
  EXPECT_EQ(movieFrameList(trotSide("1-10x3"), o_), (std::vector<int>{1, 4, 7}));
  EXPECT_EQ(movieFrameList(trotSide(), o_), (std::vector<int>{1, 2, 3}));
}

TEST_F(MovieSetFiles, EachStageWritesNamedFiles) {
  EXPECT_EQ(movieFrameDir(trotSide(), o_), o_.out / "frames" / "trot_side");
  EXPECT_EQ(movieOutputs(trotSide(), o_), (std::vector<fs::path>{o_.out / "trot_side.mp4", o_.out / "trot_side_sheet.png"}));
  o_.mov = true;
  o_.mp4 = false;
  EXPECT_EQ(movieOutputs(trotSide(), o_), (std::vector<fs::path>{o_.out / "trot_side.mov", o_.out / "trot_side_sheet.png"}));
  // Frames 1-9 and a 3-frame contact sheet: positions round(i * 8 / 2) = 0, 4, 8, so frames 1, 5 and 9
  // carry the sheet's EXR beside their PNG.
  o_.contact_count = 3;
  const fs::path frames = o_.out / "frames" / "trot_side";
  EXPECT_EQ(movieFrameFiles(trotSide("1-9"), o_, 5),
            (std::vector<fs::path>{frames / "trot_side.0005.png", frames / "trot_side.0005.sheet.exr"}));
  EXPECT_EQ(movieFrameFiles(trotSide("1-9"), o_, 2), (std::vector<fs::path>{frames / "trot_side.0002.png"}));
  EXPECT_EQ(movieFrameFiles(trotSide("1-9"), o_, 9).back(), frames / "trot_side.0009.sheet.exr");
}

// Stage 1 on a 32x18 draft: every frame's PNG, the sheet frame's EXR, nothing else; resume skips them
// all; stage 2 names the first frame that is gone.
TEST_F(MovieSetFiles, StageOneWritesEachFrameOnceAndStageTwoNeedsThemAll) {
  o_.preset = "draft";
  o_.width = 32;
  o_.height = 18;
  o_.contact_count = 1;  // the first frame only
  o_.date = "2026-11-26";
  const MovieJob job = trotSide("1-2");
  EXPECT_EQ(errorOf([&] { renderMovieFrames(job, o_, {3}, false); }),
            "trot_side: frame 3 is not one of the movie's frames (1-2)");
  int done = 0;
  EXPECT_EQ(renderMovieFrames(job, o_, {}, false, [&] { ++done; }), 2);
  EXPECT_EQ(done, 2);
  std::vector<std::string> written;
  for (const auto& e : fs::directory_iterator(movieFrameDir(job, o_))) written.push_back(e.path().filename().string());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{"trot_side.0001.png", "trot_side.0001.sheet.exr", "trot_side.0002.png"}));
  EXPECT_EQ(renderMovieFrames(job, o_, {}, true), 0);
  fs::remove(movieFrameDir(job, o_) / "trot_side.0002.png");
  EXPECT_EQ(renderMovieFrames(job, o_, {}, true), 1);  // only the missing one
  fs::remove(movieFrameDir(job, o_) / "trot_side.0002.png");
  EXPECT_EQ(errorOf([&] { finishMovie(job, o_); }),
            "trot_side: frame 2 is missing (" + (movieFrameDir(job, o_) / "trot_side.0002.png").string() + ")");
}

// A glTF shot's set (shotMovieSet) reads the file first: one that is not a shot is the file shot reader's
// one-line error naming it. The views a shot cannot make are refused with their names; its own are not.
TEST_F(MovieSetFiles, AShotsSetRefusesAFileThatIsNoShotAndNamesTheViewsItCannotMake) {
  const fs::path junk = dir_ / "notgltf.glb";
  std::ofstream(junk) << "nothing";
  const std::string error = errorOf([&] { shotMovieSet(junk); });
  EXPECT_EQ(error.rfind(junk.string() + ": ", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  for (const char* view : {"layered", "follow", "turntable_pose"}) {
    const std::string why = shotViewRefusal(view);
    EXPECT_EQ(why.rfind(std::string("the ") + view + " view cannot be made from a glTF shot: ", 0), 0u) << why;
  }
  for (const char* view : {"side", "persp", "close", "turntable", "top"}) EXPECT_EQ(shotViewRefusal(view), "") << view;
}

TEST(MovieSet, TheSharedFolderIsTheVariableElseBesideTheSource) {
  std::optional<std::string> saved;
  if (const char* v = std::getenv("STIRRUP_SHARED_DIR")) saved = v;
  ::setenv("STIRRUP_SHARED_DIR", "/data/stirrup-shared", 1);
  EXPECT_EQ(sharedDir("/src/stirrup"), fs::path("/data/stirrup-shared"));
  ::unsetenv("STIRRUP_SHARED_DIR");
  EXPECT_EQ(sharedDir("/src/stirrup"), fs::path("/src/shared"));
  if (saved) ::setenv("STIRRUP_SHARED_DIR", saved->c_str(), 1);
}

}  // namespace
}  // namespace stirrup::render
