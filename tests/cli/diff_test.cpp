// stirrup diff on synthetic images whose differences are known exactly.
#include <filesystem>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// A 10x10 RGB image of value 100/255, with `changed` pixels on the diagonal raised by 51/255 (= 0.2)
// in the green channel.
void writeImage(const fs::path& file, int changed, int width = 10) {
  const int h = 10;
  std::vector<unsigned char> px(static_cast<std::size_t>(width) * h * 3, 100);
  for (int i = 0; i < changed; ++i) px[(static_cast<std::size_t>(i) * width + i) * 3 + 1] = 151;
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(width, h, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
  out->close();
}

class Diff : public ::testing::Test {
 protected:
  // One folder per test: CTest runs tests in parallel processes.
  fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_diff" /
                 ::testing::UnitTest::GetInstance()->current_test_info()->name();
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    writeImage(dir / "ref.png", 0);
    writeImage(dir / "new.png", 3);
  }
  std::string files() { return quote((dir / "ref.png").string()) + " " + quote((dir / "new.png").string()); }
};

TEST_F(Diff, ReportsTheKnownNumbers) {
  const CommandResult r = runStirrup("diff " + files() + " --fail 0.1 --failpercent 5 --warn 0.1 --warnpercent 5");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  // 3 pixels x 1 channel off by 0.2 over 300 channel values: mean 0.002, RMS 0.02, PSNR 33.98 dB.
  EXPECT_NE(r.out.find("PASS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mean 0.002000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("RMS 0.020000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max 0.200000 at (0, 0)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PSNR 33.98 dB"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 pixels over fail"), std::string::npos) << r.out;
}

TEST_F(Diff, WarnAndFailExitCodes) {
  EXPECT_EQ(runStirrup("diff " + files() + " --fail 0.1 --failpercent 5").exit_code, 1);  // warn 1e-6, 0%
  EXPECT_EQ(runStirrup("diff " + files() + " --fail 0.1 --failpercent 2").exit_code, 2);  // 3% > 2%
  EXPECT_EQ(runStirrup("diff " + files() + " --fail 0.3").exit_code, 1);
  EXPECT_EQ(runStirrup("diff " + files() + " --fail 0.3 --warn 0.3 --hardfail 0.1").exit_code, 2);
  EXPECT_EQ(runStirrup("diff " + quote((dir / "ref.png").string()) + " " + quote((dir / "ref.png").string()))
                .exit_code,
            0);
}

TEST_F(Diff, WritesAVisibleDiffImage) {
  const fs::path d = dir / "d.png";
  runStirrup("diff " + files() + " --fail 0.1 --diff-image " + quote(d.string()));
  auto in = OIIO::ImageInput::open(d.string());
  ASSERT_TRUE(in);
  std::vector<unsigned char> px(10 * 10 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  EXPECT_EQ(px[1], 255);  // 0.2 x 16 clamps to white in green at (0, 0)
  EXPECT_EQ(px[0], 0);
  EXPECT_EQ(px[(5 * 10 + 4) * 3 + 1], 0);  // an unchanged pixel
}

TEST_F(Diff, DifferentSizesAreAnError) {
  writeImage(dir / "wide.png", 0, 12);
  const CommandResult r =
      runStirrup("diff " + quote((dir / "ref.png").string()) + " " + quote((dir / "wide.png").string()));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(lineCount(r.err), 1u);
  EXPECT_NE(r.err.find("is 10x10 but"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected images of the same size"), std::string::npos) << r.err;
}

TEST_F(Diff, ComparesSequencesFrameByFrame) {
  writeImage(dir / "a/s.0001.png", 0);
  writeImage(dir / "a/s.0002.png", 0);
  writeImage(dir / "b/s.0001.png", 0);
  writeImage(dir / "b/s.0002.png", 3);
  const CommandResult r = runStirrup("diff " + quote((dir / "a/s.####.png").string()) + " " +
                                     quote((dir / "b/s.####.png").string()) + " --fail 0.3");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("2 frames: WARNING"), std::string::npos) << r.out;
  fs::remove(dir / "b/s.0002.png");
  const CommandResult missing = runStirrup("diff " + quote((dir / "a/s.####.png").string()) + " " +
                                           quote((dir / "b/s.####.png").string()));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("frame 2 is missing"), std::string::npos) << missing.err;
}

// The frames of a pattern are the files it names exactly (docs/frame-sequences.md): s.00002.png is not
// frame 2 of s.####.png (it once was, and one of the two files won), and s.-001.png is frame -1.
TEST_F(Diff, SequencesHoldTheFramesThePatternNamesExactly) {
  for (const char* side : {"a", "b"}) {
    writeImage(dir / side / "s.-001.png", 0);
    writeImage(dir / side / "s.0002.png", 0);
  }
  writeImage(dir / "b/s.00002.png", 3);  // a look-alike, different pixels
  fs::copy_file(dir / "new.png", dir / "b/s.0003.png.tmp");  // a frame being written
  const CommandResult r = runStirrup("diff " + quote((dir / "a/s.####.png").string()) + " " +
                                     quote((dir / "b/s.####.png").string()));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 frames: PASS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("s.-001.png"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("s.00002.png"), std::string::npos) << r.out;
}

TEST_F(Diff, WritesOneDiffImagePerFrameThroughAPattern) {
  writeImage(dir / "a/s.0007.png", 0);
  writeImage(dir / "a/s.0009.png", 0);
  writeImage(dir / "b/s.0007.png", 0);
  writeImage(dir / "b/s.0009.png", 3);
  const CommandResult r = runStirrup("diff " + quote((dir / "a/s.####.png").string()) + " " +
                                     quote((dir / "b/s.####.png").string()) + " --fail 0.3 -o " +
                                     quote((dir / "d/diff.###.png").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  // The frame number takes the place of the #s, padded to their count.
  EXPECT_TRUE(fs::exists(dir / "d/diff.007.png"));
  ASSERT_TRUE(fs::exists(dir / "d/diff.009.png"));
  auto in = OIIO::ImageInput::open((dir / "d/diff.009.png").string());
  ASSERT_TRUE(in);
  std::vector<unsigned char> px(10 * 10 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  EXPECT_EQ(px[1], 255);  // frame 9 differs at (0, 0)
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "d"), fs::directory_iterator{}), 2);
}

}  // namespace
}  // namespace stirrup::test
