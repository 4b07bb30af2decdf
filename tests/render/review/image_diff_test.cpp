// Image comparison (render/review/image_diff.cpp) on tiny 8-bit images whose errors are worked out by
// hand: idiff's per-pixel error (the largest channel difference), its mean, RMS and PSNR over every
// channel value, the verdict by thresholds, and the scaled difference image.
#include "render/review/image_diff.h"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "tests/input_error.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

class ImageDiff : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("stirrup_image_diff_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path png(const std::string& name, int w, int h, int channels, const std::vector<uint8_t>& px) {
    const fs::path file = dir_ / name;
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(file.string());
    EXPECT_TRUE(out && out->open(file.string(), OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::UINT8)));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
    out->close();
    return file;
  }
  fs::path dir_;
};

// A: two black RGB pixels. B: the first one's red at 51 (0.2). Channel errors: one 0.2 among six values.
TEST_F(ImageDiff, ErrorsAreIdiffsMeasures) {
  const fs::path a = png("a.png", 2, 1, 3, {0, 0, 0, 0, 0, 0});
  const fs::path b = png("b.png", 2, 1, 3, {51, 0, 0, 0, 0, 0});
  DiffThresholds t;
  t.fail = 0.1;
  const DiffResult r = compareImageFiles(a, b, t);
  EXPECT_EQ(r.width, 2);
  EXPECT_EQ(r.channels, 3);
  EXPECT_NEAR(r.max_error, 0.2, 1e-6);
  EXPECT_EQ(r.worst_x, 0);
  EXPECT_NEAR(r.mean_error, 0.2 / 6.0, 1e-6);
  EXPECT_NEAR(r.rms_error, std::sqrt(0.04 / 6.0), 1e-6);               // 0.08165
  EXPECT_NEAR(r.psnr_db, 20.0 * std::log10(1.0 / std::sqrt(0.04 / 6.0)), 1e-4);  // 21.76 dB
  EXPECT_EQ(r.pixels_over_fail, 1);
  EXPECT_EQ(r.pixels_over_warn, 1);
  EXPECT_EQ(r.verdict, DiffVerdict::Fail);  // one pixel over, none allowed
  EXPECT_EQ(r.summary(),
            "mean 0.033333, RMS 0.081650, max 0.200000 at (0, 0), PSNR 21.76 dB, 1 pixels over fail, 1 over warn");
}

TEST_F(ImageDiff, TheVerdictFollowsTheThresholds) {
  const fs::path a = png("a.png", 2, 1, 3, {0, 0, 0, 0, 0, 0});
  const fs::path b = png("b.png", 2, 1, 3, {51, 0, 0, 0, 0, 0});
  DiffThresholds t;
  t.fail = 0.1;
  t.fail_fraction = 0.5;  // one pixel of two may fail: 1 > 0.5 * 2 is false
  EXPECT_EQ(compareImageFiles(a, b, t).verdict, DiffVerdict::Warn);  // but none may pass warn (0.004)
  t.warn_fraction = 0.5;
  EXPECT_EQ(compareImageFiles(a, b, t).verdict, DiffVerdict::Pass);
  t.hardfail = 0.15;  // whatever the fractions, a pixel past hardfail fails
  EXPECT_EQ(compareImageFiles(a, b, t).verdict, DiffVerdict::Fail);
  const DiffResult same = compareImageFiles(a, a, DiffThresholds{});
  EXPECT_EQ(same.verdict, DiffVerdict::Pass);
  EXPECT_EQ(same.max_error, 0.0);
  EXPECT_TRUE(std::isinf(same.psnr_db));
}

// |A - B| x 16, clamped: 0.2 x 16 = 3.2 -> 1 (255); 2/255 x 16 = 32/255.
TEST_F(ImageDiff, TheDifferenceImageIsScaled) {
  const fs::path a = png("a.png", 2, 1, 3, {0, 0, 0, 0, 0, 0});
  const fs::path b = png("b.png", 2, 1, 3, {51, 0, 0, 0, 2, 0});
  const fs::path d = dir_ / "d.png";
  compareImageFiles(a, b, DiffThresholds{}, d, 16.0);
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(d.string());
  ASSERT_TRUE(in);
  std::vector<uint8_t> px(6);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  EXPECT_EQ(px, (std::vector<uint8_t>{255, 0, 0, 0, 32, 0}));
}

TEST_F(ImageDiff, ImagesThatCannotBeComparedAreOneLineErrors) {
  const fs::path a = png("a.png", 2, 1, 3, {0, 0, 0, 0, 0, 0});
  const fs::path tall = png("tall.png", 1, 2, 3, {0, 0, 0, 0, 0, 0});
  const fs::path rgba = png("rgba.png", 2, 1, 4, {0, 0, 0, 255, 0, 0, 0, 255});
  EXPECT_EQ(errorOf([&] { compareImageFiles(a, tall, DiffThresholds{}); }),
            a.string() + " is 2x1 but " + tall.string() + " is 1x2: expected images of the same size");
  EXPECT_EQ(errorOf([&] { compareImageFiles(a, rgba, DiffThresholds{}); }),
            a.string() + " has 3 channels but " + rgba.string() + " has 4: expected the same channel count");
  EXPECT_EQ(errorOf([&] { compareImageFiles(a, dir_ / "gone.png", DiffThresholds{}); })
                .rfind((dir_ / "gone.png").string() + ": cannot read the image (", 0),
            0u);
}

}  // namespace
}  // namespace stirrup::render
