// Footage (render/review/footage.cpp): their frames mapped onto ours and placed on our canvas, image
// sequences on disk, plates cut into frames, the footage a scene's reference block names, and bad input. Expected
// pixels are worked out by hand in the comments.
#include "render/review/layer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/review/layer.h"
#include "render/tracer/image.h"
#include "rig/error.h"
#include "scene/scene.h"
#include "tests/input_error.h"
#include "tests/render/review/solid_image.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

using test::errorOf;

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "footage_test" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// --- Footage mapping and placement -----------------------------------------------------------------

FootageSequence fiveFrames() {
  FootageSequence f;
  for (int i = 0; i < 5; ++i) f.images.push_back(solid(2, 2, {0.1f * float(i), 0, 0, 1}));
  f.first = 101;
  f.name = "five";
  return f;
}

TEST(Footage, OffsetRateAndEdgesPickTheRightFrames) {
  FootageSequence f = fiveFrames();
  // Rate 1, offset 0: our frame 1 is their first frame.
  EXPECT_EQ(f.theirFrame(1), 101);
  EXPECT_EQ(f.theirFrame(5), 105);
  f.edge = scene::FootageEdge::Hold;
  EXPECT_EQ(f.theirFrame(6), 105);
  EXPECT_EQ(f.theirFrame(-3), 101);
  f.edge = scene::FootageEdge::Loop;
  EXPECT_EQ(f.theirFrame(6), 101);
  EXPECT_EQ(f.theirFrame(12), 102);
  EXPECT_EQ(f.theirFrame(0), 105);
  f.edge = scene::FootageEdge::Blank;
  EXPECT_EQ(f.theirFrame(6), std::nullopt);
  EXPECT_EQ(f.theirFrame(0), std::nullopt);
  // Footage at 12 fps under our 24: each of their frames held for two of ours.
  f.edge = scene::FootageEdge::Hold;
  f.rate = 0.5;
  EXPECT_EQ(f.theirFrame(1), 101);
  EXPECT_EQ(f.theirFrame(2), 101);
  EXPECT_EQ(f.theirFrame(3), 102);
  EXPECT_EQ(f.theirFrame(4), 102);
  // Footage at 48 fps: every second frame.
  f.rate = 2.0;
  EXPECT_EQ(f.theirFrame(2), 103);
  EXPECT_EQ(f.theirFrame(3), 105);
  // Footage at 18 fps under our 24: index floor((f - 1) * 0.75).
  f.rate = 0.75;
  EXPECT_EQ(f.theirFrame(5), 104);  // 3
  EXPECT_EQ(f.theirFrame(6), 104);  // 3.75
  EXPECT_EQ(f.theirFrame(7), 105);  // 4.5
  f.edge = scene::FootageEdge::Blank;
  // Offset in their frames.
  f.rate = 1.0;
  f.offset = 2;
  EXPECT_EQ(f.theirFrame(1), 103);
  EXPECT_EQ(f.theirFrame(4), std::nullopt);
  f.offset = -1;
  f.edge = scene::FootageEdge::Loop;
  EXPECT_EQ(f.theirFrame(1), 105);
  // The picture that comes back is that frame's.
  f.offset = 0;
  EXPECT_NEAR(f.frame(3, 2, 2).at(1, 1).x, 0.2f, 1e-6f);
}

Image gradient4x3() {
  Image src(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) src.at(x, y) = {0.1f * float(x), 0.1f * float(y), 0.5f, 1.0f};
  return src;
}

TEST(Footage, CropScalePositionFlipAndShiftPlaceTheFrame) {
  FootageSequence f;
  f.images = {gradient4x3()};
  f.crop = {1, 1, 2, 2};
  f.position = {3, 2};
  Image out = f.frame(1, 8, 6);
  ASSERT_EQ(out.width, 8);
  ASSERT_EQ(out.height, 6);
  expectRgb(out, 3, 2, {0.1f, 0.1f, 0.5f});  // src (1, 1)
  expectRgb(out, 4, 3, {0.2f, 0.2f, 0.5f});  // src (2, 2)
  EXPECT_FLOAT_EQ(out.at(3, 2).w, 1.0f);
  EXPECT_FLOAT_EQ(out.at(2, 2).w, 0.0f);  // left of the footage: nothing
  EXPECT_FLOAT_EQ(out.at(5, 2).w, 0.0f);  // right of it
  EXPECT_FLOAT_EQ(out.at(3, 4).w, 0.0f);  // below it
  // Mirrored: the crop's right column comes first.
  f.flip_x = true;
  expectRgb(f.frame(1, 8, 6), 3, 2, {0.2f, 0.1f, 0.5f});
  f.flip_x = false;
  // A per-frame shift of one of their pixels moves it one of ours at scale 1.
  f.shift_x = {1.0f};
  out = f.frame(1, 8, 6);
  expectRgb(out, 4, 2, {0.1f, 0.1f, 0.5f});
  EXPECT_FLOAT_EQ(out.at(3, 2).w, 0.0f);
  f.shift_x.clear();
  // Enlarged x2: our (3,2) samples the crop at 0.25 (clamped to its first column), (4,3) at 0.75:
  // 0.75 * src(1) + 0.25 * src(2) = 0.125 in x and y.
  f.scale = 2.0f;
  out = f.frame(1, 8, 6);
  expectRgb(out, 3, 2, {0.1f, 0.1f, 0.5f});
  expectRgb(out, 4, 3, {0.125f, 0.125f, 0.5f});
  EXPECT_FLOAT_EQ(out.at(6, 5).w, 1.0f);
  EXPECT_FLOAT_EQ(out.at(7, 5).w, 0.0f);
  // Reduced x0.5: one pixel, the mean of the 2x2 crop: x (0.1+0.2)/2, y likewise.
  f.scale = 0.5f;
  out = f.frame(1, 8, 6);
  expectRgb(out, 3, 2, {0.15f, 0.15f, 0.5f});
  EXPECT_FLOAT_EQ(out.at(4, 2).w, 0.0f);
}

TEST(Footage, BadInputNamesTheField) {
  FootageSequence f;
  f.images = {gradient4x3()};
  f.name = "plate.jpg";
  f.crop = {2, 1, 3, 2};  // 2 + 3 > 4
  std::string e = errorOf([&] { f.frame(1, 8, 6); });
  EXPECT_NE(e.find("plate.jpg: crop: rectangle 2,1,3,2"), std::string::npos) << e;
  EXPECT_NE(e.find("4x3"), std::string::npos) << e;
  e = errorOf([&] { f.validate("B"); });
  EXPECT_NE(e.find("B: crop"), std::string::npos) << e;
  f.crop = {};
  f.rate = 0;
  e = errorOf([&] { f.validate("scenes/x.json: reference"); });
  EXPECT_EQ(e.rfind("scenes/x.json: reference: rate: expected", 0), 0u) << e;
  f.rate = 1;
  f.scale = -1;
  EXPECT_NE(errorOf([&] { f.validate("B"); }).find("B: scale"), std::string::npos);
  EXPECT_NE(errorOf([] { FootageSequence{}.validate("B"); }).find("at least one"), std::string::npos);
}

TEST(Footage, SequencesOnDisk) {
  const fs::path dir = freshDir("sequence");
  for (int f = 3; f <= 5; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "b.%04d.png", f);
    writePng(solid(3, 2, {0.0f, 0.0f, 0.0f, 1.0f}), dir / name);
  }
  writePng(solid(3, 2, {1.0f, 1.0f, 1.0f, 1.0f}), dir / "b.0004.png");  // frame 4 white
  writePng(solid(3, 2, {1.0f, 1.0f, 1.0f, 1.0f}), dir / "b_other.0001.png");
  const FootageSequence seq = openFootage(dir / "b.####.png");
  EXPECT_EQ(seq.first, 3);
  ASSERT_EQ(seq.frameCount(), 3);
  EXPECT_EQ(seq.theirFrame(2), 4);
  EXPECT_NEAR(seq.source(4).at(2, 1).x, 1.0f, 1e-6f);
  EXPECT_NEAR(seq.source(3).at(2, 1).x, 0.0f, 1e-6f);
  EXPECT_EQ(openFootage(dir / "b.%04d.png").frameCount(), 3);
  // A gap in the middle is an error naming the missing frame; nothing matching, too.
  writePng(solid(3, 2, {0, 0, 0, 1}), dir / "b.0007.png");
  std::string e = errorOf([&] { openFootage(dir / "b.####.png"); });
  EXPECT_NE(e.find("frame 6 is missing"), std::string::npos) << e;
  e = errorOf([&] { openFootage(dir / "nothing.####.png"); });
  EXPECT_NE(e.find("no frames match"), std::string::npos) << e;
  e = errorOf([&] { openFootage(std::vector<fs::path>{dir / "b.0003.png", dir / "gone.png"}); });
  EXPECT_NE(e.find("gone.png: no such image file"), std::string::npos) << e;
  e = errorOf([&] { readLinearImage(dir / "gone.png"); });
  EXPECT_NE(e.find("gone.png: no such image file"), std::string::npos) << e;
  // sRGB files come back linear: 8-bit 188 is 0.5029 linear.
  writePng(solid(1, 1, {0.5f, 0.5f, 0.5f, 1.0f}), dir / "half.png");
  EXPECT_NEAR(readLinearImage(dir / "half.png").at(0, 0).x, 0.5029f, 0.001f);
}

// --- Plates ----------------------------------------------------------------------------------------

TEST(Footage, LayeredFrameMapsBFromAsFirstFrameAndBlanksMissingFrames) {
  // A numbered 5..7, B 1..2 with edge Blank: A's frame 5 shows B's 1, 6 shows 2, 7 has no B.
  FootageSequence a, b;
  a.first = 5;
  a.images = {solid(2, 1, {0.1f, 0, 0, 1}), solid(2, 1, {0.2f, 0, 0, 1}), solid(2, 1, {0.3f, 0, 0, 1})};
  b.images = {solid(2, 1, {0, 0.5f, 0, 1}), solid(2, 1, {0, 0.7f, 0, 1})};
  b.edge = scene::FootageEdge::Blank;
  LayerStyle s;
  s.mode = scene::LayerMode::Over;
  s.coverage = LayerCoverage::Full;
  s.opacity = 0.5f;
  // Over at full coverage: 0.5 ours + 0.5 other.
  expectRgb(layeredFrame(a, b, 5, s, true, 2, 1), 0, 0, {0.05f, 0.25f, 0.0f});
  expectRgb(layeredFrame(a, b, 6, s, true, 2, 1), 1, 0, {0.10f, 0.35f, 0.0f});
  // Unplaced side by side: B shown as it is; past its end, a blank of the given size.
  LayerStyle side;
  side.labels = false;
  side.gap = 0;
  const Image last = layeredFrame(a, b, 7, side, false, 2, 1);
  ASSERT_EQ(last.width, 4);
  expectRgb(last, 0, 0, {0.3f, 0.0f, 0.0f});
  expectRgb(last, 3, 0, {0.0f, 0.0f, 0.0f});
  const Image first = layeredFrame(a, b, 5, side, false, 2, 1);
  expectRgb(first, 2, 0, {0.0f, 0.5f, 0.0f});
}

TEST(Plate, UniformGridCellsInReadingOrder) {
  // 2 rows x 3 columns of 10x10 cells inside margins left 2, top 1, right 0, bottom 1; each cell's
  // value is its reading-order index / 10.
  Image plate(32, 22);
  for (int y = 0; y < 22; ++y)
    for (int x = 0; x < 32; ++x) {
      const int col = (x - 2) / 10, row = (y - 1) / 10;
      const bool inside = x >= 2 && y >= 1 && y < 21;
      plate.at(x, y) = inside ? glm::vec4(0.1f * float(row * 3 + col), 0, 0, 1) : glm::vec4(1, 1, 1, 1);
    }
  scene::PlateGrid g;
  g.rows = 2;
  g.columns = 3;
  g.margin_left = 2;
  g.margin_top = 1;
  g.margin_bottom = 1;
  g.cell_crop = {1, 1, 8, 7};
  const std::vector<Image> frames = cutPlate(plate, g, "plate.png");
  ASSERT_EQ(frames.size(), 6u);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(frames[i].width, 8);
    EXPECT_EQ(frames[i].height, 7);
    EXPECT_NEAR(frames[i].at(0, 0).x, 0.1f * float(i), 1e-6f) << i;
    EXPECT_NEAR(frames[i].at(7, 6).x, 0.1f * float(i), 1e-6f) << i;
  }
  // No crop: whole cells.
  g.cell_crop = {};
  EXPECT_EQ(cutPlate(plate, g, "plate.png")[5].width, 10);
  // Errors name the grid field.
  g.cell_crop = {5, 5, 8, 8};
  std::string e = errorOf([&] { cutPlate(plate, g, "plate.png"); });
  EXPECT_EQ(e.rfind("plate.png: grid.cell_crop: 5,5,8,8 of cell 3", 0), 0u) << e;
  g.cell_crop = {};
  g.rows = 0;
  e = errorOf([&] { cutPlate(plate, g, "plate.png"); });
  EXPECT_EQ(e.rfind("plate.png: grid.rows: expected an integer >= 1", 0), 0u) << e;
  g.rows = 2;
  g.margin_left = 40;
  EXPECT_NE(errorOf([&] { cutPlate(plate, g, "plate.png"); }).find("grid.margins"), std::string::npos);
}

TEST(Plate, SnapFindsEachPhotographsCorner) {
  // A dark plate with two pale photographs off the nominal grid: [3, 47] and [56, 98] across, [2, 37] down.
  Image plate = solid(100, 40, {0.01f, 0.01f, 0.01f, 1.0f});
  for (int y = 2; y <= 37; ++y) {
    for (int x = 3; x <= 47; ++x) plate.at(x, y) = {0.6f, 0.6f, 0.6f, 1};
    for (int x = 56; x <= 98; ++x) plate.at(x, y) = {0.7f, 0.7f, 0.7f, 1};
  }
  plate.at(3, 2) = {0.9f, 0.0f, 0.0f, 1};   // markers at the photographs' corners
  plate.at(56, 2) = {0.0f, 0.9f, 0.0f, 1};
  scene::PlateGrid g;
  g.columns = 2;
  g.cell_crop = {0, 0, 40, 30};
  std::vector<Image> frames = cutPlate(plate, g, "p");
  expectRgb(frames[1], 0, 0, {0.01f, 0.01f, 0.01f});  // nominal x 50: the gutter
  g.snap = true;
  frames = cutPlate(plate, g, "p");
  ASSERT_EQ(frames.size(), 2u);
  expectRgb(frames[0], 0, 0, {0.9f, 0.0f, 0.0f});
  expectRgb(frames[1], 0, 0, {0.0f, 0.9f, 0.0f});
}

fs::path sharedDir() { return fs::path(STIRRUP_SHARED_DIR); }

TEST(Plate, MuybridgeHorseAndRiderGallopIsTwelveFrames) {
  const fs::path plate = sharedDir() / "reference/muybridge/horse-and-rider-gallop-plate.jpg";
  if (!fs::exists(plate)) GTEST_SKIP() << plate << " is absent (../shared/reference)";
  // The scene's own grid, so the test checks what the movies use.
  const scene::SceneSpec scene = scene::loadScene(fs::path(STIRRUP_SOURCE_DIR) / "scenes/gallop_layered.json");
  ASSERT_TRUE(scene.reference.has_value());
  ASSERT_TRUE(scene.reference->grid.has_value());
  const Image img = readLinearImage(plate);
  ASSERT_EQ(img.width, 2872);
  ASSERT_EQ(img.height, 1008);
  const std::vector<Image> frames = cutPlate(img, *scene.reference->grid, plate.string());
  ASSERT_EQ(frames.size(), 12u);
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].width, 446) << i;
    EXPECT_EQ(frames[i].height, 422) << i;
    // Snapped inside the photograph: the left and top edges are the pale wall, not the plate's dark
    // border (mean sRGB well above the border's ~0.05).
    double left = 0, top = 0;
    for (int y = 0; y < frames[i].height / 2; ++y) left += linearToSrgb(frames[i].at(1, y).y);
    for (int x = 0; x < frames[i].width; ++x) top += linearToSrgb(frames[i].at(x, 1).y);
    EXPECT_GT(left / (frames[i].height / 2), 0.35) << "frame " << i + 1 << " left edge is dark";
    EXPECT_GT(top / frames[i].width, 0.25) << "frame " << i + 1 << " top edge is dark";
  }
  // The frames differ (the horse moves) and the sequence maps our frame 1 to plate frame 9.
  const FootageSequence seq = openReference(*scene.reference, "gallop_layered");
  EXPECT_EQ(seq.frameCount(), 12);
  EXPECT_EQ(seq.theirFrame(1), 9);
  EXPECT_EQ(seq.theirFrame(5), 1);
  EXPECT_EQ(seq.theirFrame(13), 9);  // one stride later, the same
  const Image canvas = seq.frame(1, scene.width, scene.height);
  EXPECT_EQ(canvas.width, 640);
  EXPECT_EQ(canvas.height, 360);
}

// --- The footage a scene's reference block names -------------------------------------------------------------------

TEST(ReferenceBlock, StyleAndAvailabilityFollowTheBlock) {
  scene::ReferenceSpec r;
  r.file = "/nonexistent/plates/p.jpg";
  r.mode = scene::LayerMode::SideBySide;
  r.label = "PLATE";
  EXPECT_FALSE(referenceAvailable(r));
  const LayerStyle style = referenceStyle(r, "OURS");
  EXPECT_EQ(style.mode, scene::LayerMode::SideBySide);
  EXPECT_EQ(style.other_label, "PLATE");
  EXPECT_EQ(style.ours_label, "OURS");
}

TEST(ReferenceBlock, ShiftCountMustMatchTheFootage) {
  const fs::path dir = freshDir("shifts");
  writePng(solid(4, 4, {1, 1, 1, 1}), dir / "one.png");
  scene::ReferenceSpec r;
  r.file = dir / "one.png";
  EXPECT_TRUE(referenceAvailable(r));
  r.shift_x = {1.0f, 2.0f};
  const std::string e = errorOf([&] { openReference(r, "s.json: reference"); });
  EXPECT_EQ(e.rfind("s.json: reference: shift_x: expected one shift per footage frame (1), got 2", 0), 0u) << e;
  r.crop = {2, 2, 4, 4};
  r.shift_x.clear();
  EXPECT_NE(errorOf([&] { openReference(r, "s.json: reference"); }).find("s.json: reference: crop"), std::string::npos);
}

}  // namespace
}  // namespace stirrup::render
