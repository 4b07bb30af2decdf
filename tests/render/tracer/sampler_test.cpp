#include "render/tracer/sampler.h"

#include <algorithm>
#include <array>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

TEST(Sampler, SameCoordinatesGiveTheSameNumbers) {
  const PixelSampler a(12, 34, 5), b(12, 34, 5);
  for (uint32_t s = 0; s < 64; ++s) {
    EXPECT_EQ(a.uniform(s, SampleDimension::SunCone, 1), b.uniform(s, SampleDimension::SunCone, 1));
    EXPECT_EQ(a.stratified2D(s, 64, SampleDimension::SkyHemisphere), b.stratified2D(s, 64, SampleDimension::SkyHemisphere));
  }
  EXPECT_EQ(hashSample(1, 2, 3, 4, 5), hashSample(1, 2, 3, 4, 5));
}

// A PixelSampler's numbers are the five-coordinate hash's, written out here round by round from
// MurmurHash3's finalizer: every golden image rests on this sequence, so a faster sampler must keep it.
TEST(Sampler, ThePixelsNumbersAreTheFiveCoordinateHash) {
  auto mix = [](uint64_t v) {
    v = (v ^ (v >> 33)) * 0xff51afd7ed558ccdull;
    v = (v ^ (v >> 33)) * 0xc4ceb9fe1a85ec53ull;
    return v ^ (v >> 33);
  };
  auto hash = [&](uint32_t x, uint32_t y, uint32_t frame, uint32_t sample, uint32_t dim) {
    const uint64_t h = mix(mix((uint64_t(x) << 32 | y) ^ 0x9e3779b97f4a7c15ull) ^ (uint64_t(frame) << 32 | dim));
    return mix(h ^ (uint64_t(sample) * 0xd1b54a32d192ed03ull));
  };
  for (const auto& [x, y, frame] : {std::array<int, 3>{0, 0, 1}, {639, 359, 72}, {-5, 12, 0}, {17, 3, 1000}}) {
    const PixelSampler p(x, y, frame);
    const auto ux = uint32_t(x), uy = uint32_t(y), uf = uint32_t(frame);
    for (uint32_t s : {0u, 1u, 15u, 0xfffffffeu}) {
      for (auto dim : {SampleDimension::PixelFilter, SampleDimension::SunCone, SampleDimension::SkyHemisphere}) {
        const uint32_t d = uint32_t(dim);
        EXPECT_EQ(hashSample(ux, uy, uf, s, d * 4 + 1), hash(ux, uy, uf, s, d * 4 + 1));
        EXPECT_EQ(p.uniform(s, dim, 1), float(hash(ux, uy, uf, s, d * 4 + 1) >> 40) * 0x1p-24f);
        const uint64_t h2 = hash(ux, uy, uf, s, d * 4 + 3);
        EXPECT_EQ(p.uniform2D(s, dim), glm::vec2(float(h2 >> 40) * 0x1p-24f, float((h2 >> 8) & 0xffffff) * 0x1p-24f));
        EXPECT_EQ(p.seed(dim), uint32_t(hash(ux, uy, uf, 0xffffffffu, d)));
      }
    }
  }
}

TEST(Sampler, EveryCoordinateChangesTheHash) {
  const uint64_t base = hashSample(1, 2, 3, 4, 5);
  EXPECT_NE(base, hashSample(2, 2, 3, 4, 5));
  EXPECT_NE(base, hashSample(1, 3, 3, 4, 5));
  EXPECT_NE(base, hashSample(1, 2, 4, 4, 5));
  EXPECT_NE(base, hashSample(1, 2, 3, 5, 5));
  EXPECT_NE(base, hashSample(1, 2, 3, 4, 6));
  EXPECT_NE(hashSample(1, 2, 0, 0, 0), hashSample(2, 1, 0, 0, 0));  // x and y do not commute
}

TEST(Sampler, UniformNumbersAreInRangeWithTheRightMean) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const PixelSampler p(x, y, 7);
      for (uint32_t s = 0; s < 16; ++s) {
        const float u = p.uniform(s, SampleDimension::PixelFilter);
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        sum += u;
        ++n;
      }
    }
  }
  EXPECT_NEAR(sum / n, 0.5, 0.01);
}

TEST(Sampler, FastModIsTheRemainder) {
  uint64_t state = 12345;
  auto next = [&] { return uint32_t((state = mixBits(state + 0x9e3779b97f4a7c15ull)) >> 32); };
  int wrong = 0;
  for (uint32_t d = 1; d <= 4100; ++d) {
    const uint64_t m = fastModMultiplier(d);
    for (uint32_t a : {0u, 1u, d - 1, d, d + 1, 0xffffffffu, 0xfffffffeu, next(), next(), next()})
      wrong += fastMod(a, d, m) != a % d;
  }
  for (int k = 0; k < 20000; ++k) {
    const uint32_t d = next() | 1u, a = next();
    wrong += fastMod(a, d, fastModMultiplier(d)) != a % d;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(Sampler, PermutationIsABijection) {
  for (uint32_t count : {1u, 2u, 7u, 16u, 64u, 100u}) {
    std::set<uint32_t> seen;
    for (uint32_t i = 0; i < count; ++i) seen.insert(permuteIndex(i, count, 0x1234567u));
    EXPECT_EQ(seen.size(), count);
    EXPECT_LT(*seen.rbegin(), count);
  }
}

// A square count puts exactly one point in every cell of the sqrt x sqrt grid.
TEST(Sampler, SquareCountsAreGridStratified) {
  const PixelSampler p(3, 9, 1);
  for (uint32_t side : {2u, 4u, 8u}) {
    const uint32_t count = side * side;
    std::vector<int> cells(count, 0);
    for (uint32_t i = 0; i < count; ++i) {
      const glm::vec2 u = p.stratified2D(i, count, SampleDimension::PixelFilter);
      ASSERT_GE(u.x, 0.0f);
      ASSERT_LT(u.x, 1.0f);
      ASSERT_GE(u.y, 0.0f);
      ASSERT_LT(u.y, 1.0f);
      ++cells[uint32_t(u.y * side) * side + uint32_t(u.x * side)];
    }
    EXPECT_TRUE(std::all_of(cells.begin(), cells.end(), [](int c) { return c == 1; })) << count;
  }
}

// Any other count is a Latin hypercube: one point in every column and every row.
TEST(Sampler, OtherCountsAreLatinHypercubes) {
  const PixelSampler p(5, 6, 2);
  const uint32_t count = 12;
  std::vector<int> cols(count, 0), rows(count, 0);
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec2 u = p.stratified2D(i, count, SampleDimension::SunCone);
    ++cols[uint32_t(u.x * count)];
    ++rows[uint32_t(u.y * count)];
  }
  EXPECT_TRUE(std::all_of(cols.begin(), cols.end(), [](int c) { return c == 1; }));
  EXPECT_TRUE(std::all_of(rows.begin(), rows.end(), [](int c) { return c == 1; }));
}

TEST(Sampler, PixelsAndFramesGetDifferentPatterns) {
  const PixelSampler a(0, 0, 1), b(1, 0, 1), c(0, 0, 2);
  int same_pixel = 0, same_frame = 0;
  for (uint32_t i = 0; i < 16; ++i) {
    same_pixel += a.stratified2D(i, 16, SampleDimension::PixelFilter) == b.stratified2D(i, 16, SampleDimension::PixelFilter);
    same_frame += a.stratified2D(i, 16, SampleDimension::PixelFilter) == c.stratified2D(i, 16, SampleDimension::PixelFilter);
  }
  EXPECT_EQ(same_pixel, 0);
  EXPECT_EQ(same_frame, 0);
}

}  // namespace
}  // namespace stirrup::render
