// Contact sheets: a grid of evenly spaced frames of a movie, each labelled with its frame number, to
// look at without playing anything (like `oiiotool --mosaic` with labels).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/tracer/image.h"

namespace stirrup::render {

// `count` frames evenly spaced over `frames` (first and last included; all when fewer).
std::vector<int> contactFrames(const std::vector<int>& frames, int count);

struct ContactFrame {
  int frame = 0;
  Image image;  // linear, any size (all the same size)
};

// Writes the sheet: `columns` thumbnails per row, each `thumb_width` wide, with the title above.
void writeContactSheet(const std::string& title, const std::vector<ContactFrame>& frames,
                       const std::filesystem::path& file, int columns = 4, int thumb_width = 320);

}  // namespace stirrup::render
