// Spine files: the input of `stirrup spine` (bone lengths, segments, layout and poses of the three
// controllers, in cm; docs/curve-spine.md) and the JSON form of a laid spine. Every bad field is a
// one-line InputError naming the file and the field.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/curve_spine.h"

namespace stirrup::rig {

struct SpinePose {
  SpineControllers controllers;
  double stretch = 1.0;
};

struct SpineFile {
  std::array<double, 3> bones{};
  int segments = CurveSpine::kRiderSegments;
  ChainLayout layout = ChainLayout::EqualArcLength;
  std::vector<SpinePose> poses;
};

SpineFile readSpineFile(const std::string& file);
// A laid spine as JSON: FK chain, curve points, lengths, samples and joints (position, rotation
// w,x,y,z, twist in degrees).
nlohmann::json spineResultToJson(const SpineResult& r, double stretch);

}  // namespace stirrup::rig
