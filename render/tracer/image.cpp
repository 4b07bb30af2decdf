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
#include <OpenImageIO/imageio.h>

#include "render/tracer/png_encoder.h"
#include "render/tracer/srgb_encoder.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

// Writes `pixels` (interleaved float channels, or per-channel formats given in the spec) through
// OIIO to FILE.tmp in `format`, then renames it to FILE (rig/io/atomic_file.h). On any failure the
// temporary is removed.
void writeAtomically(const fs::path& file, const char* format, const OIIO::ImageSpec& spec,
                     OIIO::TypeDesc data_type, const void* pixels) {
  // The format is named explicitly: OIIO would otherwise guess it from the ".tmp" extension.
  auto out = OIIO::ImageOutput::create(format);
  if (!out) throw std::runtime_error("cannot write " + file.string() + ": no OpenImageIO " + format + " writer");
  auto fail = [&](const std::string& what) { throw std::runtime_error("cannot write " + file.string() + ": " + what); };
  rig::replaceFileAtomically(file, [&](const fs::path& tmp) {
    if (!out->open(tmp.string(), spec)) fail(out->geterror());
    if (!out->write_image(data_type, pixels)) {
      const std::string err = out->geterror();
      out->close();
      fail(err);
    }
    if (!out->close()) fail(out->geterror());
  });
}

}  // namespace

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
  std::vector<std::string> names = {"R", "G", "B", "A"};
  std::vector<OIIO::TypeDesc> formats(4, OIIO::TypeDesc::HALF);
  if (has_depth) names.push_back("Z"), formats.push_back(OIIO::TypeDesc::FLOAT);
  if (has_matte) names.push_back("matte"), formats.push_back(OIIO::TypeDesc::HALF);
  // Ids as float: exact for small integers, and every EXR reader understands float channels.
  if (has_id) names.push_back("objectId"), formats.push_back(OIIO::TypeDesc::FLOAT);
  if (has_normal) {
    for (const char* n : {"N.x", "N.y", "N.z"}) names.push_back(n), formats.push_back(OIIO::TypeDesc::HALF);
  }
  const int channels = int(names.size());

  // Interleaved float data; OIIO converts each channel to its own file format.
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
  OIIO::ImageSpec spec(image.width, image.height, channels, OIIO::TypeDesc::HALF);
  spec.channelnames = names;
  spec.channelformats = formats;
  spec.alpha_channel = 3;
  spec.z_channel = has_depth ? 4 : -1;
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  for (const ExrAttribute& a : metadata) {
    if (const auto* text = std::get_if<std::string>(&a.value)) {
      spec.attribute(a.name, *text);
    } else if (const int* i = std::get_if<int>(&a.value)) {
      spec.attribute(a.name, *i);
    } else if (const float* f = std::get_if<float>(&a.value)) {
      spec.attribute(a.name, *f);
    } else if (const auto* v = std::get_if<glm::vec3>(&a.value)) {
      spec.attribute(a.name, OIIO::TypeDesc::TypeVector, v);
    } else if (const auto* m = std::get_if<glm::mat4>(&a.value)) {
      spec.attribute(a.name, OIIO::TypeDesc::TypeMatrix44, m);
    }
  }
  writeAtomically(file, "openexr", spec, OIIO::TypeDesc::FLOAT, data.data());
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
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT);
  spec.alpha_channel = 3;
  spec.attribute("compression", "zip");
  writeAtomically(file, "openexr", spec, OIIO::TypeDesc::FLOAT, image.rgba.data());
}

Image readRgbaExr(const fs::path& file) {
  // OpenImageIO's messages can run over several lines; an InputError is one.
  auto oneLine = [](std::string text) {
    for (char& c : text)
      if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
  };
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) throw rig::InputError(file.string() + ": cannot read (" + oneLine(OIIO::geterror()) + ")");
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels != 4 || spec.width <= 0 || spec.height <= 0)
    throw rig::InputError(file.string() + ": expected an RGBA image, got " + std::to_string(spec.nchannels) + " channels");
  Image image(spec.width, spec.height);
  if (!in->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, image.rgba.data()))
    throw rig::InputError(file.string() + ": cannot read (" + oneLine(in->geterror()) + ")");
  return image;
}

}  // namespace stirrup::render
