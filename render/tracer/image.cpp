#include "render/tracer/image.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include <glm/geometric.hpp>

#include "render/image_files/image_file.h"
#include "render/tracer/png_encoder.h"
#include "render/tracer/srgb_encoder.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"

namespace stirrup::render {

namespace fs = std::filesystem;

Image::Image(int w, int h) : Image(unfilled(w, h)) { std::fill(rgba.begin(), rgba.end(), glm::vec4(0.0f)); }

Image Image::unfilled(int w, int h) {
  if (w <= 0 || h <= 0) throw std::invalid_argument("image size must be positive");
  Image image;
  image.width = w, image.height = h;
  image.rgba.resize(image.pixelCount());
  return image;
}

float linearToSrgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);  // also maps NaN to 0 via the comparisons below
  if (!(c > 0.0031308f)) return c > 0.0f ? 12.92f * c : 0.0f;
  return 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

uint8_t linearToSrgb8(float linear) { return uint8_t(std::lround(linearToSrgb(linear) * 255.0f)); }

void encodeSrgb8(std::span<const glm::vec4> rgba, std::span<uint8_t> rgb) {
  if (rgb.size() != rgba.size() * 3) throw std::invalid_argument("encodeSrgb8: expected 3 bytes a pixel");
  static_assert(sizeof(glm::vec4) == 4 * sizeof(float));
  if (!rgba.empty()) srgbCodesRgb(&rgba[0].x, rgb.data(), rgba.size());
}

void writePng(const Image& image, const fs::path& file, int compression) {
  if (image.rgba.size() != image.pixelCount() || image.rgba.empty()) {
    throw std::invalid_argument("writePng: image has no pixels");
  }
  if (compression < scene::kPngCompressionMin || compression > scene::kPngCompressionMax) {
    throw std::invalid_argument("writePng: compression " + std::to_string(compression) + " is not a zlib level 0 to 9");
  }
  // The rows straight into PNG's scanlines (each row's filter byte, 0: none, then its sRGB codes), the
  // file made whole in memory (render/tracer/png_encoder.h), then written in one go.
  const std::size_t row_bytes = pngScanlineBytes(image.width);
  std::vector<uint8_t> scanlines(row_bytes * std::size_t(image.height));
  for (int y = 0; y < image.height; ++y) {
    uint8_t* row = &scanlines[std::size_t(y) * row_bytes];
    row[0] = 0;
    srgbCodesRgb(&image.rgba[std::size_t(y) * std::size_t(image.width)].x, row + 1, std::size_t(image.width));
  }
  const std::vector<uint8_t> png = encodePngRgb8(scanlines, image.width, image.height, compression);
  rig::replaceFileAtomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    if (!out.flush()) {
      throw std::runtime_error("cannot write " + file.string() + ": " + std::strerror(errno));
    }
  });
}

void writeExr(const Image& image, const fs::path& file, const ExrMetadata& metadata) {
  const size_t n = image.pixelCount();
  if (image.rgba.size() != n || n == 0) throw std::invalid_argument("writeExr: image has no pixels");
  auto present = [n](const auto& pass) {
    if (!pass.empty() && pass.size() != n) throw std::invalid_argument("writeExr: pass size mismatch");
    return !pass.empty();
  };
  const bool has_depth = present(image.depth), has_matte = present(image.matte),
             has_normal = present(image.normal), has_id = present(image.object_id);

  // Channels in the order OpenImageIO reads them back: RGBA, Z, the unlayered passes, then N.
  ImageFileSpec spec;
  spec.width = image.width, spec.height = image.height;
  spec.channel_names = {"R", "G", "B", "A"};
  spec.channel_formats.assign(4, StoredAs::Half);
  const auto add = [&](const char* name, StoredAs format) {
    spec.channel_names.push_back(name), spec.channel_formats.push_back(format);
  };
  if (has_depth) add("Z", StoredAs::Float);
  if (has_matte) add("matte", StoredAs::Half);
  // Ids as float: exact for small integers, and every EXR reader understands float channels.
  if (has_id) add("objectId", StoredAs::Float);
  if (has_normal) {
    for (const char* n : {"N.x", "N.y", "N.z"}) add(n, StoredAs::Half);
  }
  const int channels = int(spec.channel_names.size());

  // Interleaved float data; OpenImageIO converts each channel to its own file format.
  std::vector<float> data(n * channels);
  for (size_t i = 0; i < n; ++i) {
    float* px = &data[i * channels];
    for (int c = 0; c < 4; ++c) px[c] = image.rgba[i][c];
    int c = 4;
    if (has_depth) px[c++] = image.depth[i];
    if (has_matte) px[c++] = image.matte[i];
    if (has_id) px[c++] = image.object_id[i] == kNoObject ? -1.0f : float(image.object_id[i]);
    if (has_normal) {
      for (int k = 0; k < 3; ++k) px[c++] = image.normal[i][k];
    }
  }
  spec.alpha_channel = 3;
  spec.z_channel = has_depth ? 4 : -1;
  spec.attributes = {{"compression", std::string("zip")}, {"oiio:ColorSpace", std::string("Linear")}};
  spec.attributes.insert(spec.attributes.end(), metadata.begin(), metadata.end());
  writeImageFile(file, "openexr", spec, data.data());
}

ExrMetadata exrFrameMetadata(const scene::Camera& camera, const std::string& camera_name, int frame, double time_s,
                             const std::string& scene_name) {
  const bool ortho = camera.projection == scene::Camera::Projection::Orthographic;
  const scene::CameraFrame view(camera, 1.0, 1);
  // worldToCamera as OpenEXR defines it: row vectors (p * M), a camera looking down its -Z axis with
  // +Y up. Stored row-major, glm's column-major array read as rows is exactly that layout.
  glm::mat4 m(1.0f);
  const glm::dvec3 r = view.right(), u = view.upward(), b = -view.forward();
  const glm::dvec3 p = camera.position;
  for (int k = 0; k < 3; ++k) {
    m[k][0] = float(r[k]);
    m[k][1] = float(u[k]);
    m[k][2] = float(b[k]);
    m[k][3] = 0.0f;
  }
  m[3][0] = float(-glm::dot(r, p));
  m[3][1] = float(-glm::dot(u, p));
  m[3][2] = float(-glm::dot(b, p));
  m[3][3] = 1.0f;
  ExrMetadata md = {
      {"stirrup:scene", scene_name},
      {"stirrup:frame", frame},
      {"stirrup:time", float(time_s)},
      {"stirrup:camera", camera_name},
      {"stirrup:camera:projection", std::string(ortho ? "orthographic" : "perspective")},
      {"stirrup:camera:position", glm::vec3(camera.position)},
      {"stirrup:camera:target", glm::vec3(camera.target)},
      {"worldToCamera", m},
  };
  if (ortho) {
    md.push_back({"stirrup:camera:ortho_height", float(camera.ortho_height_cm)});
  } else {
    md.push_back({"stirrup:camera:fov", float(camera.fov_deg)});
  }
  return md;
}

void writeRgbaExr(const Image& image, const fs::path& file) {
  if (image.rgba.size() != image.pixelCount() || image.pixelCount() == 0)
    throw std::invalid_argument("writeRgbaExr: image has no pixels");
  ImageFileSpec spec;
  spec.width = image.width, spec.height = image.height;
  spec.channel_formats.assign(4, StoredAs::Float);
  spec.alpha_channel = 3;
  spec.attributes = {{"compression", std::string("zip")}};
  writeImageFile(file, "openexr", spec, &image.rgba.data()->x);
}

Image readRgbaExr(const fs::path& file) {
  const ImageFileData read = readImageFile(file);
  if (read.channels != 4)
    throw rig::InputError(file.string() + ": expected an RGBA image, got " + std::to_string(read.channels) + " channels");
  Image image = Image::unfilled(read.width, read.height);
  std::copy(read.pixels.begin(), read.pixels.end(), &image.rgba.data()->x);
  return image;
}

}  // namespace stirrup::render
