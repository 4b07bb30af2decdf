#include "render/review/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/review/plot_canvas.h"
#include "scene/frame_sequence.h"

namespace stirrup::render {

std::vector<int> contactFrames(const std::vector<int>& frames, int count) {
  if (frames.empty() || count <= 0) return {};
  const int n = static_cast<int>(frames.size());
  if (n <= count) return frames;
  std::vector<int> out;
  for (int i = 0; i < count; ++i) {
    const int k = count == 1 ? 0 : static_cast<int>(std::lround(double(i) * (n - 1) / (count - 1)));
    out.push_back(frames[static_cast<std::size_t>(k)]);
  }
  return out;
}

namespace {

// Box-filtered sRGB thumbnail (display-referred RGB floats).
std::vector<float> thumbnail(const Image& im, int tw, int th) {
  std::vector<float> rgb(std::size_t(tw) * th * 3, 0.0f);
  for (int y = 0; y < th; ++y)
    for (int x = 0; x < tw; ++x) {
      const int sx0 = x * im.width / tw, sx1 = std::max(sx0 + 1, (x + 1) * im.width / tw);
      const int sy0 = y * im.height / th, sy1 = std::max(sy0 + 1, (y + 1) * im.height / th);
      glm::vec3 sum(0.0f);
      for (int sy = sy0; sy < sy1; ++sy)
        for (int sx = sx0; sx < sx1; ++sx) sum += glm::vec3(im.at(sx, sy));
      sum /= float((sx1 - sx0) * (sy1 - sy0));
      for (int k = 0; k < 3; ++k) rgb[(std::size_t(y) * tw + x) * 3 + k] = linearToSrgb(sum[k]);
    }
  return rgb;
}

}  // namespace

void writeContactSheet(const std::string& title, const std::vector<ContactFrame>& frames,
                       const std::filesystem::path& file, int columns, int thumb_width) {
  if (frames.empty()) throw std::invalid_argument(file.string() + ": no frames for the contact sheet");
  const Image& first = frames.front().image;
  const int tw = thumb_width;
  const int th = std::max(1, int(std::lround(double(tw) * first.height / first.width)));
  const int cols = std::min<int>(columns, static_cast<int>(frames.size()));
  const int rows = (static_cast<int>(frames.size()) + cols - 1) / cols;
  const int gap = 10, label = 24, titleH = 40;
  const int W = cols * tw + (cols + 1) * gap;
  const int H = titleH + rows * (th + label + gap) + gap;
  Canvas c(W, H, {0.13f, 0.13f, 0.14f});
  c.text(gap, 27, title, 18, {0.92f, 0.92f, 0.92f}, TextAlign::Left, FontStyle::SansBold);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const int col = int(i) % cols, row = int(i) / cols;
    const int x = gap + col * (tw + gap), y = titleH + row * (th + label + gap);
    c.paste(x, y, tw, th, thumbnail(frames[i].image, tw, th));
    c.text(x + tw / 2, y + th + 17, "frame " + scene::paddedFrameNumber(frames[i].frame), 14, {0.85f, 0.85f, 0.85f},
           TextAlign::Center, FontStyle::Mono);
  }
  if (!file.parent_path().empty()) std::filesystem::create_directories(file.parent_path());
  c.write(file);
}

}  // namespace stirrup::render
