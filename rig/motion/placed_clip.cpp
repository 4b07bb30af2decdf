#include "rig/motion/placed_clip.h"

#include <cmath>

#include "rig/units.h"

namespace stirrup::rig {

PlacedClip::PlacedClip(std::shared_ptr<const Clip> clip, glm::dvec2 from, glm::dvec2 to, double turn_deg)
    : clip_(std::move(clip)), from_(from), to_(to), turn_deg_(turn_deg),
      cos_(std::cos(turn_deg * kRadiansPerDegree)), sin_(std::sin(turn_deg * kRadiansPerDegree)) {}

HorseFrame PlacedClip::placed(HorseFrame f) const {
  // The heading turns +X toward +Z (rig/clip.h): a turn by d takes (x, z) to (x cos d - z sin d, x sin d + z cos d).
  const glm::dvec2 p = glm::dvec2(f.travel_cm, f.travel_z_cm) - from_;
  f.travel_cm = to_.x + p.x * cos_ - p.y * sin_;
  f.travel_z_cm = to_.y + p.x * sin_ + p.y * cos_;
  f.heading_deg += turn_deg_;
  return f;
}

}  // namespace stirrup::rig
