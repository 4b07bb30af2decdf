// Image comparison the way OpenImageIO's idiff does it: per-pixel error is the largest absolute
// channel difference; a comparison fails when more than `fail_fraction` of the pixels exceed
// `fail`, or any pixel exceeds `hardfail`, and warns likewise with `warn`.
#pragma once

#include <filesystem>
#include <limits>
#include <string>

namespace stirrup::render {

struct DiffThresholds {
  double fail = 0.016;          // per-pixel error (0..1) that counts as a failure (≈ 4/255, Blender's)
  double fail_fraction = 0.0;   // fraction of pixels allowed over `fail`
  double warn = 0.004;
  double warn_fraction = 0.0;
  double hardfail = std::numeric_limits<double>::infinity();
};

enum class DiffVerdict { Pass = 0, Warn = 1, Fail = 2 };

struct DiffResult {
  int width = 0, height = 0, channels = 0;
  double mean_error = 0, rms_error = 0, max_error = 0, psnr_db = 0;
  int worst_x = 0, worst_y = 0;
  long pixels_over_fail = 0, pixels_over_warn = 0;
  DiffVerdict verdict = DiffVerdict::Pass;
  std::string summary() const;  // one line: mean, RMS, max at (x, y), PSNR, counts
};

// Compares two image files. Different sizes or channel counts, or an unreadable file, throw
// rig::InputError naming the files. When diff_image is not empty, writes |a - b| scaled by
// `diff_scale` so small differences are visible.
DiffResult compareImageFiles(const std::filesystem::path& a, const std::filesystem::path& b,
                             const DiffThresholds& t, const std::filesystem::path& diff_image = {},
                             double diff_scale = 16.0);

}  // namespace stirrup::render
