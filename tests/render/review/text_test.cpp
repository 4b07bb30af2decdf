// Text (render/review/text.cpp): finding the DejaVu fonts and drawing text into a coverage mask where
// its alignment says, measured on the mask.
#include "render/review/text.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/error.h"

namespace stirrup::render {
namespace {

// The covered box of a mask: {min x, min y, max x, max y}, or all -1 when nothing is covered.
std::array<int, 4> coveredBox(const std::vector<float>& mask, int width) {
  std::array<int, 4> box = {-1, -1, -1, -1};
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] <= 0.0f) continue;
    const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
    if (box[0] < 0) box = {x, y, x, y};
    box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
  }
  return box;
}

std::vector<float> drawn(const std::string& text, int x, int y, TextAlign align) {
  std::vector<float> mask(200 * 40, 0.0f);
  drawTextMask(mask, 200, 40, x, y, text, 20, FontStyle::Sans, align);
  return mask;
}

TEST(Font, ABadStirrupFontIsAClearError) {
  ::setenv("STIRRUP_FONT", "/nonexistent/font.ttf", 1);
  try {
    (void)findFont();
    ADD_FAILURE() << "expected an error";
  } catch (const rig::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("STIRRUP_FONT: /nonexistent/font.ttf"), std::string::npos) << e.what();
  }
  ::unsetenv("STIRRUP_FONT");
  EXPECT_TRUE(std::filesystem::is_regular_file(findFont()));
}

TEST(Font, EachStyleIsItsDejaVuFile) {
  EXPECT_EQ(findFont(FontStyle::Sans).filename(), "DejaVuSans.ttf");
  EXPECT_EQ(findFont(FontStyle::SansBold).filename(), "DejaVuSans-Bold.ttf");
  EXPECT_EQ(findFont(FontStyle::Mono).filename(), "DejaVuSansMono.ttf");
}

// Text at 20 px, baseline at y = 30: capitals without descenders stand on it, about 15 px tall
// (DejaVu's cap height is 0.73 em).
TEST(Text, LeftCentreAndRightAlignmentPlaceTheText) {
  const std::array<int, 4> left = coveredBox(drawn("HELLO", 10, 30, TextAlign::Left), 200);
  ASSERT_GE(left[0], 0) << "nothing drawn";
  EXPECT_GE(left[0], 10);
  EXPECT_LE(left[0], 13);  // the H's left side bearing
  EXPECT_LE(left[3], 30);  // nothing below the baseline
  EXPECT_GE(left[3], 28);
  EXPECT_NEAR(30 - left[1], 15, 2);  // cap height
  const std::array<int, 4> right = coveredBox(drawn("HELLO", 190, 30, TextAlign::Right), 200);
  EXPECT_LE(right[2], 190);
  EXPECT_GE(right[2], 186);
  const std::array<int, 4> centre = coveredBox(drawn("HELLO", 100, 30, TextAlign::Center), 200);
  EXPECT_NEAR(0.5 * (centre[0] + centre[2]), 100.0, 2.0);
  // The three are the same text moved: the same width.
  EXPECT_NEAR(right[2] - right[0], left[2] - left[0], 1);
}

TEST(Text, NothingOutsideTheMaskAndNothingForNoText) {
  // Half below the bottom edge: the top half is drawn, down to the last row.
  const std::array<int, 4> half = coveredBox(drawn("HELLO", 10, 47, TextAlign::Left), 200);
  EXPECT_EQ(half[3], 39);
  EXPECT_NEAR(half[1], 47 - 15, 2);
  EXPECT_EQ(coveredBox(drawn("HELLO", 10, 100, TextAlign::Left), 200)[0], -1);  // baseline far below
  EXPECT_EQ(coveredBox(drawn("HELLO", 250, 30, TextAlign::Left), 200)[0], -1);   // right of the mask
  EXPECT_EQ(coveredBox(drawn("HELLO", -5, 30, TextAlign::Right), 200)[0], -1);   // left of it
  EXPECT_EQ(coveredBox(drawn("", 10, 30, TextAlign::Left), 200)[0], -1);
}

TEST(Text, SizeGrowsWithTheTextAndTheFontSize) {
  const std::array<int, 2> w = textSize("W", 20), ww = textSize("WW", 20), big = textSize("W", 40);
  EXPECT_GT(w[0], 0);
  EXPECT_NEAR(ww[0], 2 * w[0], 2);  // no kerning between two Ws
  EXPECT_NEAR(big[0], 2 * w[0], 0.1 * 2 * w[0]);  // hinting rounds each size its own way
  EXPECT_GT(big[1], w[1]);
  EXPECT_LE(w[1], 20 + 2);
}

}  // namespace
}  // namespace stirrup::render
