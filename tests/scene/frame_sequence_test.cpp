#include "scene/frame_sequence.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;

std::string errorOf(const fs::path& pattern) {
  return stirrup::test::errorOf([&] { FrameSequence::parse(pattern); }, "");
}

// printf's %0*d: zero-padded to the padding, never cut, the sign taking one place.
TEST(FrameSequence, FrameNumbersArePaddedNeverCut) {
  EXPECT_EQ(paddedFrameNumber(7), "0007");
  EXPECT_EQ(paddedFrameNumber(0), "0000");
  EXPECT_EQ(paddedFrameNumber(9999), "9999");
  EXPECT_EQ(paddedFrameNumber(12345), "12345");  // overflows ####: wider, not cut to 2345
  EXPECT_EQ(paddedFrameNumber(-3), "-003");       // as `stirrup render --frames -3` always wrote it
  EXPECT_EQ(paddedFrameNumber(-12345), "-12345");
  EXPECT_EQ(paddedFrameNumber(7, 6), "000007");
  EXPECT_EQ(paddedFrameNumber(7, 1), "7");
  EXPECT_EQ(paddedFrameNumber(7, 0), "7");
}

TEST(FrameSequence, HashesAreTheDigits) {
  const std::optional<FrameSequence> s = FrameSequence::parse("out/trot_side.####.png");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->folder(), fs::path("out"));
  EXPECT_EQ(s->padding(), 4);
  EXPECT_EQ(s->fileName(12), "trot_side.0012.png");
  EXPECT_EQ(s->path(12), fs::path("out/trot_side.0012.png"));
  EXPECT_EQ(s->fileName(12345), "trot_side.12345.png");
  EXPECT_EQ(s->pattern(), "out/trot_side.####.png");
  const std::optional<FrameSequence> six = FrameSequence::parse("f######.exr");
  ASSERT_TRUE(six);
  EXPECT_EQ(six->padding(), 6);
  EXPECT_EQ(six->path(42), fs::path("f000042.exr"));
  EXPECT_EQ(six->folder(), fs::path(""));
}

TEST(FrameSequence, PrintfPatternsAsFfmpegWritesThem) {
  const std::optional<FrameSequence> s = FrameSequence::parse("plates/take.%04d.jpg");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->padding(), 4);
  EXPECT_EQ(s->path(3), fs::path("plates/take.0003.jpg"));
  EXPECT_EQ(s->pattern(), "plates/take.####.jpg");
  const std::optional<FrameSequence> bare = FrameSequence::parse("f.%d.png");
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->padding(), 0);
  EXPECT_EQ(bare->fileName(7), "f.7.png");
  EXPECT_EQ(bare->fileName(1234), "f.1234.png");
  EXPECT_EQ(bare->pattern(), "f.%d.png");
}

TEST(FrameSequence, OneImageIsNoSequence) {
  EXPECT_FALSE(FrameSequence::parse("still.png"));
  EXPECT_FALSE(FrameSequence::isPattern("still.png"));
  EXPECT_FALSE(FrameSequence::parse("take#2/still.png"));   // only the file name is read
  EXPECT_FALSE(FrameSequence::parse("50%d/still.png"));
  EXPECT_FALSE(FrameSequence::parse("rate.50%.png"));       // a % that is no %d
  EXPECT_FALSE(FrameSequence::parse("a.%s.png"));
  EXPECT_TRUE(FrameSequence::isPattern("take#2/a.#.png"));
  EXPECT_TRUE(FrameSequence::isPattern("a.%03d.png"));
}

TEST(FrameSequence, AmbiguousOrTooWidePatternsAreOneLineErrors) {
  EXPECT_EQ(errorOf("out/a.##.b.##.png"), "out/a.##.b.##.png: expected one run of # for the frame number, got two");
  EXPECT_EQ(errorOf("a.##########.png"), "a.##########.png: expected at most 9 # for the frame number, got 10");
  EXPECT_EQ(errorOf("a.%010d.png"), "a.%010d.png: expected %d or %0Nd with N at most 9 for the frame number, got %010d");
  EXPECT_EQ(FrameSequence::parse("a.#########.png")->padding(), 9);
  EXPECT_TRUE(FrameSequence::isPattern("a.##.b.##.png"));  // a pattern, if a wrong one
}

// The farm's manifest, the movie set and `stirrup render` name a frame the same way.
TEST(FrameSequence, NamedIsNameDotNumberExtension) {
  EXPECT_EQ(FrameSequence::named("out", "trot_side", ".png").path(7), fs::path("out/trot_side.0007.png"));
  EXPECT_EQ(FrameSequence::named("", "trot_side", ".png").fileName(48), "trot_side.0048.png");
  EXPECT_EQ(FrameSequence::named("f/trot", "trot", ".sheet.exr").path(9), fs::path("f/trot/trot.0009.sheet.exr"));
  EXPECT_EQ(FrameSequence::named("o", "x", ".exr", 6).fileName(12), "x.000012.exr");
  EXPECT_THROW(FrameSequence::named("o", "x", ".exr", 10), rig::InputError);
  EXPECT_THROW(FrameSequence::named("o", "x", ".exr", -1), rig::InputError);
}

class FrameSequenceScan : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("stirrup_frame_sequence_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void touch(const std::string& name) { std::ofstream(dir_ / name) << "x"; }
  fs::path dir_;
};

TEST_F(FrameSequenceScan, FindsTheFramesByNumberAndIgnoresLookAlikes) {
  for (const char* frame : {"trot.0002.png", "trot.0010.png", "trot.0001.png", "trot.12345.png", "trot.-003.png"})
    touch(frame);
  for (const char* stray : {"trot.00012.png",    // five digits for frame 12: another padding
                            "trot.012.png",      // three
                            "trot.-0003.png",    // -3 is -003 with ####
                            "trot.+001.png", "trot.000a.png", "trot..png", "trot.0003.exr", "trot.0004.png.tmp",
                            "other.0005.png", "xtrot.0006.png", "trot.0007.pngx", "trot.1234567890.png"})
    touch(stray);
  fs::create_directories(dir_ / "trot.0008.png");  // a folder, not a frame
  const std::map<int, fs::path> frames = FrameSequence::parse(dir_ / "trot.####.png")->scan();
  std::vector<int> numbers;
  for (const auto& [n, file] : frames) numbers.push_back(n);
  EXPECT_EQ(numbers, (std::vector<int>{-3, 1, 2, 10, 12345}));  // by number: 10 after 2
  EXPECT_EQ(frames.at(10), dir_ / "trot.0010.png");
  EXPECT_EQ(frames.at(-3), dir_ / "trot.-003.png");
  EXPECT_EQ(frames.at(12345), dir_ / "trot.12345.png");
}

TEST_F(FrameSequenceScan, UnpaddedPatternsTakeOnlyUnpaddedNumbers) {
  for (const char* name : {"f.7.png", "f.07.png", "f.10.png", "f.0.png", "f.00.png"}) touch(name);
  const std::map<int, fs::path> frames = FrameSequence::parse(dir_ / "f.%d.png")->scan();
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames.begin()->second, dir_ / "f.0.png");
  EXPECT_EQ(frames.at(7), dir_ / "f.7.png");
  EXPECT_EQ(frames.at(10), dir_ / "f.10.png");
}

TEST_F(FrameSequenceScan, AnEmptyFolderHasNoFramesAMissingOneIsAnError) {
  EXPECT_TRUE(FrameSequence::parse(dir_ / "a.####.png")->scan().empty());
  const fs::path missing = dir_ / "nowhere" / "a.####.png";
  try {
    FrameSequence::parse(missing)->scan();
    FAIL() << "expected an InputError";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), missing.string() + ": no such folder " + (dir_ / "nowhere").string());
  }
}

TEST_F(FrameSequenceScan, AFolderlessPatternScansTheWorkingFolder) {
  const fs::path before = fs::current_path();
  fs::current_path(dir_);
  touch("w.0003.png");
  const std::map<int, fs::path> frames = FrameSequence::parse("w.####.png")->scan();
  fs::current_path(before);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames.begin()->first, 3);
  EXPECT_EQ(frames.begin()->second.filename(), "w.0003.png");
}

}  // namespace
}  // namespace stirrup::scene
