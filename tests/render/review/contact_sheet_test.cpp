#include "render/review/contact_sheet.h"

#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

TEST(ContactFrames, EvenlySpacedWithFirstAndLast) {
  std::vector<int> frames;
  for (int f = 1; f <= 100; ++f) frames.push_back(f);
  EXPECT_EQ(contactFrames(frames, 4), (std::vector<int>{1, 34, 67, 100}));
  EXPECT_EQ(contactFrames({5, 7, 9}, 12), (std::vector<int>{5, 7, 9}));
  EXPECT_TRUE(contactFrames(frames, 0).empty());
}

TEST(ContactSheet, LaysFramesOutInAGridOfThumbnails) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_contact_sheet";
  fs::remove_all(dir);
  std::vector<ContactFrame> frames;
  for (int i = 0; i < 5; ++i) {
    ContactFrame f{i + 1, Image(160, 90)};
    // Linear 0.2 * i in red: the thumbnails must carry the colour to their place in the grid.
    for (glm::vec4& p : f.image.rgba) p = glm::vec4(0.2f * float(i), 0.0f, 0.0f, 1.0f);
    frames.push_back(std::move(f));
  }
  const fs::path file = dir / "sheet.png";
  writeContactSheet("test", frames, file, 3, 100);
  ASSERT_TRUE(fs::exists(file));
  OIIO::ImageBuf sheet(file.string());
  ASSERT_TRUE(sheet.read());
  // 3 columns of 100 px with 10 px gaps; 2 rows of 56 px thumbnails (100 * 90 / 160 = 56.25).
  EXPECT_EQ(sheet.spec().width, 3 * 100 + 4 * 10);
  for (int i = 0; i < 5; ++i) {
    const int col = i % 3, row = i / 3;
    const int x = 10 + col * 110 + 50, y = 40 + row * (56 + 24 + 10) + 28;
    float px[3];
    sheet.getpixel(x, y, px, 3);
    EXPECT_NEAR(px[0], linearToSrgb(0.2f * float(i)), 1.0 / 255 + 1e-6) << "frame " << i + 1;
    EXPECT_NEAR(px[1], 0.0f, 1e-6);
  }
}

}  // namespace
}  // namespace stirrup::render
