// Text for burn-ins, slates, contact sheets and plots: OpenImageIO's ImageBufAlgo::render_text with a
// DejaVu font. The font is found once: $STIRRUP_FONT, then Debian's fonts-dejavu-core location, then
// fontconfig (fc-match). A missing font is a one-line error naming what to install.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "render/image_files/image_file.h"

namespace stirrup::render {

enum class FontStyle { Sans, SansBold, Mono };

// The font file for a style; throws rig::InputError if no DejaVu font can be found.
std::filesystem::path findFont(FontStyle style = FontStyle::Sans);

using TextAlign = HorizontalAlign;  // Left, Center, Right (render/image_files/image_file.h)

// Coverage (0..1) of `text` drawn at `size` pixels into a width x height single-channel mask, the
// baseline at y, x being the left edge, centre or right edge by `align`. Pixels outside stay 0.
void drawTextMask(std::vector<float>& mask, int width, int height, int x, int y, const std::string& text,
                  int size, FontStyle style = FontStyle::Sans, TextAlign align = TextAlign::Left);

// The width and height in pixels that `text` takes at `size`.
std::array<int, 2> textSize(const std::string& text, int size, FontStyle style = FontStyle::Sans);

}  // namespace stirrup::render
