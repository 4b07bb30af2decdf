// Base colour textures: the sRGB transfer undone, the three glTF wraps on texel indices, and lookups
// (nearest and bilinear) at hand-placed texture coordinates of a 2 x 2 image.
#include "rig/texture.h"

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// IEC 61966-2-1 at a few codes, worked by hand: code / 255 below 0.04045 is divided by 12.92, above it
// is ((c + 0.055) / 1.055)^2.4 (128 -> 0.2158605, 188 -> 0.5028865, the standard table's values).
TEST(Texture, SrgbCodesDecodeToTheStandardsLinearValues) {
  const std::vector<float>& table = srgb8ToLinearTable();
  ASSERT_EQ(table.size(), 256u);
  EXPECT_EQ(table[0], 0.0f);
  EXPECT_EQ(table[255], 1.0f);
  EXPECT_NEAR(table[10], 10.0 / 255.0 / 12.92, 1e-9);  // 0.0030353: on the linear segment
  EXPECT_NEAR(table[128], 0.2158605, 1e-6);
  EXPECT_NEAR(table[188], 0.5028865, 1e-6);
  EXPECT_NEAR(srgbToLinear(0.04045), 0.04045 / 12.92, 1e-12);  // the segments meet here
  EXPECT_NEAR(srgbToLinear(0.5), 0.2140411, 1e-6);
}

TEST(Texture, WrapsFoldTexelIndicesAsGltfSays) {
  // Four texels: 0 1 2 3.
  const std::vector<std::pair<std::int64_t, std::int64_t>> repeat = {{-1, 3}, {-4, 0}, {4, 0}, {5, 1}, {-5, 3}, {2, 2}};
  for (const auto& [i, want] : repeat) EXPECT_EQ(wrapTexel(i, 4, TextureWrap::Repeat), want) << i;
  const std::vector<std::pair<std::int64_t, std::int64_t>> clamp = {{-1, 0}, {-100, 0}, {4, 3}, {100, 3}, {1, 1}};
  for (const auto& [i, want] : clamp) EXPECT_EQ(wrapTexel(i, 4, TextureWrap::ClampToEdge), want) << i;
  // Mirrored: ... 1 0 | 0 1 2 3 | 3 2 1 0 | 0 1 ...
  const std::vector<std::pair<std::int64_t, std::int64_t>> mirror = {{-1, 0}, {-2, 1}, {-4, 3}, {-5, 3}, {4, 3},
                                                                     {5, 2},  {7, 0},  {8, 0},  {9, 1},  {3, 3}};
  for (const auto& [i, want] : mirror) EXPECT_EQ(wrapTexel(i, 4, TextureWrap::MirroredRepeat), want) << i;
}

// A 2 x 2 image: red, green on the top row; blue, white below.
Texture twoByTwo(TextureFilter filter, TextureWrap s, TextureWrap t) {
  Texture tex;
  tex.width = tex.height = 2;
  tex.texels = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  tex.filter = filter;
  tex.wrap_s = s;
  tex.wrap_t = t;
  return tex;
}

TEST(Texture, NearestReadsTheTexelUnderThePoint) {
  const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1, 1, 1);
  const Texture r = twoByTwo(TextureFilter::Nearest, TextureWrap::Repeat, TextureWrap::Repeat);
  EXPECT_EQ(r.sample({0.25f, 0.25f}), red);  // (0, 0) is the image's top-left
  EXPECT_EQ(r.sample({0.75f, 0.25f}), green);
  EXPECT_EQ(r.sample({0.25f, 0.75f}), blue);
  EXPECT_EQ(r.sample({0.99f, 0.99f}), white);
  EXPECT_EQ(r.sample({1.25f, 0.25f}), red);    // repeat: texel 2 is texel 0
  EXPECT_EQ(r.sample({-0.25f, 0.25f}), green); // texel -1 is texel 1
  EXPECT_EQ(r.sample({1000.25f, -7.75f}), red);
  const Texture c = twoByTwo(TextureFilter::Nearest, TextureWrap::ClampToEdge, TextureWrap::ClampToEdge);
  EXPECT_EQ(c.sample({1.25f, 0.25f}), green);  // past the right edge: the last column
  EXPECT_EQ(c.sample({-3.0f, 5.0f}), blue);
  const Texture m = twoByTwo(TextureFilter::Nearest, TextureWrap::MirroredRepeat, TextureWrap::Repeat);
  EXPECT_EQ(m.sample({1.25f, 0.25f}), green);  // texel 2 mirrors to texel 1
  EXPECT_EQ(m.sample({1.75f, 0.25f}), red);    // texel 3 mirrors to texel 0
  EXPECT_EQ(m.sample({2.25f, 0.25f}), red);    // the next period reads forward again
}

TEST(Texture, BilinearBlendsTheFourNearestTexelCentres) {
  const Texture r = twoByTwo(TextureFilter::Linear, TextureWrap::Repeat, TextureWrap::Repeat);
  // At a texel centre: that texel alone.
  EXPECT_EQ(r.sample({0.25f, 0.25f}), glm::vec3(1, 0, 0));
  EXPECT_EQ(r.sample({0.75f, 0.75f}), glm::vec3(1, 1, 1));
  // Halfway between the top row's centres: half red, half green.
  const glm::vec3 mid = r.sample({0.5f, 0.25f});
  EXPECT_NEAR(mid.x, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.y, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.z, 0.0f, 1e-6f);
  // The image's centre: the mean of all four, (0.5, 0.5, 0.5).
  const glm::vec3 centre = r.sample({0.5f, 0.5f});
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(centre[k], 0.5f, 1e-6f);
  // A quarter of the way from red's centre to green's: 3/4 red, 1/4 green.
  const glm::vec3 quarter = r.sample({0.375f, 0.25f});
  EXPECT_NEAR(quarter.x, 0.75f, 1e-6f);
  EXPECT_NEAR(quarter.y, 0.25f, 1e-6f);
  // On the left edge the neighbour is the wrapped texel: repeat blends with green, clamp keeps red.
  const glm::vec3 edge = r.sample({0.0f, 0.25f});
  EXPECT_NEAR(edge.x, 0.5f, 1e-6f);
  EXPECT_NEAR(edge.y, 0.5f, 1e-6f);
  const Texture c = twoByTwo(TextureFilter::Linear, TextureWrap::ClampToEdge, TextureWrap::ClampToEdge);
  EXPECT_EQ(c.sample({0.0f, 0.25f}), glm::vec3(1, 0, 0));
  EXPECT_EQ(c.sample({-2.0f, -2.0f}), glm::vec3(1, 0, 0));
}

}  // namespace
}  // namespace stirrup::rig
