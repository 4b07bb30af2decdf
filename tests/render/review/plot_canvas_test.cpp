// The diagram canvas (render/review/plot_canvas.cpp): fills, blends, antialiased lines and pastes,
// read back from the PNG it writes, with coverages worked out by hand.
#include "render/review/plot_canvas.h"

#include <unistd.h>

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

class CanvasTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("stirrup_plot_canvas_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // The canvas written and read back: 8-bit RGB, row by row.
  std::vector<uint8_t> pixels(const Canvas& c) {
    const fs::path file = dir_ / "c.png";
    c.write(file);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    EXPECT_TRUE(in);
    std::vector<uint8_t> px(std::size_t(c.width()) * std::size_t(c.height()) * 3);
    EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
    return px;
  }
  static uint8_t red(const std::vector<uint8_t>& px, int w, int x, int y) { return px[(std::size_t(y) * w + x) * 3]; }
  fs::path dir_;
};

TEST_F(CanvasTest, FillAndBlendMixTowardTheColourByCoverage) {
  Canvas c(8, 4, {0, 0, 0});
  c.fill(2, 1, 4, 3, {1, 0, 0});  // [2, 4) x [1, 3)
  c.blend(6, 0, 0.5, {1, 1, 1});   // half way from black to white: 0.5 -> 128 of 255
  c.fill(-5, 3, 1, 99, {0, 0, 1});  // clipped to the canvas: only (0, 3)
  const std::vector<uint8_t> px = pixels(c);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool filled = x >= 2 && x < 4 && y >= 1 && y < 3;
      EXPECT_EQ(red(px, 8, x, y), filled ? 255 : (x == 6 && y == 0 ? 128 : 0)) << x << ", " << y;
    }
  EXPECT_EQ(px[(3 * 8 + 0) * 3 + 2], 255);  // blue at (0, 3)
  EXPECT_EQ(px[(3 * 8 + 1) * 3 + 2], 0);
}

// A 1-pixel line along the centres of row 2 (y = 2.5) from x = 1 to 6: a pixel's coverage is
// r + 0.5 - d = 1 - d for its centre's distance d to the segment. Row 2: d = 0 inside, so full; pixel 0's
// centre (0.5, 2.5) is 0.5 from the end (1, 2.5): half. Rows 1 and 3: d = 1, nothing.
TEST_F(CanvasTest, LinesAreCoveredByDistance) {
  Canvas c(8, 4, {0, 0, 0});
  c.line({1.0, 2.5}, {6.0, 2.5}, 1.0, {1, 1, 1});
  const std::vector<uint8_t> px = pixels(c);
  EXPECT_EQ(red(px, 8, 0, 2), 128);
  for (int x = 1; x <= 5; ++x) EXPECT_EQ(red(px, 8, x, 2), 255) << x;
  EXPECT_EQ(red(px, 8, 6, 2), 128);  // centre 6.5 is 0.5 past the end
  EXPECT_EQ(red(px, 8, 7, 2), 0);
  for (int x = 0; x < 8; ++x) {
    EXPECT_EQ(red(px, 8, x, 1), 0) << x;
    EXPECT_EQ(red(px, 8, x, 3), 0) << x;
  }
}

TEST_F(CanvasTest, PasteCopiesAndClipsAndWriteFailsCleanly) {
  Canvas c(4, 2, {0, 0, 0});
  c.paste(3, 1, 2, 1, {0.2f, 0.4f, 1.0f, 1.0f, 1.0f, 1.0f});  // its second pixel falls off the right edge
  const std::vector<uint8_t> px = pixels(c);
  EXPECT_EQ(std::vector<uint8_t>(px.end() - 3, px.end()), (std::vector<uint8_t>{51, 102, 255}));
  EXPECT_EQ(px[(1 * 4 + 2) * 3], 0);
  const fs::path nowhere = dir_ / "no" / "such" / "folder" / "c.png";
  EXPECT_EQ(test::errorOf([&] { c.write(nowhere); }), nowhere.string() + ": cannot write the image");
  EXPECT_FALSE(fs::exists(nowhere.string() + ".tmp.png"));
}

}  // namespace
}  // namespace stirrup::render
