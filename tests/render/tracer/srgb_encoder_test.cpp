// The sRGB encoder's tables and SIMD lanes against linearToSrgb8's formula, on every instruction set this
// CPU runs, at every length a run's tail can have.
#include "render/tracer/srgb_encoder.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "render/tracer/image.h"
#include "render/tracer/sample_lanes.h"  // simdTargets, pinSimdTarget

namespace stirrup::render {
namespace {

// Values that try the encoder: the specials, an even sweep of [0, 1], and the floats either side of each
// step (where one wrong comparison would change a code).
std::vector<float> trialValues() {
  std::vector<float> values = {0.0f, -0.0f, -1.0f, 1.0f, 1.5f, 0.0031308f, 0.5f, 0.18f,
                               std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min(),
                               std::nextafter(1.0f, 0.0f)};
  const uint32_t one = std::bit_cast<uint32_t>(1.0f);
  for (uint32_t bits = 0; bits <= one; bits += 4099) values.push_back(std::bit_cast<float>(bits));
  const SrgbTables& tables = SrgbTables::get();
  for (int k = 1; k < 256; ++k) {
    const float step = tables.step[std::size_t(k)];
    values.push_back(std::nextafter(step, 0.0f));
    values.push_back(step);
    values.push_back(std::nextafter(step, 2.0f));
  }
  return values;
}

TEST(SrgbEncoder, TheStepsAreWhereTheFormulaStepsUp) {
  const SrgbTables& tables = SrgbTables::get();
  for (int k = 1; k < 256; ++k) {
    const float step = tables.step[std::size_t(k)];
    EXPECT_EQ(linearToSrgb8(step), k) << "step " << k;
    EXPECT_EQ(linearToSrgb8(std::nextafter(step, 0.0f)), k - 1) << "below step " << k;
  }
  EXPECT_EQ(tables.step[256], std::numeric_limits<float>::infinity());
  // Each step is where the code's half-way value decodes to, by sRGB's inverse (IEC 61966-2-1) in doubles.
  for (int k = 1; k < 256; ++k) {
    const double s = (k - 0.5) / 255.0;
    const double linear = s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
    EXPECT_NEAR(tables.step[std::size_t(k)], linear, 2e-6 * linear + 1e-9) << "step " << k;
  }
}

TEST(SrgbEncoder, OneCodeAtATimeMatchesTheFormula) {
  const SrgbTables& tables = SrgbTables::get();
  for (const float v : trialValues()) EXPECT_EQ(tables.code(v), linearToSrgb8(v)) << "value " << v;
}

TEST(SrgbEncoder, TheLanesMatchTheFormulaOnEveryTargetAndTail) {
  // The trial values as the RGB of pixels whose alpha is a value that would code otherwise (0.5: 188),
  // so a lane that coded alpha into the bytes would show.
  const std::vector<float> values = trialValues();
  const std::size_t pixels = values.size() / 3;
  std::vector<float> rgba(4 * pixels);
  std::vector<uint8_t> expected(3 * pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (std::size_t c = 0; c < 3; ++c) {
      rgba[4 * p + c] = values[3 * p + c];
      expected[3 * p + c] = linearToSrgb8(values[3 * p + c]);
    }
    rgba[4 * p + 3] = 0.5f;
  }
  const std::vector<std::string> targets = simdTargets();
  ASSERT_FALSE(targets.empty());
  for (const std::string& target : targets) {
    pinSimdTarget(target);
    std::vector<uint8_t> codes(3 * pixels, 7);
    srgbCodesRgb(rgba.data(), codes.data(), pixels);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < codes.size(); ++i)
      if (codes[i] != expected[i] && ++wrong <= 3)
        ADD_FAILURE() << target << ": value " << values[i] << " coded " << int(codes[i]) << ", formula " << int(expected[i]);
    EXPECT_EQ(wrong, 0u) << target << ", of " << codes.size();
    // Every short run (the vector's tail done one by one), and nothing written past it.
    for (std::size_t n = 0; n <= 40; ++n) {
      std::vector<uint8_t> some(3 * n + 1, 7);
      srgbCodesRgb(rgba.data() + 4 * 300, some.data(), n);
      for (std::size_t i = 0; i < 3 * n; ++i) ASSERT_EQ(some[i], expected[3 * 300 + i]) << target << ", n " << n << ", i " << i;
      ASSERT_EQ(some[3 * n], 7) << target << ": wrote past " << n << " pixels";
    }
  }
  pinSimdTarget("best");
}

}  // namespace
}  // namespace stirrup::render
