#include "render/review/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/image_files/image_file.h"
#include "rig/error.h"

namespace stirrup::render {

std::string DiffResult::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "mean %.6f, RMS %.6f, max %.6f at (%d, %d), PSNR %.2f dB, %ld pixels over fail, %ld over warn",
                mean_error, rms_error, max_error, worst_x, worst_y, psnr_db, pixels_over_fail, pixels_over_warn);
  return buf;
}

DiffResult compareImageFiles(const std::filesystem::path& a_file, const std::filesystem::path& b_file,
                             const DiffThresholds& t, const std::filesystem::path& diff_image,
                             double diff_scale) {
  const ImageFileData sa = readImageFile(a_file), sb = readImageFile(b_file);
  if (sa.width != sb.width || sa.height != sb.height)
    throw rig::InputError(a_file.string() + " is " + std::to_string(sa.width) + "x" + std::to_string(sa.height) +
                     " but " + b_file.string() + " is " + std::to_string(sb.width) + "x" +
                     std::to_string(sb.height) + ": expected images of the same size");
  if (sa.channels != sb.channels)
    throw rig::InputError(a_file.string() + " has " + std::to_string(sa.channels) + " channels but " +
                     b_file.string() + " has " + std::to_string(sb.channels) +
                     ": expected the same channel count");

  DiffResult r;
  r.width = sa.width;
  r.height = sa.height;
  r.channels = sa.channels;
  const int nc = sa.channels;
  const std::vector<float>&pa = sa.pixels, &pb = sb.pixels;

  std::vector<float> diff(pa.size());
  double sum = 0, sum_sq = 0;
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      double pixel_error = 0;
      for (int c = 0; c < nc; ++c) {
        const std::size_t i = (static_cast<std::size_t>(y) * r.width + x) * nc + c;
        const double d = std::abs(double(pa[i]) - double(pb[i]));
        diff[i] = static_cast<float>(std::min(1.0, d * diff_scale));
        sum += d;
        sum_sq += d * d;
        pixel_error = std::max(pixel_error, d);
      }
      if (pixel_error > r.max_error) {
        r.max_error = pixel_error;
        r.worst_x = x;
        r.worst_y = y;
      }
      r.pixels_over_fail += pixel_error > t.fail;
      r.pixels_over_warn += pixel_error > t.warn;
    }
  }
  const double n = double(pa.size());
  r.mean_error = sum / n;
  r.rms_error = std::sqrt(sum_sq / n);
  r.psnr_db = r.rms_error > 0 ? 20.0 * std::log10(1.0 / r.rms_error) : std::numeric_limits<double>::infinity();
  const double pixels = double(r.width) * r.height;
  if (r.pixels_over_fail > t.fail_fraction * pixels || r.max_error > t.hardfail) {
    r.verdict = DiffVerdict::Fail;
  } else if (r.pixels_over_warn > t.warn_fraction * pixels) {
    r.verdict = DiffVerdict::Warn;
  }

  if (!diff_image.empty()) {
    if (nc == 4)  // keep the diff visible: opaque alpha
      for (std::size_t i = 3; i < diff.size(); i += 4) diff[i] = 1.0f;
    ImageFileSpec spec;
    spec.width = r.width, spec.height = r.height;
    spec.channel_formats.assign(std::size_t(nc), StoredAs::UInt8);
    writeImageFile(diff_image, "", spec, diff.data());
  }
  return r;
}

}  // namespace stirrup::render
