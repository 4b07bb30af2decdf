#include "rig/motion/crowd_middle_clip.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stirrup::rig {

CrowdMiddleClip::CrowdMiddleClip(std::vector<const Clip*> clips) : clips_(std::move(clips)) {
  if (clips_.empty()) throw std::invalid_argument("CrowdMiddleClip: no pairs");
  for (const Clip* c : clips_)
    if (!c) throw std::invalid_argument("CrowdMiddleClip: a pair without a clip");
  for (const Clip* c : clips_) duration_ = std::max(duration_, c->duration());
  // A second past the end: cameras look a little ahead of a frame (a follow filter's velocity).
  const auto points = static_cast<std::size_t>(std::ceil((duration_ + 1.0) / kCrowdMiddleTableStepS)) + 1;
  table_.reserve(points);
  for (std::size_t i = 0; i < points; ++i) table_.push_back(average(double(i) * kCrowdMiddleTableStepS));
}

double CrowdMiddleClip::duration() const { return duration_; }

HorseFrame CrowdMiddleClip::sample(double seconds) const {
  const double at = seconds / kCrowdMiddleTableStepS;
  if (!(at >= 0.0 && at < double(table_.size() - 1))) return average(seconds);
  const auto i = static_cast<std::size_t>(at);
  const double f = at - double(i);
  const HorseFrame& a = table_[i];
  const HorseFrame& b = table_[i + 1];
  HorseFrame out;
  out.travel_cm = a.travel_cm + f * (b.travel_cm - a.travel_cm);
  out.travel_z_cm = a.travel_z_cm + f * (b.travel_z_cm - a.travel_z_cm);
  out.ground_y_cm = a.ground_y_cm + f * (b.ground_y_cm - a.ground_y_cm);
  const double ra = a.heading_deg * (3.14159265358979323846 / 180.0), rb = b.heading_deg * (3.14159265358979323846 / 180.0);
  const double c = std::cos(ra) + f * (std::cos(rb) - std::cos(ra)), s = std::sin(ra) + f * (std::sin(rb) - std::sin(ra));
  out.heading_deg = (c == 0.0 && s == 0.0) ? 0.0 : std::atan2(s, c) * (180.0 / 3.14159265358979323846);
  return out;
}

HorseFrame CrowdMiddleClip::average(double seconds) const {
  HorseFrame out;
  double x = 0.0, z = 0.0, y = 0.0, cos_sum = 0.0, sin_sum = 0.0;
  for (const Clip* c : clips_) {
    const HorseFrame f = c->sampleTravel(seconds);
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
