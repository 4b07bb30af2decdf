#include "render/review/burn_in.h"

#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

TEST(Timecode, CountsFromFrameOneAtTheSceneRate) {
  EXPECT_EQ(timecode(1, 24.0), "00:00:00:00");
  EXPECT_EQ(timecode(24, 24.0), "00:00:00:23");
  EXPECT_EQ(timecode(25, 24.0), "00:00:01:00");
  EXPECT_EQ(timecode(24 * 61 + 3, 24.0), "00:01:01:02");
  EXPECT_EQ(timecode(30 * 3600 + 1, 30.0), "01:00:00:00");
}

Image grey(int w, int h) {
  Image im(w, h);
  for (glm::vec4& p : im.rgba) p = glm::vec4(0.18f, 0.18f, 0.18f, 1.0f);
  return im;
}

TEST(BurnIn, WritesTextInTheBandsAndLeavesThePictureBetween) {
  Image im = grey(320, 180);
  BurnInFacts facts{"trot", "trot", "side", "thesis", 24.0, "1-72", 72, "review", "2026-01-01"};
  burnIn(im, facts, 12);
  int bright_top = 0, bright_bottom = 0, changed_middle = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const glm::vec4& p = im.at(x, y);
      if (y < 20 && p.x > 0.5f) ++bright_top;
      if (y > im.height - 20 && p.x > 0.5f) ++bright_bottom;
      if (y > 30 && y < im.height - 30 && p != glm::vec4(0.18f, 0.18f, 0.18f, 1.0f)) ++changed_middle;
    }
  EXPECT_GT(bright_top, 100);     // scene | movement | view, profile
  EXPECT_GT(bright_bottom, 100);  // frame number, timecode
  EXPECT_EQ(changed_middle, 0);
}

TEST(BurnIn, DifferentFramesBurnDifferentNumbers) {
  BurnInFacts facts{"trot", "trot", "side", "thesis", 24.0, "1-72", 72, "review", "2026-01-01"};
  Image a = grey(320, 180), b = grey(320, 180);
  burnIn(a, facts, 12);
  burnIn(b, facts, 13);
  int differ = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) differ += a.rgba[i] != b.rgba[i];
  EXPECT_GT(differ, 10);
}

TEST(Slate, ShowsTheFactsOnAnOpaqueFrame) {
  BurnInFacts facts{"jump", "jump", "persp", "thesis", 24.0, "1-126", 126, "review", "2026-01-01"};
  const Image s = makeSlate(640, 360, facts);
  ASSERT_EQ(s.width, 640);
  int text = 0;
  for (const glm::vec4& p : s.rgba) {
    EXPECT_EQ(p.w, 1.0f);
    text += p.x > 0.4f;
  }
  EXPECT_GT(text, 2000);
  // Another date changes the slate.
  facts.date = "2026-01-02";
  const Image t = makeSlate(640, 360, facts);
  EXPECT_NE(s.rgba, t.rgba);
}

}  // namespace
}  // namespace stirrup::render
