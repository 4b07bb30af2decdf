#include "render/review/burn_in.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "render/review/text.h"
#include "scene/frame_sequence.h"

namespace stirrup::render {
namespace {

// Darkens rows [y0, y1) towards black by `amount` (a translucent band behind the text).
void darken(Image& image, int y0, int y1, float amount) {
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
    for (int x = 0; x < image.width; ++x) {
      glm::vec4& p = image.at(x, y);
      p = glm::vec4(glm::vec3(p) * (1.0f - amount), p.w);
    }
}

// Blends `colour` (linear) over the image by the mask's coverage.
void paint(Image& image, const std::vector<float>& mask, glm::vec3 colour) {
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const float m = std::clamp(mask[i], 0.0f, 1.0f);
    if (m <= 0.0f) continue;
    glm::vec4& p = image.rgba[i];
    p = glm::vec4(glm::vec3(p) * (1.0f - m) + colour * m, 1.0f);
  }
}

}  // namespace

std::string timecode(int frame, double fps) {
  const int rate = std::max(1, static_cast<int>(std::lround(fps)));
  const long n = std::max(0, frame - 1);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02ld:%02ld:%02ld:%02ld", n / (3600L * rate), (n / (60L * rate)) % 60,
                (n / rate) % 60, n % rate);
  return buf;
}

void burnIn(Image& image, const BurnInFacts& f, int frame) {
  const int size = std::max(9, image.height / 24);
  const int band = size + size / 2 + 2;
  darken(image, 0, band, 0.6f);
  darken(image, image.height - band, image.height, 0.6f);
  std::vector<float> mask(image.pixelCount(), 0.0f);
  const int pad = size / 2 + 2;
  const int top = band - (band - size) / 2 - size / 6;
  const int bottom = image.height - (band - size) / 2 - size / 6;
  drawTextMask(mask, image.width, image.height, pad, top, f.scene + "  |  " + f.movement + "  |  " + f.view,
               size, FontStyle::SansBold);
  drawTextMask(mask, image.width, image.height, image.width - pad, top, "profile " + f.profile, size,
               FontStyle::Sans, TextAlign::Right);
  drawTextMask(mask, image.width, image.height, pad, bottom, "frame " + scene::paddedFrameNumber(frame), size, FontStyle::Mono);
  drawTextMask(mask, image.width, image.height, image.width - pad, bottom, timecode(frame, f.fps), size,
               FontStyle::Mono, TextAlign::Right);
  paint(image, mask, glm::vec3(0.92f));
}

void labelPanels(Image& image, const std::vector<std::string>& labels) {
  if (labels.empty()) return;
  const int size = std::max(9, image.height / 24);
  const int band = size + size / 2 + 2;
  const int panel = image.width / static_cast<int>(labels.size());
  std::vector<float> mask(image.pixelCount(), 0.0f);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const int x = static_cast<int>(i) * panel + size / 2 + 2, y = band + size + size / 3;
    const auto [w, h] = textSize(labels[i], size, FontStyle::SansBold);
    (void)h;
    for (int py = band + 2; py < std::min(image.height, y + size / 2); ++py)
      for (int px = x - 3; px < std::min(image.width, x + w + 4); ++px) {
        glm::vec4& p = image.at(std::max(0, px), py);
        p = glm::vec4(glm::vec3(p) * 0.4f, p.w);
      }
    drawTextMask(mask, image.width, image.height, x, y, labels[i], size, FontStyle::SansBold);
  }
  paint(image, mask, glm::vec3(1.0f, 0.85f, 0.3f));
}

Image makeSlate(int width, int height, const BurnInFacts& f) {
  Image slate(width, height);
  for (glm::vec4& p : slate.rgba) p = glm::vec4(0.012f, 0.013f, 0.016f, 1.0f);
  // Nine rows and the title fit in the middle 80% of the height at any size.
  const int size = std::max(8, std::min(height / 22, int(height * 0.62 / (9 * 1.5))));
  const int big = std::max(11, size * 2);
  std::vector<float> mask(slate.pixelCount(), 0.0f);
  const int x = width / 10;
  int y = height / 10 + big;
  drawTextMask(mask, width, height, x, y, f.title, big, FontStyle::SansBold);
  y += big / 3;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g fps", f.fps);
  const std::vector<std::pair<std::string, std::string>> rows = {
      {"scene", f.scene},
      {"movement", f.movement},
      {"view", f.view},
      {"rig profile", f.profile},
      {"frames", f.frames + " (" + std::to_string(f.frame_count) + " at " + rate + ")"},
      {"timecode", timecode(1, f.fps) + " - " + timecode(f.frame_count, f.fps)},
      {"resolution", std::to_string(width) + " x " + std::to_string(height)},
      {"quality", f.quality},
      {"date", f.date},
  };
  const int labelWidth = width * 3 / 10;
  for (const auto& [label, value] : rows) {
    y += size + size / 2;
    if (y > height - size) break;
    drawTextMask(mask, width, height, x, y, label, size, FontStyle::Sans);
    drawTextMask(mask, width, height, x + labelWidth, y, value, size, FontStyle::SansBold);
  }
  paint(slate, mask, glm::vec3(0.85f));
  return slate;
}

std::string todayUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
  return buf;
}

}  // namespace stirrup::render
