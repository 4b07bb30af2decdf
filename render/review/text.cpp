#include "render/review/text.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>

#include "render/image_files/image_file.h"
#include "rig/error.h"

namespace stirrup::render {
namespace {

const char* fileName(FontStyle style) {
  switch (style) {
    case FontStyle::SansBold: return "DejaVuSans-Bold.ttf";
    case FontStyle::Mono: return "DejaVuSansMono.ttf";
    default: return "DejaVuSans.ttf";
  }
}

std::filesystem::path locate(FontStyle style) {
  namespace fs = std::filesystem;
  const std::string name = fileName(style);
  if (const char* env = std::getenv("STIRRUP_FONT"); env && *env) {
    if (fs::is_regular_file(env)) return env;
    throw rig::InputError(std::string("STIRRUP_FONT: ") + env + ": no such font file (expected a .ttf file)");
  }
  for (const char* dir : {"/usr/share/fonts/truetype/dejavu", "/usr/share/fonts/dejavu", "/usr/share/fonts/TTF",
                          "/usr/local/share/fonts", "/usr/share/fonts/truetype"}) {
    const fs::path p = fs::path(dir) / name;
    if (fs::is_regular_file(p)) return p;
  }
  // fontconfig, when present: fc-match prints the file of the closest font.
  const std::string family = style == FontStyle::Mono ? "DejaVu Sans Mono" : style == FontStyle::SansBold ? "DejaVu Sans:bold" : "DejaVu Sans";
  if (FILE* pipe = popen(("fc-match -f '%{file}' '" + family + "' 2>/dev/null").c_str(), "r")) {
    char buf[1024] = {};
    const std::size_t n = fread(buf, 1, sizeof buf - 1, pipe);
    pclose(pipe);
    const fs::path p(std::string(buf, n));
    if (n > 0 && p.filename().string().find("DejaVu") != std::string::npos && fs::is_regular_file(p)) return p;
  }
  throw rig::InputError(std::string("font: ") + name +
                   " not found (install fonts-dejavu-core, run scripts/setup, or set STIRRUP_FONT to a .ttf file)");
}

}  // namespace

std::filesystem::path findFont(FontStyle style) {
  if (const char* env = std::getenv("STIRRUP_FONT"); env && *env) return locate(style);
  static std::mutex m;
  static std::map<FontStyle, std::filesystem::path> found;
  std::lock_guard<std::mutex> lock(m);
  auto it = found.find(style);
  if (it == found.end()) it = found.emplace(style, locate(style)).first;
  return it->second;
}

std::array<int, 2> textSize(const std::string& text, int size, FontStyle style) {
  const TextBox box = measureText(text, size, findFont(style));
  if (!box.defined) return {0, 0};
  return {box.width(), box.height()};
}

void drawTextMask(std::vector<float>& mask, int width, int height, int x, int y, const std::string& text,
                  int size, FontStyle style, TextAlign align) {
  if (text.empty()) return;
  // OpenImageIO's render_text fails an assertion (aborts) when no pixel of the text lands in the
  // image: draw nothing for text outside the mask. kSliverPx keeps a text whose box OpenImageIO places a
  // pixel or two differently from this estimate on the safe side (such a sliver shows nothing legible).
  constexpr int kSliverPx = 2;
  const std::filesystem::path font = findFont(style);
  const TextBox box = measureText(text, size, font);
  if (!box.defined) return;
  const int left = x - (align == TextAlign::Left ? 0 : align == TextAlign::Center ? box.width() / 2 : box.width());
  if (left + box.xend <= kSliverPx || left + box.xbegin >= width - kSliverPx || y + box.yend <= kSliverPx ||
      y + box.ybegin >= height - kSliverPx)
    return;
  drawTextCoverage(mask, width, height, x, y, text, size, font, align);
}

}  // namespace stirrup::render
