// Burn-ins and slates for review movies. Every frame carries, in a dark band at the top, the scene,
// the movement, the view and the rig profile, and at the bottom the frame number and the timecode
// (HH:MM:SS:FF at the scene's rate, frame 1 = 00:00:00:00). The slate, shown for one second before
// the first frame, lists the same facts with the frame range, resolution, quality and the date.
#pragma once

#include <string>
#include <vector>

#include "render/tracer/image.h"

namespace stirrup::render {

struct BurnInFacts {
  std::string scene;     // e.g. "trot"
  std::string movement;  // the clip's name, e.g. "trot" or "stop"
  std::string view;      // the camera's name, e.g. "side"
  std::string profile;   // rig profile, e.g. "thesis"
  double fps = 24.0;
  std::string frames;    // e.g. "1-72"
  int frame_count = 0;
  std::string quality;   // e.g. "review (16 spp)"
  std::string date;      // the slate's date, YYYY-MM-DD
  std::string title = "stirrup review";
};

// SMPTE-style non-drop timecode of a frame: frame 1 is 00:00:00:00; fps is rounded to whole frames.
std::string timecode(int frame, double fps);

// Draws the burn-in bands onto a rendered (linear) image, in place.
void burnIn(Image& image, const BurnInFacts& facts, int frame);

// Labels the panels of a side-by-side layered frame (equal widths, left to right), below the top band.
void labelPanels(Image& image, const std::vector<std::string>& labels);

// A slate the size of the movie's frames (linear, opaque).
Image makeSlate(int width, int height, const BurnInFacts& facts);

// Today's date in UTC, YYYY-MM-DD.
std::string todayUtc();

}  // namespace stirrup::render
