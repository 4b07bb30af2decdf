// Per-frame composites of layered comparisons: side by side, over, difference, onion skin; and the
// small bitmap font their labels use. Footage, plates and the scene's reference block are in
// render/review/footage.cpp.
#include "render/review/layer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "rig/error.h"

namespace stirrup::render {

namespace {

void requireSameSize(const Image& a, const Image& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    throw rig::InputError(std::string("layer ") + what + ": the two images must be the same size, got " +
                     std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                     std::to_string(b.width) + "x" + std::to_string(b.height));
}

// How much of pixel i of `img` lies over what is below it.
float coverageAt(const Image& img, size_t i, LayerCoverage coverage) {
  switch (coverage) {
    case LayerCoverage::Matte: return img.matte.empty() ? 1.0f : std::clamp(img.matte[i], 0.0f, 1.0f);
    case LayerCoverage::Alpha: return std::clamp(img.rgba[i].w, 0.0f, 1.0f);
    case LayerCoverage::Full: return 1.0f;
  }
  return 1.0f;
}

// Lays `top` (times `tint`) over `out` with weight opacity * coverage, per pixel.
void layOver(Image& out, const Image& top, float opacity, LayerCoverage coverage, glm::vec4 tint) {
  const glm::vec3 t(tint);
  for (size_t i = 0; i < out.pixelCount(); ++i) {
    const float k = std::clamp(opacity, 0.0f, 1.0f) * coverageAt(top, i, coverage);
    const glm::vec3 c = k * (glm::vec3(top.rgba[i]) * t) + (1.0f - k) * glm::vec3(out.rgba[i]);
    out.rgba[i] = glm::vec4(c, 1.0f);
  }
}

Image opaqueCopy(const Image& img) {
  Image out(img.width, img.height);
  for (size_t i = 0; i < img.pixelCount(); ++i) out.rgba[i] = glm::vec4(glm::vec3(img.rgba[i]), 1.0f);
  return out;
}

// `src` resampled to height `h` keeping its aspect: bilinear when enlarging, the mean of a grid of
// bilinear taps over each output pixel's footprint when reducing. Exact copy when the sizes match.
Image resampleToHeight(const Image& src, int h) {
  if (src.height == h || src.height <= 0) return opaqueCopy(src);
  const double s = double(h) / src.height;
  const int w = std::max(1, int(std::lround(src.width * s)));
  Image out(w, h);
  const int taps = std::max(1, int(std::ceil(1.0 / s)));
  auto texel = [&](int x, int y) {
    x = std::clamp(x, 0, src.width - 1);
    y = std::clamp(y, 0, src.height - 1);
    return glm::vec3(src.at(x, y));
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < taps; ++j)
        for (int i = 0; i < taps; ++i) {
          const double u = (x + (i + 0.5) / taps) / s - 0.5, v = (y + (j + 0.5) / taps) / s - 0.5;
          const int x0 = int(std::floor(u)), y0 = int(std::floor(v));
          const float fx = float(u - x0), fy = float(v - y0);
          sum += (1 - fy) * ((1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
                 fy * ((1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
        }
      out.at(x, y) = glm::vec4(sum / float(taps * taps), 1.0f);
    }
  return out;
}

Image sideBySide(const Image& ours, const Image& other, const LayerStyle& style) {
  const Image right = resampleToHeight(other, ours.height);
  const int gap = std::max(0, style.gap);
  Image out(ours.width + gap + right.width, ours.height);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < ours.width; ++x) out.at(x, y) = glm::vec4(glm::vec3(ours.at(x, y)), 1.0f);
    for (int x = 0; x < gap; ++x) out.at(ours.width + x, y) = glm::vec4(glm::vec3(style.gap_colour), 1.0f);
    for (int x = 0; x < right.width; ++x) out.at(ours.width + gap + x, y) = right.at(x, y);
  }
  if (style.labels) {
    const int margin = 2 * std::max(1, style.label_scale);
    drawLabel(out, margin, margin, style.ours_label, style.label_scale);
    drawLabel(out, ours.width + gap + margin, margin, style.other_label, style.label_scale);
  }
  return out;
}

// 5x7 glyphs, one byte per row from the top, bit 4 the leftmost column.
struct Glyph {
  char c;
  std::array<uint8_t, 7> rows;
};
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'A', {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11}}, {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}}, {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}}, {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}}, {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}}, {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}}, {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}}, {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}}, {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}}, {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}}, {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}}, {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}}, {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}}, {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
};

const Glyph* findGlyph(char c) {
  if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;  // a space
}

}  // namespace

void drawLabel(Image& image, int x, int y, const std::string& text, int scale, glm::vec4 colour) {
  if (text.empty()) return;
  scale = std::max(1, scale);
  const int advance = 6 * scale, pad = scale;
  const int w = int(text.size()) * advance - scale + 2 * pad, h = 7 * scale + 2 * pad;
  auto put = [&](int px, int py, glm::vec3 c, float k) {
    if (px < 0 || py < 0 || px >= image.width || py >= image.height) return;
    glm::vec4& p = image.at(px, py);
    p = glm::vec4(k * c + (1.0f - k) * glm::vec3(p), 1.0f);
  };
  // A translucent dark box so the label reads on sky, ground and footage alike.
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) put(x + i, y + j, glm::vec3(0.0f), 0.6f);
  for (size_t n = 0; n < text.size(); ++n) {
    const Glyph* g = findGlyph(text[n]);
    if (!g) continue;
    for (int row = 0; row < 7; ++row)
      for (int col = 0; col < 5; ++col)
        if (g->rows[size_t(row)] & (0x10 >> col))
          for (int j = 0; j < scale; ++j)
            for (int i = 0; i < scale; ++i)
              put(x + pad + int(n) * advance + col * scale + i, y + pad + row * scale + j, glm::vec3(colour), 1.0f);
  }
}

Image onionSkin(const Image& ours, std::span<const Image> ghosts, std::span<const int> ghost_offsets,
                const Image& other, const LayerStyle& style) {
  requireSameSize(ours, other, "onion-skin");
  if (ghosts.size() != ghost_offsets.size())
    throw rig::InputError("layer onion-skin: " + std::to_string(ghosts.size()) + " ghost frames but " +
                     std::to_string(ghost_offsets.size()) + " offsets");
  for (const Image& g : ghosts) requireSameSize(ours, g, "onion-skin");
  const int step = std::max(1, style.onion_step);
  // Farthest first, so nearer ghosts lie over farther ones; ties (same distance before and after)
  // keep the earlier frame below.
  std::vector<size_t> order(ghosts.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const int da = std::abs(ghost_offsets[a]), db = std::abs(ghost_offsets[b]);
    return da != db ? da > db : ghost_offsets[a] < ghost_offsets[b];
  });
  Image out = opaqueCopy(other);
  for (size_t i : order) {
    const int d = ghost_offsets[i];
    if (d == 0) throw rig::InputError("layer onion-skin: a ghost frame offset is 0 (the current frame)");
    const int ring = std::max(1, (std::abs(d) + step - 1) / step);
    const float opacity = style.opacity * std::pow(style.onion_falloff, float(ring - 1));
    layOver(out, ghosts[i], opacity, style.coverage, d < 0 ? style.onion_before : style.onion_after);
  }
  layOver(out, ours, 1.0f, style.coverage, glm::vec4(1.0f));
  return out;
}

std::vector<int> onionGhostFrames(int frame, const LayerStyle& style, int first, int last) {
  std::vector<int> frames;
  const int step = std::max(1, style.onion_step);
  for (int k = std::max(0, style.onion_frames); k >= 1; --k)
    if (frame - k * step >= first && frame - k * step <= last) frames.push_back(frame - k * step);
  for (int k = 1; k <= std::max(0, style.onion_frames); ++k)
    if (frame + k * step >= first && frame + k * step <= last) frames.push_back(frame + k * step);
  return frames;
}

Image layerFrame(const Image& ours, const Image& other, const LayerStyle& style) {
  switch (style.mode) {
    case scene::LayerMode::SideBySide: return sideBySide(ours, other, style);
    case scene::LayerMode::Over: {
      requireSameSize(ours, other, "over");
      Image out = opaqueCopy(other);
      layOver(out, ours, style.opacity, style.coverage, glm::vec4(1.0f));
      return out;
    }
    case scene::LayerMode::Difference: {
      requireSameSize(ours, other, "difference");
      Image out(ours.width, ours.height);
      for (size_t i = 0; i < out.pixelCount(); ++i) {
        const glm::vec3 d = glm::abs(glm::vec3(ours.rgba[i]) - glm::vec3(other.rgba[i])) * style.difference_gain;
        out.rgba[i] = glm::vec4(glm::min(d, glm::vec3(1.0f)), 1.0f);
      }
      return out;
    }
    case scene::LayerMode::OnionSkin: return onionSkin(ours, {}, {}, other, style);
  }
  return opaqueCopy(ours);
}

}  // namespace stirrup::render
