// A diagnostic picture of curve-spine poses (stirrup spine --plot), three poses to a row: for every
// pose, two panels side by side — the x–y plane (bend front/back: +X forward to the right) and the z–y plane (side to side: +Z
// to the right), Y up in both. Grey: the three FK bones; blue: the curve; orange: the chain with its
// joints; green ticks: each joint's y axis (forward at rest), which shows the twist. One scale for all
// panels, so poses compare by size. Lines are drawn antialiased into a float buffer and written by
// OpenImageIO.
#pragma once

#include <filesystem>
#include <vector>

#include "rig/curve_spine.h"

namespace stirrup::render {

struct SpinePlotStyle {
  int panel_size = 320;  // pixels, square
  int margin = 24;       // pixels around the drawing in each panel
  int poses_per_row = 3;  // each pose takes two panels; rows as needed
};

// Writes FILE via FILE.tmp.EXT and a rename. Throws rig::InputError if the image can't be written.
void writeSpinePlot(const std::vector<rig::SpineResult>& poses, const std::filesystem::path& file,
                    const SpinePlotStyle& style = {});

}  // namespace stirrup::render
