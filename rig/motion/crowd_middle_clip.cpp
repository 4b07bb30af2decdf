#include "rig/motion/crowd_middle_clip.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stirrup::rig {

CrowdMiddleClip::CrowdMiddleClip(std::vector<const Clip*> clips) : clips_(std::move(clips)) {
  if (clips_.empty()) throw std::invalid_argument("CrowdMiddleClip: no pairs");
  for (const Clip* c : clips_)
    if (!c) throw std::invalid_argument("CrowdMiddleClip: a pair without a clip");
}

double CrowdMiddleClip::duration() const {
  double d = 0.0;
  for (const Clip* c : clips_) d = std::max(d, c->duration());
  return d;
}

HorseFrame CrowdMiddleClip::sample(double seconds) const {
  HorseFrame out;
  double x = 0.0, z = 0.0, y = 0.0, cos_sum = 0.0, sin_sum = 0.0;
  for (const Clip* c : clips_) {
    const HorseFrame f = c->sample(seconds);
    x += f.travel_cm, z += f.travel_z_cm, y += f.ground_y_cm;
    const double a = f.heading_deg * (3.14159265358979323846 / 180.0);
    cos_sum += std::cos(a), sin_sum += std::sin(a);
  }
  const double n = double(clips_.size());
  out.travel_cm = x / n;
  out.travel_z_cm = z / n;
  out.ground_y_cm = y / n;
  // Mean of directions, not of angles: headings of 179 and -179 degrees mean 180, not 0.
  out.heading_deg = (cos_sum == 0.0 && sin_sum == 0.0) ? 0.0 : std::atan2(sin_sum, cos_sum) * (180.0 / 3.14159265358979323846);
  return out;
}

}  // namespace stirrup::rig
