#include "render/review/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "rig/error.h"

namespace stirrup::render {

std::string DiffResult::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "mean %.6f, RMS %.6f, max %.6f at (%d, %d), PSNR %.2f dB, %ld pixels over fail, %ld over warn",
                mean_error, rms_error, max_error, worst_x, worst_y, psnr_db, pixels_over_fail, pixels_over_warn);
  return buf;
}

namespace {

OIIO::ImageBuf readImage(const std::filesystem::path& file) {
  OIIO::ImageBuf buf(file.string());
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
    throw rig::InputError(file.string() + ": cannot read the image (" + buf.geterror() + ")");
  return buf;
}

}  // namespace

DiffResult compareImageFiles(const std::filesystem::path& a_file, const std::filesystem::path& b_file,
                             const DiffThresholds& t, const std::filesystem::path& diff_image,
                             double diff_scale) {
  const OIIO::ImageBuf a = readImage(a_file), b = readImage(b_file);
  const OIIO::ImageSpec &sa = a.spec(), &sb = b.spec();
  if (sa.width != sb.width || sa.height != sb.height)
    throw rig::InputError(a_file.string() + " is " + std::to_string(sa.width) + "x" + std::to_string(sa.height) +
                     " but " + b_file.string() + " is " + std::to_string(sb.width) + "x" +
                     std::to_string(sb.height) + ": expected images of the same size");
  if (sa.nchannels != sb.nchannels)
    throw rig::InputError(a_file.string() + " has " + std::to_string(sa.nchannels) + " channels but " +
                     b_file.string() + " has " + std::to_string(sb.nchannels) +
                     ": expected the same channel count");

  DiffResult r;
  r.width = sa.width;
  r.height = sa.height;
  r.channels = sa.nchannels;
  const int nc = sa.nchannels;
  std::vector<float> pa(static_cast<std::size_t>(r.width) * r.height * nc), pb(pa.size());
  a.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pa.data());
  b.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pb.data());

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
    OIIO::ImageBuf out(OIIO::ImageSpec(r.width, r.height, nc, OIIO::TypeDesc::UINT8));
    out.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, diff.data());
    if (!out.write(diff_image.string()))
      throw rig::InputError(diff_image.string() + ": cannot write the diff image (" + out.geterror() + ")");
  }
  return r;
}

}  // namespace stirrup::render
