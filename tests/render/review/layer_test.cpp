// Layered comparisons (render/review/layer.cpp): composites on small synthetic images whose expected
// pixels are worked out by hand in the comments, and bad input. Footage, plates and the reference block
// (render/review/footage.cpp) are tested in footage_test.cpp.
#include "render/review/layer.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "tests/input_error.h"
#include "tests/render/review/solid_image.h"

#include "rig/error.h"
#include "scene/scene.h"

namespace stirrup::render {
namespace {

using test::errorOf;

// --- Over ------------------------------------------------------------------------------------------

TEST(LayerOver, MatteKeyedOpacityByHand) {
  Image ours(2, 1), other(2, 1);
  ours.rgba = {{0.8f, 0.4f, 0.2f, 1.0f}, {0.2f, 0.6f, 1.0f, 1.0f}};
  ours.matte = {1.0f, 0.5f};
  other.rgba = {{0.0f, 0.2f, 0.4f, 1.0f}, {1.0f, 1.0f, 1.0f, 1.0f}};
  LayerStyle s;
  s.mode = scene::LayerMode::Over;
  s.opacity = 0.5f;
  s.coverage = LayerCoverage::Matte;
  const Image out = layerFrame(ours, other, s);
  ASSERT_EQ(out.width, 2);
  ASSERT_EQ(out.height, 1);
  // k = 0.5 * 1: 0.5*0.8 + 0.5*0.0, 0.5*0.4 + 0.5*0.2, 0.5*0.2 + 0.5*0.4
  expectRgb(out, 0, 0, {0.4f, 0.3f, 0.3f});
  // k = 0.5 * 0.5 = 0.25: 0.25*0.2 + 0.75*1, 0.25*0.6 + 0.75, 0.25*1 + 0.75
  expectRgb(out, 1, 0, {0.8f, 0.9f, 1.0f});
  EXPECT_FLOAT_EQ(out.at(0, 0).w, 1.0f);
  EXPECT_TRUE(out.matte.empty());
}

TEST(LayerOver, FullCoverageIsACrossDissolveAndNoMatteMeansFull) {
  Image ours = solid(1, 1, {1.0f, 0.0f, 0.5f, 0.0f});  // alpha 0: open sky
  const Image other = solid(1, 1, {0.0f, 1.0f, 0.5f, 1.0f});
  LayerStyle s;
  s.mode = scene::LayerMode::Over;
  s.opacity = 0.25f;
  s.coverage = LayerCoverage::Full;
  expectRgb(layerFrame(ours, other, s), 0, 0, {0.25f, 0.75f, 0.5f});
  s.coverage = LayerCoverage::Matte;  // no matte pass: the whole frame
  expectRgb(layerFrame(ours, other, s), 0, 0, {0.25f, 0.75f, 0.5f});
  s.coverage = LayerCoverage::Alpha;  // alpha 0: other shows through untouched
  expectRgb(layerFrame(ours, other, s), 0, 0, {0.0f, 1.0f, 0.5f});
  ours.rgba[0].w = 0.5f;  // k = 0.25 * 0.5 = 0.125
  expectRgb(layerFrame(ours, other, s), 0, 0, {0.125f, 0.875f, 0.5f});
}

TEST(LayerOver, DifferentSizesAreAnError) {
  LayerStyle s;
  s.mode = scene::LayerMode::Over;
  const std::string e = errorOf([&] { layerFrame(Image(4, 2), Image(4, 3), s); });
  EXPECT_NE(e.find("same size"), std::string::npos) << e;
  EXPECT_NE(e.find("4x2"), std::string::npos) << e;
  s.mode = scene::LayerMode::Difference;
  EXPECT_NE(errorOf([&] { layerFrame(Image(4, 2), Image(3, 2), s); }).find("same size"), std::string::npos);
}

// --- Difference ------------------------------------------------------------------------------------

TEST(LayerDifference, AbsoluteDifferenceTimesGainClampedToOne) {
  const Image a = solid(2, 2, {0.5f, 0.25f, 0.1f, 1.0f});
  const Image b = solid(2, 2, {0.25f, 0.5f, 0.1f, 1.0f});
  LayerStyle s;
  s.mode = scene::LayerMode::Difference;
  s.difference_gain = 2.0f;
  // |0.5-0.25|*2, |0.25-0.5|*2, 0
  expectRgb(layerFrame(a, b, s), 1, 1, {0.5f, 0.5f, 0.0f});
  s.difference_gain = 4.0f;  // 1.0 each, clamped
  expectRgb(layerFrame(a, b, s), 0, 1, {1.0f, 1.0f, 0.0f});
  // Identical pixels are black.
  expectRgb(layerFrame(a, a, s), 0, 0, {0.0f, 0.0f, 0.0f});
}

// --- Side by side ----------------------------------------------------------------------------------

TEST(LayerSideBySide, LayoutAtOursHeightWithGap) {
  const Image ours = solid(4, 2, {1.0f, 0.0f, 0.0f, 1.0f});
  Image other(2, 1);
  other.rgba = {{0.0f, 1.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f, 1.0f}};
  LayerStyle s;
  s.mode = scene::LayerMode::SideBySide;
  s.labels = false;
  s.gap = 1;
  s.gap_colour = {0.5f, 0.5f, 0.5f, 1.0f};
  const Image out = layerFrame(ours, other, s);
  // ours 4 wide, 1 gap, other scaled x2 to height 2: 4 wide.
  ASSERT_EQ(out.width, 9);
  ASSERT_EQ(out.height, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 4; ++x) expectRgb(out, x, y, {1.0f, 0.0f, 0.0f});
    expectRgb(out, 4, y, {0.5f, 0.5f, 0.5f});
    // Bilinear x2 of (green, blue): centres at 0.25, 0.75, 1.25, 1.75 of the source, clamped at the ends.
    expectRgb(out, 5, y, {0.0f, 1.0f, 0.0f});
    expectRgb(out, 6, y, {0.0f, 0.75f, 0.25f});
    expectRgb(out, 7, y, {0.0f, 0.25f, 0.75f});
    expectRgb(out, 8, y, {0.0f, 0.0f, 1.0f});
  }
}

TEST(LayerSideBySide, SameHeightIsAnExactCopyAndReductionAverages) {
  Image other(2, 2);
  other.rgba = {{0.1f, 0.2f, 0.3f, 1}, {0.4f, 0.5f, 0.6f, 1}, {0.7f, 0.8f, 0.9f, 1}, {0.0f, 0.0f, 0.0f, 1}};
  LayerStyle s;
  s.labels = false;
  s.gap = 0;
  Image out = layerFrame(solid(3, 2, {1, 1, 1, 1}), other, s);
  ASSERT_EQ(out.width, 5);
  expectRgb(out, 3, 0, {0.1f, 0.2f, 0.3f});
  expectRgb(out, 4, 1, {0.0f, 0.0f, 0.0f});
  // Other reduced to height 1: one pixel, the mean of the four.
  out = layerFrame(solid(3, 1, {1, 1, 1, 1}), other, s);
  ASSERT_EQ(out.width, 4);
  expectRgb(out, 3, 0, {0.3f, 0.375f, 0.45f});
}

TEST(LayerSideBySide, LabelsNameEachSide) {
  const Image ours = solid(20, 12, {0.5f, 0.5f, 0.5f, 1.0f});
  const Image other = solid(20, 12, {0.5f, 0.5f, 0.5f, 1.0f});
  LayerStyle s;
  s.gap = 2;
  s.label_scale = 1;
  s.ours_label = std::string(1, 'A');
  s.other_label = std::string(1, '1');
  const Image out = layerFrame(ours, other, s);
  ASSERT_EQ(out.width, 42);
  // The label box starts 2 px in (2 * scale); the glyph 1 px inside it. "A" row 0 is .###. and
  // "1" row 0 is ..#..; unlit pixels in the box are darkened to 0.4 of the picture.
  expectRgb(out, 2 + 1 + 1, 2 + 1, {1.0f, 1.0f, 1.0f});
  expectRgb(out, 2 + 1 + 0, 2 + 1, {0.2f, 0.2f, 0.2f});
  const int right = 20 + 2;
  expectRgb(out, right + 2 + 1 + 2, 2 + 1, {1.0f, 1.0f, 1.0f});
  expectRgb(out, right + 2 + 1 + 1, 2 + 1, {0.2f, 0.2f, 0.2f});
  // Away from the labels the pictures are untouched.
  expectRgb(out, 15, 10, {0.5f, 0.5f, 0.5f});
  expectRgb(out, right + 15, 10, {0.5f, 0.5f, 0.5f});
}

// --- Onion skin ------------------------------------------------------------------------------------

TEST(LayerOnionSkin, GhostsFarthestFirstTintedAndFadedOursOnTop) {
  Image ours(2, 1);
  ours.rgba = {{0.9f, 0.9f, 0.9f, 1.0f}, {0.3f, 0.6f, 0.9f, 1.0f}};
  ours.matte = {0.0f, 1.0f};  // pixel 0 shows the ghosts, pixel 1 is ours
  const Image other = solid(2, 1, {0.0f, 0.0f, 0.0f, 1.0f});
  Image ghost = solid(2, 1, {1.0f, 1.0f, 1.0f, 1.0f});
  ghost.matte = {1.0f, 1.0f};
  const std::vector<Image> ghosts = {ghost, ghost, ghost};
  const std::vector<int> offsets = {+1, -2, -1};
  LayerStyle s;
  s.mode = scene::LayerMode::OnionSkin;
  s.opacity = 0.5f;
  s.onion_falloff = 0.5f;
  s.onion_before = {1.0f, 0.5f, 0.25f, 1.0f};
  s.onion_after = {0.25f, 0.5f, 1.0f, 1.0f};
  const Image out = onionSkin(ours, ghosts, offsets, other, s);
  // -2 (ring 2, 0.25): 0.25 * (1, .5, .25)                      = (.25, .125, .0625)
  // -1 (ring 1, 0.5):  0.5 * (1, .5, .25) + 0.5 * previous       = (.625, .3125, .15625)
  // +1 (ring 1, 0.5):  0.5 * (.25, .5, 1) + 0.5 * previous       = (.4375, .40625, .578125)
  expectRgb(out, 0, 0, {0.4375f, 0.40625f, 0.578125f});
  expectRgb(out, 1, 0, {0.3f, 0.6f, 0.9f});
  // Without ghosts it is ours over other at full coverage.
  expectRgb(layerFrame(ours, other, s), 0, 0, {0.0f, 0.0f, 0.0f});
  expectRgb(layerFrame(ours, other, s), 1, 0, {0.3f, 0.6f, 0.9f});
}

TEST(LayerOnionSkin, GhostFramesAndBadInput) {
  LayerStyle s;
  s.onion_frames = 2;
  s.onion_step = 2;
  EXPECT_EQ(onionGhostFrames(10, s, 1, 12), (std::vector<int>{6, 8, 12}));
  EXPECT_EQ(onionGhostFrames(1, s, 1, 12), (std::vector<int>{3, 5}));
  s.onion_step = 1;
  s.onion_frames = 1;
  EXPECT_EQ(onionGhostFrames(5, s, 1, 12), (std::vector<int>{4, 6}));
  const Image one = solid(1, 1, {0, 0, 0, 1});
  const std::vector<Image> ghosts = {one};
  const std::vector<int> zero = {0}, two = {1, 2};
  EXPECT_NE(errorOf([&] { onionSkin(one, ghosts, zero, one, s); }).find("offset is 0"), std::string::npos);
  EXPECT_NE(errorOf([&] { onionSkin(one, ghosts, two, one, s); }).find("offsets"), std::string::npos);
}

}  // namespace
}  // namespace stirrup::render
