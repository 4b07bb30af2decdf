// Deterministic per-pixel random numbers. Every value is a pure hash of (pixel x, y, frame, sample
// index, dimension), never a shared generator or the clock, so a pixel's samples do not depend on
// which thread renders it, on the tile order or on the thread count (pbrt-v4 keys its
// IndependentSampler to the pixel the same way; the frame is hashed in so the noise moves with time).
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>

namespace stirrup::render {

// The dimensions a camera sample consumes. Each gets independent numbers and its own stratification
// permutation, so pixel position, sun direction and sky direction are decorrelated.
enum class SampleDimension : uint32_t {
  PixelFilter = 0,  // position in the pixel (through the reconstruction filter)
  SunCone = 1,      // direction within the sun's disc
  SkyHemisphere = 2 // cosine-weighted sky (ambient occlusion) direction
};

// MurmurHash3's 64-bit finalizer: every input bit affects every output bit.
constexpr uint64_t mixBits(uint64_t v) {
  v ^= v >> 33;
  v *= 0xff51afd7ed558ccdull;
  v ^= v >> 33;
  v *= 0xc4ceb9fe1a85ec53ull;
  v ^= v >> 33;
  return v;
}

// A hash of all five coordinates; chained so that (1, 2) and (2, 1) differ. The first two rounds
// depend on the pixel, frame and dimension only, so a pixel's sequence hashes them once
// (hashPixel) and each sample costs one round (hashSampleOf).
constexpr uint64_t hashPixel(uint32_t x, uint32_t y, uint32_t frame, uint32_t dim) {
  const uint64_t h = mixBits((uint64_t(x) << 32 | y) ^ 0x9e3779b97f4a7c15ull);
  return mixBits(h ^ (uint64_t(frame) << 32 | dim));
}
constexpr uint64_t hashSampleOf(uint64_t pixel_hash, uint32_t sample) {
  return mixBits(pixel_hash ^ (uint64_t(sample) * 0xd1b54a32d192ed03ull));
}
constexpr uint64_t hashSample(uint32_t x, uint32_t y, uint32_t frame, uint32_t sample, uint32_t dim) {
  return hashSampleOf(hashPixel(x, y, frame, dim), sample);
}

// The top 24 bits as a float in [0, 1): exactly representable, so never rounds up to 1.
constexpr float unitFloat(uint64_t bits) { return float(bits >> 40) * 0x1p-24f; }

// Kensler's hashed permutation ("Correlated Multi-Jittered Sampling", 2013): a bijection of
// [0, count) chosen by `seed`, computed without tables (no allocation per pixel). `mask` is the
// smallest 2^k - 1 >= count - 1 and `offset` is seed % count: both fixed per sequence, so callers that
// permute many indices compute them once (integer division is the slow part).
constexpr uint32_t permutationMask(uint32_t count) {
  uint32_t w = count > 0 ? count - 1 : 0;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  return w;
}

constexpr uint32_t permuteIndex(uint32_t i, uint32_t count, uint32_t seed, uint32_t mask, uint32_t offset) {
  if (count <= 1) return 0;
  const uint32_t w = mask;
  do {
    i ^= seed;
    i *= 0xe170893d;
    i ^= seed >> 16;
    i ^= (i & w) >> 4;
    i ^= seed >> 8;
    i *= 0x0929eb3f;
    i ^= seed >> 23;
    i ^= (i & w) >> 1;
    i *= 1 | seed >> 27;
    i *= 0x6935fa69;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3;
    i ^= (i & w) >> 2;
    i *= 0xc860a3df;
    i &= w;
    i ^= i >> 5;
  } while (i >= count);
  const uint32_t r = i + offset;  // (i + seed) % count, with i, offset < count
  return r >= count ? r - count : r;
}

// a % d by a multiply and a shift (Lemire, Kaser and Kurz, "Faster Remainder by Direct Computation",
// 2019): exact for every 32-bit a and d >= 1, with m = fastModMultiplier(d) worked out once per d. The
// divisions of a pixel's sequence set-up were a visible part of the per-sample time.
__extension__ using Uint128 = unsigned __int128;  // (GCC and Clang; __extension__ keeps -Wpedantic quiet)
constexpr uint64_t fastModMultiplier(uint32_t d) { return d > 0 ? UINT64_C(0xFFFFFFFFFFFFFFFF) / d + 1 : 0; }
constexpr uint32_t fastMod(uint32_t a, uint32_t d, uint64_t m) {
  return uint32_t((static_cast<Uint128>(m * a) * d) >> 64);
}

constexpr uint32_t permuteIndex(uint32_t i, uint32_t count, uint32_t seed) {
  return count <= 1 ? 0 : permuteIndex(i, count, seed, permutationMask(count), seed % count);
}

// The random numbers of one pixel of one frame.
class PixelSampler {
 public:
  constexpr PixelSampler(int x, int y, int frame)
      : x_(uint32_t(x)), y_(uint32_t(y)), frame_(uint32_t(frame)) {}

  // An independent uniform number in [0, 1) for (sample, dimension, component).
  constexpr float uniform(uint32_t sample, SampleDimension dim, uint32_t component = 0) const {
    return unitFloat(hashSample(x_, y_, frame_, sample, uint32_t(dim) * 4 + component));
  }
  // Two independent uniform numbers from one hash (the top and the next 24 bits).
  constexpr glm::vec2 uniform2D(uint32_t sample, SampleDimension dim) const {
    return split2D(hashSample(x_, y_, frame_, sample, uint32_t(dim) * 4 + 3));
  }
  // A per-pixel seed for the stratification permutations of a dimension.
  constexpr uint32_t seed(SampleDimension dim) const {
    return uint32_t(hashSample(x_, y_, frame_, 0xffffffffu, uint32_t(dim)));
  }

  // Sample `index` of `count` stratified points in [0, 1)^2 (see Stratified2D).
  glm::vec2 stratified2D(uint32_t index, uint32_t count, SampleDimension dim) const;

  // The pixel part of uniform2D's hash for a dimension: uniform2D(i, dim) is split(hashSampleOf(it, i)).
  constexpr uint64_t pixelHash2D(SampleDimension dim) const {
    return hashPixel(x_, y_, frame_, uint32_t(dim) * 4 + 3);
  }
  static constexpr glm::vec2 split2D(uint64_t h) { return {unitFloat(h), float((h >> 8) & 0xffffffu) * 0x1p-24f}; }

 private:
  uint32_t x_, y_, frame_;
};

// `count` stratified points in [0, 1)^2 for one pixel and dimension. A square count is jittered on a
// sqrt x sqrt grid; any other count is Latin-hypercube stratified (one point in every row and every
// column). The index is shuffled by a per-pixel permutation first, so sample i of one dimension is
// not tied to cell i of another. Set up once per pixel and dimension; each point is then a
// permutation and one hash.
class Stratified2D {
 public:
  // What depends on the count only (the grid's side, the permutation's mask): worked out once per
  // frame for each count, so setting up a pixel's sequence costs hashes and no square roots.
  struct Layout {
    explicit Layout(uint32_t count)
        : count(count),
          mask(permutationMask(count)),
          mod_multiplier(fastModMultiplier(count)),
          inv_count(count > 0 ? 1.0f / float(count) : 0.0f) {
      const auto s = uint32_t(std::lround(std::sqrt(double(count))));
      side = s * s == count ? s : 0;
      inv_side = side ? 1.0f / float(side) : 0.0f;
      side_shift = 0;
      while (side && (1u << side_shift) < side) ++side_shift;
      if (side && (1u << side_shift) != side) side_shift = -1;  // not a power of two: divide
    }
    uint32_t count, mask;
    uint64_t mod_multiplier;  // fastMod by count
    float inv_count;
    uint32_t side;
    float inv_side;
    int side_shift;
  };

  Stratified2D() = default;  // no points; assign a real sequence before use
  Stratified2D(const PixelSampler& sampler, uint32_t count, SampleDimension dim)
      : Stratified2D(sampler, Layout(count), dim) {}
  Stratified2D(const PixelSampler& sampler, const Layout& layout, SampleDimension dim)
      : pixel_hash_(sampler.pixelHash2D(dim)),
        count_(layout.count),
        seed_(layout.count > 1 ? sampler.seed(dim) : 0),  // one point needs no permutation
        row_seed_(seed_ ^ 0x5bd1e995u),
        mask_(layout.mask),
        offset_(layout.count > 1 ? fastMod(seed_, layout.count, layout.mod_multiplier) : 0),
        row_offset_(layout.count > 1 ? fastMod(row_seed_, layout.count, layout.mod_multiplier) : 0),
        inv_count_(layout.inv_count),
        side_(layout.side),
        inv_side_(layout.inv_side),
        side_shift_(layout.side_shift) {}

  // What a sequence holds for its pixel, for the SIMD lanes (render/tracer/sample_lanes.h: stratifiedLanes
  // computes operator[] from these and the Layout, bit for bit).
  struct PixelPart {
    uint64_t pixel_hash;
    uint32_t seed, row_seed, offset, row_offset;
  };
  PixelPart pixelPart() const { return {pixel_hash_, seed_, row_seed_, offset_, row_offset_}; }

  glm::vec2 operator[](uint32_t index) const {
    const uint32_t cell = permuteIndex(index, count_, seed_, mask_, offset_);
    const glm::vec2 j = PixelSampler::split2D(hashSampleOf(pixel_hash_, index));
    if (side_ != 0) {
      const uint32_t row = side_shift_ >= 0 ? cell >> side_shift_ : cell / side_;
      const uint32_t col = cell - row * side_;
      return {belowOne((float(col) + j.x) * inv_side_), belowOne((float(row) + j.y) * inv_side_)};
    }
    const uint32_t row = permuteIndex(cell, count_, row_seed_, mask_, row_offset_);
    return {belowOne((float(cell) + j.x) * inv_count_), belowOne((float(row) + j.y) * inv_count_)};
  }

 private:
  // (cell + jitter) / n can round up to exactly 1 in float; keep the half-open range.
  static constexpr float belowOne(float v) { return v < 0x1.fffffep-1f ? v : 0x1.fffffep-1f; }

  uint64_t pixel_hash_ = 0;  // hashed once per pixel and dimension
  uint32_t count_ = 0, seed_ = 0, row_seed_ = 0, mask_ = 0, offset_ = 0, row_offset_ = 0;
  float inv_count_ = 0.0f;
  uint32_t side_ = 0;
  float inv_side_ = 0.0f;
  int side_shift_ = 0;
};

inline glm::vec2 PixelSampler::stratified2D(uint32_t index, uint32_t count, SampleDimension dim) const {
  return Stratified2D(*this, count, dim)[index];
}

}  // namespace stirrup::render
