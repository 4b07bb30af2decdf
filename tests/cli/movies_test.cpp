// stirrup movies end to end, small: a few movies at 96x54, 3 frames each, draft quality. Checks the
// movies with ffprobe, the index's links, and the index in a real headless Chromium.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

CommandResult runStirrupHere(const std::string& args) { return runCommand(quote(STIRRUP_EXE) + " " + args); }

std::string probe(const fs::path& movie) {
  return runCommand("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                    "stream=codec_name,pix_fmt,nb_read_frames,r_frame_rate -of csv=p=0 " +
                    quote(movie.string()))
      .out;
}

// Every decoded frame's checksum (ffmpeg's framemd5 without its header): the pixels a viewer sees.
std::string decodedFrames(const fs::path& movie) {
  return runCommand("ffmpeg -v error -i " + quote(movie.string()) + " -f framemd5 - | grep -v '^#'").out;
}

class MoviesCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // CTest runs every test in its own process, two at a time: each process renders into its own folder.
    dir_ = fs::path(STIRRUP_BINARY_DIR) / ("test_movies_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    result_ = new CommandResult(runStirrupHere(
        "movies --only trot_side,walk_layered,turntable_pose --frames-limit 3 --preset draft --resolution 96x54 "
        "--mov prores --date 2026-01-01 --out " + quote(dir_.string())));
  }
  static void TearDownTestSuite() {
    delete result_;
    if (!::testing::UnitTest::GetInstance()->Failed()) fs::remove_all(dir_);  // kept for a look on failure
  }
  static fs::path dir_;
  static CommandResult* result_;
};
fs::path MoviesCommand::dir_;
CommandResult* MoviesCommand::result_ = nullptr;

TEST_F(MoviesCommand, WritesMoviesWithTheRightFramesRateAndCodec) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  EXPECT_EQ(result_->out, (dir_ / "index.html").string() + "\n");
  EXPECT_EQ(result_->err, "");  // quiet when stderr is not a terminal
  // 24 fps scenes: a one-second slate (24 frames) and 3 rendered frames.
  for (const char* name : {"trot_side", "walk_layered", "turntable_pose"}) {
    EXPECT_EQ(probe(dir_ / (std::string(name) + ".mp4")), "h264,yuv420p,24/1,27\n") << name;
    EXPECT_EQ(probe(dir_ / (std::string(name) + ".mov")), "prores,yuv422p10le,24/1,27\n") << name;
    EXPECT_TRUE(fs::exists(dir_ / (std::string(name) + "_sheet.png"))) << name;
  }
  EXPECT_TRUE(fs::exists(dir_ / "trot_plot.png"));
  EXPECT_TRUE(fs::exists(dir_ / "walk_plot.png"));
  EXPECT_FALSE(fs::exists(dir_ / "frames"));  // frames are not kept without --keep-frames
}

TEST_F(MoviesCommand, LayeredMovieIsTwoPanelsWide) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  const std::string size = runCommand("ffprobe -v error -select_streams v:0 -show_entries stream=width,height "
                                      "-of csv=p=0 " + quote((dir_ / "walk_layered.mp4").string())).out;
  const std::string single = runCommand("ffprobe -v error -select_streams v:0 -show_entries stream=width,height "
                                        "-of csv=p=0 " + quote((dir_ / "trot_side.mp4").string())).out;
  EXPECT_EQ(single, "96,54\n");
  int w = 0, h = 0;
  ASSERT_EQ(std::sscanf(size.c_str(), "%d,%d", &w, &h), 2) << size;
  EXPECT_GE(w, 2 * 96);
  EXPECT_EQ(h, 54);
}

TEST_F(MoviesCommand, IndexLinksOnlyExistingFilesAndShowsEveryMovie) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  const std::string html = readText(dir_ / "index.html");
  const std::regex link("(?:src|href)=\"([^\"]+)\"");
  int links = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it, ++links)
    EXPECT_TRUE(fs::is_regular_file(dir_ / (*it)[1].str())) << (*it)[1].str();
  EXPECT_GE(links, 3 * 5);
  for (const char* name : {"trot_side", "walk_layered", "turntable_pose"})
    EXPECT_NE(html.find("<video controls preload=\"auto\" muted playsinline src=\"" + std::string(name) + ".mp4\""),
              std::string::npos)
        << name;
}

// Loads index.html in Debian's Chromium, headless, lets the page load the movies and dumps the DOM:
// every <video> must report its metadata (duration, size) through the page's data attributes.
TEST_F(MoviesCommand, HeadlessChromiumLoadsEveryVideo) {
  ASSERT_EQ(result_->exit_code, 0) << result_->err;
  if (runCommand("command -v chromium").exit_code != 0) GTEST_SKIP() << "chromium is not installed (scripts/setup)";
  const fs::path profile = dir_ / "chromium-profile";
  fs::remove_all(profile);
  const CommandResult r = runCommand(
      "timeout 60 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --mute-audio "
      "--allow-file-access-from-files --autoplay-policy=no-user-gesture-required --virtual-time-budget=8000 "
      "--user-data-dir=" + quote(profile.string()) + " --dump-dom " +
      quote("file://" + fs::absolute(dir_ / "index.html").string()));
  fs::remove_all(profile);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::regex video("<video[^>]*>");
  int videos = 0;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), video); it != std::sregex_iterator(); ++it) {
    const std::string tag = it->str();
    ++videos;
    EXPECT_EQ(tag.find("data-error"), std::string::npos) << "the browser could not play: " << tag;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(tag, m, std::regex("data-duration=\"([0-9.]+)\""))) << tag;
    // 27 frames at 24 fps.
    EXPECT_NEAR(std::stod(m[1].str()), 27.0 / 24.0, 0.05) << tag;
    EXPECT_NE(tag.find("data-height=\"54\""), std::string::npos) << tag;
  }
  EXPECT_EQ(videos, 3);
}

TEST(MoviesErrors, UnknownMovieAndPresetAreOneLineErrors) {
  CommandResult r = runStirrupHere("movies --only trot_sidee --out /tmp/never");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--only: no movie named \"trot_sidee\""), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  r = runStirrupHere("movies --preset fast --out /tmp/never");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--preset"), std::string::npos) << r.err;
  r = runStirrupHere("movies --mov avi --out /tmp/never");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--mov: expected prores or h264"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists("/tmp/never"));
}

TEST(MoviesList, ListsTheThesisSetAndMore) {
  const CommandResult r = runStirrupHere("movies --list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"jump_side", "jump_persp", "rear_side", "rear_persp", "stop_side", "stop_persp",
                           "stop_close", "stop_layered", "trot_side", "trot_persp", "trot_close", "trot_layered",
                           "walk_side", "walk_persp", "walk_close", "walk_layered", "buck_side", "buck_persp",
                           "canter_side", "gallop_side", "turntable_pose", "turntable_trot", "cross_country_persp",
                           "figure_eight_persp", "figure_eight_top", "trail_persp"})
    EXPECT_NE(r.out.find(std::string(name) + "\t"), std::string::npos) << name;
  const bool plate = fs::exists(fs::path(STIRRUP_SHARED_DIR) / "reference/muybridge/horse-and-rider-gallop-plate.jpg");
  EXPECT_EQ(r.out.find("gallop_layered\t") != std::string::npos, plate);
}

// The two stages a farm runs apart (render/review/movie_set.h): --frames renders a share of one movie's
// frames, --finish makes the movie from them. Together they make what one `stirrup movies` makes.
TEST(MoviesStages, FramesThenFinishMakeTheSameMovieAsOneRun) {
  const fs::path one = fs::path(STIRRUP_BINARY_DIR) / ("test_movies_one_" + std::to_string(::getpid()));
  const fs::path two = fs::path(STIRRUP_BINARY_DIR) / ("test_movies_two_" + std::to_string(::getpid()));
  const std::string set = "--only trot_side --frames-limit 5 --preset draft --resolution 96x54 --date 2026-01-01 --keep-frames";
  ASSERT_EQ(runStirrupHere("movies " + set + " --out " + quote(one.string())).exit_code, 0);
  CommandResult r = runStirrupHere("movies " + set + " --frames 4-5 --out " + quote(two.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");  // a share of frames, no movie yet
  EXPECT_FALSE(fs::exists(two / "trot_side.mp4"));
  // Finishing before every frame is there names the first missing one and encodes nothing.
  r = runStirrupHere("movies " + set + " --finish --out " + quote(two.string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "stirrup: trot_side: frame 1 is missing (" + (two / "frames/trot_side/trot_side.0001.png").string() + ")\n");
  EXPECT_FALSE(fs::exists(two / "trot_side.mp4"));
  // --resume renders only what is missing (frames 1-3), then the movie is made as one run makes it.
  const auto written = fs::last_write_time(two / "frames/trot_side/trot_side.0004.png");
  ASSERT_EQ(runStirrupHere("movies " + set + " --frames 1-5 --resume --out " + quote(two.string())).exit_code, 0);
  EXPECT_EQ(fs::last_write_time(two / "frames/trot_side/trot_side.0004.png"), written);
  r = runStirrupHere("movies " + set + " --finish --out " + quote(two.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, (two / "index.html").string() + "\n");
  for (const char* file : {"trot_side_sheet.png", "trot_plot.png", "frames/trot_side/trot_side.0001.png",
                           "frames/trot_side/trot_side.0005.png", "frames/trot_side/trot_side.slate.png"})
    EXPECT_TRUE(readText(one / file) == readText(two / file)) << file;
  EXPECT_EQ(probe(two / "trot_side.mp4"), probe(one / "trot_side.mp4"));
  // One run pipes its frames to the encoder from memory; the farm's stages encode the PNGs: the same
  // pixels (every decoded frame's checksum).
  const std::string from_memory = decodedFrames(one / "trot_side.mp4");
  EXPECT_EQ(std::count(from_memory.begin(), from_memory.end(), '\n'), 24 + 5);  // the slate and the frames
  EXPECT_EQ(from_memory, decodedFrames(two / "trot_side.mp4"));
  EXPECT_FALSE(fs::exists(two / "frames/trot_side/trot_side.0001.sheet.exr"));  // kept frames are the PNGs
  fs::remove_all(one);
  fs::remove_all(two);
}

// --timings writes a row a movie, in the set's order, whose seconds add up to no more than the run.
TEST(MoviesTimings, ARowAMovieWithItsFramesAndSeconds) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / ("test_movies_timings_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path tsv = dir / "times.tsv";
  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = runStirrupHere("movies --only trot_side,walk_side --frames-limit 2 --preset draft "
                                         "--resolution 96x54 --date 2026-01-01 --timings " + quote(tsv.string()) +
                                         " --out " + quote((dir / "out").string()));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = readText(tsv);
  ASSERT_EQ(lineCount(text), 3u) << text;
  EXPECT_EQ(text.substr(0, text.find('\n')), "movie\tframes\trender_s\tfinish_s\trender_s_per_frame\tencode_cpu_s");
  const std::regex row("(\\w+)\t(\\d+)\t([0-9.]+)\t([0-9.]+)\t([0-9.]+)");
  double total = 0.0;
  std::vector<std::string> names;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), row); it != std::sregex_iterator(); ++it) {
    names.push_back((*it)[1].str());
    EXPECT_EQ((*it)[2].str(), "2");
    const double render_s = std::stod((*it)[3].str()), finish_s = std::stod((*it)[4].str());
    EXPECT_GT(render_s, 0.0);
    EXPECT_GT(finish_s, 0.0);
    EXPECT_NEAR(std::stod((*it)[5].str()), render_s / 2.0, 1e-3);
    total += render_s + finish_s;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"trot_side", "walk_side"}));
  EXPECT_LE(total, wall);
  EXPECT_FALSE(fs::exists(tsv.string() + ".partial"));
  // A folder that is not there is a one-line error, before any frame is rendered.
  const CommandResult bad = runStirrupHere("movies --only trot_side --frames-limit 1 --preset draft --resolution 96x54 "
                                           "--timings " + quote((dir / "nowhere/t.tsv").string()) + " --out " +
                                           quote((dir / "out2").string()));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.err, "stirrup: --timings: " + (dir / "nowhere/t.tsv").string() + ": cannot write (does its folder exist?)\n");
  EXPECT_FALSE(fs::exists(dir / "out2" / "trot_side.mp4"));  // refused before rendering anything
  fs::remove_all(dir);
}

TEST(MoviesStages, MisusedStageOptionsAreOneLineErrors) {
  CommandResult r = runStirrupHere("movies --only trot_side,jump_side --frames 1-2 --out /tmp/never");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "stirrup: --frames: expected exactly one movie with --only NAME, got 2\n");
  r = runStirrupHere("movies --only trot_side --frames 1-2 --finish --out /tmp/never");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  r = runStirrupHere("movies --only trot_side --frames-limit 4 --frames 9 --out /tmp/never_frames");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "stirrup: trot_side: frame 9 is not one of the movie's frames (1-4)\n");
  EXPECT_FALSE(fs::exists("/tmp/never"));
  fs::remove_all("/tmp/never_frames");
}

}  // namespace
}  // namespace stirrup::test
