#include "render/review/plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>

#include "rig/error.h"
#include "rig/io/atomic_file.h"

namespace stirrup::render {

Canvas::Canvas(int width, int height, const Color& background)
    : width_(width), height_(height), rgb_(std::size_t(width) * std::size_t(height) * 3) {
  for (std::size_t i = 0; i < rgb_.size(); ++i) rgb_[i] = background[i % 3];
}

void Canvas::line(glm::dvec2 a, glm::dvec2 b, double width, const Color& c) {
  const double r = 0.5 * width;
  const int x0 = std::max(0, int(std::floor(std::min(a.x, b.x) - r - 1)));
  const int x1 = std::min(width_ - 1, int(std::ceil(std::max(a.x, b.x) + r + 1)));
  const int y0 = std::max(0, int(std::floor(std::min(a.y, b.y) - r - 1)));
  const int y1 = std::min(height_ - 1, int(std::ceil(std::max(a.y, b.y) + r + 1)));
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const glm::dvec2 p(x + 0.5, y + 0.5);
      const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
      const double d = glm::length(p - (a + t * ab));
      blend(x, y, std::clamp(r + 0.5 - d, 0.0, 1.0), c);
    }
}

void Canvas::fill(int x0, int y0, int x1, int y1, const Color& c) {
  for (int y = std::max(0, y0); y < std::min(height_, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(width_, x1); ++x) blend(x, y, 1.0, c);
}

void Canvas::text(int x, int y, const std::string& s, int size, const Color& c, TextAlign align, FontStyle style) {
  std::vector<float> mask(std::size_t(width_) * std::size_t(height_), 0.0f);
  drawTextMask(mask, width_, height_, x, y, s, size, style, align);
  for (int py = 0; py < height_; ++py)
    for (int px = 0; px < width_; ++px) {
      const float m = mask[std::size_t(py) * width_ + px];
      if (m > 0.0f) blend(px, py, std::min(1.0f, m), c);
    }
}

void Canvas::paste(int x, int y, int w, int h, const std::vector<float>& rgb) {
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const int X = x + px, Y = y + py;
      if (X < 0 || Y < 0 || X >= width_ || Y >= height_) continue;
      for (int k = 0; k < 3; ++k) rgb_[(std::size_t(Y) * width_ + X) * 3 + k] = rgb[(std::size_t(py) * w + px) * 3 + k];
    }
}

void Canvas::write(const std::filesystem::path& file) const {
  rig::replaceFileAtomically(
      file,
      [&](const std::filesystem::path& tmp) {
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(tmp.string());
        const OIIO::ImageSpec spec(width_, height_, 3, OIIO::TypeDesc::UINT8);
        if (!out || !out->open(tmp.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, rgb_.data()) ||
            !out->close())
          throw InputError(file.string() + ": cannot write the image");
      },
      rig::TempName::KeepExtension);
}

void Canvas::blend(int x, int y, double coverage, const Color& c) {
  if (coverage <= 0.0 || x < 0 || y < 0 || x >= width_ || y >= height_) return;
  float* px = &rgb_[(std::size_t(y) * width_ + x) * 3];
  for (int k = 0; k < 3; ++k) px[k] = float(px[k] + coverage * (c[k] - px[k]));
}

}  // namespace stirrup::render
