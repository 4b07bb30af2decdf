// Shared by the golden-image tests: the thresholds, the comparison with a reference, and the HTML
// report written next to the new image when a comparison fails.
#pragma once

#include <filesystem>
#include <string>

#include "render/image_diff.h"

namespace stirrup::test {

inline const std::filesystem::path kGoldenDir = std::filesystem::path(STIRRUP_SOURCE_DIR) / "tests/golden";

// The golden frames of tests/golden/trot_side.json (scripts/update-goldens renders the same list).
// Frame 4: the diagonal pairs spread wide and the rider lifted; frame 9: the pairs passing, the
// rider sunk back into the saddle.
inline constexpr int kGoldenFrames[] = {4, 9};

// Rendering is byte-deterministic (the measured difference is 0 at every thread count), so the
// tolerance only has to absorb another CPU's floating-point paths: a handful of isolated pixels.
// A pixel fails when a channel is off by more than 4/255 (Blender's per-pixel threshold); the
// comparison fails when more than 0.01% of the pixels (5 of 320x180) fail. Blender's 0.5% (288
// pixels) let a 10% change of the Equation 1, 4 or 10 weights through: they move the rider's torso
// and head by 20-40 pixels of a 320x180 frame (README, "Golden images", for the measured margins).
inline render::DiffThresholds goldenThresholds() {
  render::DiffThresholds t;
  t.fail = 4.0 / 255.0;
  t.fail_fraction = 0.0001;
  t.warn = 1.0 / 255.0;
  t.warn_fraction = 0.0;
  return t;
}

// "trot_side.0004.png"
std::string goldenName(int frame);

struct GoldenComparison {
  render::DiffResult diff;
  std::filesystem::path image, reference, diff_image;
  std::filesystem::path report;  // empty unless the comparison failed
  bool failed() const { return diff.verdict == render::DiffVerdict::Fail; }
  std::string message() const;   // the numbers and where the files and the report are
};

// Compares `image` with `reference` under goldenThresholds(), writing the diff image (x16) next to
// `image`. When the comparison fails, also copies the reference next to `image` and writes
// IMAGE_STEM.report.html there: the reference, the new image and the diff side by side (relative
// links) and the numbers.
GoldenComparison compareWithGolden(const std::filesystem::path& reference, const std::filesystem::path& image);

}  // namespace stirrup::test
