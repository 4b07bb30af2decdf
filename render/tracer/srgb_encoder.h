// 8-bit sRGB codes of linear values, exactly linearToSrgb8's (render/tracer/image.h) without a pow per
// value: the review PNGs and the movies' frames are encoded by it on the writer's thread, beside the
// tracer on the same cores, so its time is taken from the trace (docs/performance-history.md, "The frames' write").
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace stirrup::render {

// The tables behind the encoding. linearToSrgb8 is monotonic, so it is fixed by the 255 inputs at which
// it steps up: step[k] is the smallest float whose code is k, found once by bisection over the bit
// patterns of the floats in [0, 1] (ordered like the integers for non-negative floats). A value's code
// is then its 4096-bin table entry over [0, 1] plus one comparison with the next step: sRGB's steepest
// slope (its linear toe, 12.92 x 255 codes a unit) crosses 0.8 of a code in a bin, so a bin holds at
// most one step (checked when the tables are made).
class SrgbTables {
 public:
  static constexpr int kBins = 4096;
  static const SrgbTables& get();  // made once, on first use

  // The code of one value: 0 for NaN and anything <= 0, 255 from 1 up.
  uint8_t code(float v) const {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    const int32_t k = bin_code[std::size_t(std::min(int(v * float(kBins)), kBins - 1))];
    return uint8_t(k + int32_t(v >= step[std::size_t(k) + 1]));
  }

  std::array<float, 257> step{};         // step[256] = infinity: no code past 255
  std::array<int32_t, kBins> bin_code{};  // the code at each bin's start
  // What the SIMD lanes gather, one 64-bit entry a bin: its code (low half) and the bits of the step
  // after it (high half), so a value costs one gathered element, not two.
  std::array<uint64_t, kBins> bin_entry{};

 private:
  SrgbTables();
};

// The codes of the R, G and B of `pixels` RGBA pixels (4 floats each; alpha is not coded), 3 bytes a
// pixel: rgb[3p + c] = linearToSrgb8(rgba[4p + c]), in SIMD lanes (Highway, the best target this CPU has).
void srgbCodesRgb(const float* rgba, uint8_t* rgb, std::size_t pixels);

}  // namespace stirrup::render
