// The plotter (render/review/plot_canvas.cpp): the raster canvas's fills, blends, antialiased and dashed
// lines and pastes, read back from the PNG it writes, with coverages worked out by hand; the SVG canvas's
// markup for the same calls; the hex colours both take.
#include "render/review/plot_canvas.h"

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
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
  const std::string error = test::errorOf([&] { c.write(nowhere); });
  EXPECT_EQ(error.rfind(nowhere.string() + ": cannot write the image (", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(nowhere.string() + ".tmp.png"));
}

// A 1-pixel line along row 1 dashed 2 on, 2 off from x = 0 to 8: dashes [0, 2] and [4, 6]. Pixels 0, 1, 4
// and 5 are covered; 2, 3 and 6 are half a pixel from a dash's end (half covered); 7 is 1.5 from one.
TEST_F(CanvasTest, DashedLinesLeaveGaps) {
  Canvas c(8, 3, {0, 0, 0});
  c.dashedLine({0.0, 1.5}, {8.0, 1.5}, 1.0, {1, 1, 1}, 2.0);
  const std::vector<uint8_t> px = pixels(c);
  const std::vector<int> expected = {255, 255, 128, 128, 255, 255, 128, 0};
  for (int x = 0; x < 8; ++x) EXPECT_EQ(red(px, 8, x, 1), expected[std::size_t(x)]) << x;
}

// A polyline is its segments drawn in turn, and a rectangle its fill with a line around its outer pixels.
TEST_F(CanvasTest, PolylinesAndRectanglesAreTheirLinesAndFills) {
  Canvas a(8, 6, {0, 0, 0}), b(8, 6, {0, 0, 0});
  a.polyline({{1.0, 1.0}, {6.0, 2.0}, {3.0, 5.0}}, 1.5, {1, 0.5f, 0});
  b.line({1.0, 1.0}, {6.0, 2.0}, 1.5, {1, 0.5f, 0});
  b.line({6.0, 2.0}, {3.0, 5.0}, 1.5, {1, 0.5f, 0});
  EXPECT_EQ(pixels(a), pixels(b));
  Canvas r(8, 6, {0, 0, 0});
  r.rect({1.0, 1.0}, {7.0, 5.0}, {0, 0, 1}, {1, 0, 0});
  const std::vector<uint8_t> px = pixels(r);
  EXPECT_EQ(red(px, 8, 1, 1), 255);  // the edge
  EXPECT_EQ(red(px, 8, 6, 4), 255);
  EXPECT_EQ(red(px, 8, 3, 3), 0);  // inside: the fill
  EXPECT_EQ(px[(3 * 8 + 3) * 3 + 2], 255);
  EXPECT_EQ(red(px, 8, 0, 0), 0);  // outside
}

TEST(HexColor, ReadsShortAndLongForms) {
  EXPECT_EQ(hexColor("#c00"), (Color{0.8f, 0.0f, 0.0f}));
  EXPECT_EQ(hexColor("#ff8000"), (Color{1.0f, 128 / 255.0f, 0.0f}));
  EXPECT_THROW(hexColor("c00"), std::invalid_argument);
  EXPECT_THROW(hexColor("#c000"), std::invalid_argument);
}

// Each call is one element, in order; numbers to a tenth without a trailing .0; colours written back
// as given; black text, a stroke width of 1 and the root's font size left out; text escaped.
TEST(SvgCanvas, WritesEachCallAsAnElement) {
  SvgCanvas s(360, 150, 10);
  s.rect({40, 8}, {352, 128}, hexColor("#fafafa"), hexColor("#ccc"));
  s.dashedLine({40, 20.25}, {352, 20.25}, 1.0, hexColor("#c00"), 3);
  s.line({100, 8}, {100, 128}, 1.0, hexColor("#888"));
  s.polyline({{40, 60.04}, {50.5, 70}}, 1.5, hexColor("#1f77b4"));
  s.text({350, 18.3}, "limit <5>", 10, hexColor("#c00"), TextAlign::Right);
  s.text({4, 30}, "1", 10, hexColor("#000"));
  s.text({4, 40}, "big", 12, hexColor("#000"), TextAlign::Center, FontStyle::SansBold);
  EXPECT_EQ(s.markup(),
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"360\" height=\"150\" font-size=\"10\">"
            "<rect x=\"40\" y=\"8\" width=\"312\" height=\"120\" fill=\"#fafafa\" stroke=\"#ccc\"/>"
            "<line x1=\"40\" x2=\"352\" y1=\"20.2\" y2=\"20.2\" stroke=\"#c00\" stroke-dasharray=\"3,3\"/>"
            "<line x1=\"100\" x2=\"100\" y1=\"8\" y2=\"128\" stroke=\"#888\"/>"
            "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.5\" points=\"40,60 50.5,70\"/>"
            "<text x=\"350\" y=\"18.3\" text-anchor=\"end\" fill=\"#c00\">limit &lt;5&gt;</text>"
            "<text x=\"4\" y=\"30\">1</text>"
            "<text x=\"4\" y=\"40\" text-anchor=\"middle\" font-size=\"12\" font-weight=\"bold\">big</text>"
            "</svg>");
}

}  // namespace
}  // namespace stirrup::render
