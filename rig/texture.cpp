#include "rig/texture.h"

#include <algorithm>
#include <cmath>

namespace stirrup::rig {

double srgbToLinear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

const std::vector<float>& srgb8ToLinearTable() {
  static const std::vector<float> table = [] {
    std::vector<float> t(256);
    for (int i = 0; i < 256; ++i) t[std::size_t(i)] = float(srgbToLinear(i / 255.0));
    return t;
  }();
  return table;
}

std::int64_t wrapTexel(std::int64_t i, std::int64_t n, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::ClampToEdge: return std::clamp<std::int64_t>(i, 0, n - 1);
    case TextureWrap::MirroredRepeat: {
      // Even periods read the image forward, odd ones backward (OpenGL's mirror(), as glTF defines it).
      const std::int64_t m = ((i % (2 * n)) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
    case TextureWrap::Repeat: break;
  }
  return ((i % n) + n) % n;
}

glm::vec3 Texture::texel(std::int64_t x, std::int64_t y) const {
  const std::int64_t wx = wrapTexel(x, width, wrap_s), wy = wrapTexel(y, height, wrap_t);
  return texels[std::size_t(wy) * std::size_t(width) + std::size_t(wx)];
}

glm::vec3 Texture::sample(glm::vec2 uv) const {
  // In texels. Far from the image the coordinate is first brought back within two periods of it (the
  // wraps repeat every 2n texels, the clamp is flat past one texel out), so it always fits an integer.
  const auto toTexels = [](float u, int n, TextureWrap wrap) {
    double x = std::isfinite(u) ? double(u) * n : 0.0;
    if (wrap == TextureWrap::ClampToEdge) return std::clamp(x, -1.0, n + 1.0);
    const double period = 2.0 * n;
    return x - period * std::floor(x / period);
  };
  const double s = toTexels(uv.x, width, wrap_s), t = toTexels(uv.y, height, wrap_t);
  if (filter == TextureFilter::Nearest) return texel(std::int64_t(std::floor(s)), std::int64_t(std::floor(t)));
  // Bilinear between the four texel centres around the point.
  const double x = s - 0.5, y = t - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const float fx = float(x - x0), fy = float(y - y0);
  const std::int64_t ix = std::int64_t(x0), iy = std::int64_t(y0);
  const glm::vec3 top = texel(ix, iy) * (1.0f - fx) + texel(ix + 1, iy) * fx;
  const glm::vec3 bottom = texel(ix, iy + 1) * (1.0f - fx) + texel(ix + 1, iy + 1) * fx;
  return top * (1.0f - fy) + bottom * fy;
}

}  // namespace stirrup::rig
