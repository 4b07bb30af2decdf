// Channel plots: the main horse and rider channels of a movement over time, so an animator can see
// why the rider moves. Stacked panels share the time axis (seconds below, frames above); each panel
// has its own value axis with ticks, a unit, gridlines and a legend. Drawn on the plot Canvas shared
// with the spine plot (render/review/plot_canvas.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/review/plot_canvas.h"
#include "rig/bake.h"
#include "rig/motion/path_clip.h"

namespace stirrup::render {

struct ChannelSeries {
  std::string label;           // legend text, e.g. "lfHoof.ty (left fore)"
  Color colour;
  std::vector<double> values;  // one per frame
};

struct PlotPanel {
  std::string title;  // e.g. "Hoof heights"
  std::string unit;   // e.g. "cm"
  std::vector<ChannelSeries> series;
};

struct ChannelPlot {
  std::string title;            // e.g. "trot: horse and rider channels"
  std::vector<int> frames;      // frame numbers, one per value
  std::vector<double> seconds;  // time of each frame
  std::vector<PlotPanel> panels;
};

// The review plot of a movement from its baked frames: hoof heights; the rear pivot's height and
// pitch; the rider's lower-back rotation and lift (cog.ty in cm).
ChannelPlot movementPlot(const std::string& title, const std::vector<rig::BakedFrame>& frames,
                         double rider_unit_cm);

// The panels a path clip adds (issue 15), from the same baked frames: speed (m/s) with the gait as a
// step (1 walk, 2 trot, 3 canter, 4 gallop; the lead as a sign, + right, at the canter and gallop),
// and the body's roll into the turn (rearPivot.rx), the ground's pitch and the rider's lowerBack.ry.
// `clip_offset_s`: the frames were baked from the clip started this far in (a crowd pair's start phase).
std::vector<PlotPanel> pathPanels(const rig::PathClip& clip, const std::vector<rig::BakedFrame>& frames,
                                  double clip_offset_s = 0.0);

// Writes the plot as a PNG, `width` pixels wide (via FILE.tmp.png and a rename).
void writeChannelPlot(const ChannelPlot& plot, const std::filesystem::path& file, int width = 1280);

// Evenly spaced "nice" tick values (1, 2 or 5 times a power of ten) covering [lo, hi].
std::vector<double> niceTicks(double lo, double hi, int approx_count);

}  // namespace stirrup::render
