#include "rig/motion/ground_path.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "rig/error.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {


std::string index(const std::string& source, std::size_t i) {
  return source + ": points[" + std::to_string(i) + "]";
}


}  // namespace

GroundPath::GroundPath(std::vector<glm::dvec2> points, const std::string& source) : points_(std::move(points)) {
  if (points_.size() < 2)
    throw InputError(source + ": points: expected at least two points [x, z] (cm), got " + std::to_string(points_.size()));
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!(std::abs(points_[i].x) <= kMaxCoordinateCm && std::abs(points_[i].y) <= kMaxCoordinateCm))
      throw InputError(index(source, i) + ": expected coordinates from -1e+07 to 1e+07 cm, got [" + numberText(points_[i].x) + ", " +
                       numberText(points_[i].y) + "]");
    if (i > 0 && glm::length(points_[i] - points_[i - 1]) < kMinSegmentCm)
      throw InputError(index(source, i) + ": expected a point at least 1 cm from points[" + std::to_string(i - 1) +
                       "] (a zero-length segment has no heading), got one " +
                       numberText(glm::length(points_[i] - points_[i - 1])) + " cm away");
  }
  // Reflected end points, then centripetal knots (alpha = 1/2).
  control_.reserve(points_.size() + 2);
  control_.push_back(2.0 * points_[0] - points_[1]);
  control_.insert(control_.end(), points_.begin(), points_.end());
  control_.push_back(2.0 * points_.back() - points_[points_.size() - 2]);
  knots_.assign(control_.size(), 0.0);
  for (std::size_t i = 1; i < control_.size(); ++i)
    knots_[i] = knots_[i - 1] + std::sqrt(glm::length(control_[i] - control_[i - 1]));

  const int segments = int(points_.size()) - 1;
  table_s_.assign(std::size_t(segments) * kSamplesPerSegment + 1, 0.0);
  glm::dvec2 prev = points_[0];
  for (int seg = 0; seg < segments; ++seg)
    for (int k = 1; k <= kSamplesPerSegment; ++k) {
      const glm::dvec2 p = position(seg, double(k) / kSamplesPerSegment);
      const std::size_t at = std::size_t(seg) * kSamplesPerSegment + std::size_t(k);
      table_s_[at] = table_s_[at - 1] + glm::length(p - prev);
      prev = p;
    }
  length_ = table_s_.back();
}

// Segment `segment` runs from points_[segment] to points_[segment + 1], i.e. control_[segment + 1] to
// control_[segment + 2]. As a cubic Hermite on u in [0, 1] with the centripetal Catmull-Rom tangents
// (the Barry-Goldman pyramid written out), scaled by the segment's knot span.
GroundPath::Hermite GroundPath::hermite(int segment) const {
  const int i = segment + 1;
  const glm::dvec2 &p0 = control_[i - 1], &p1 = control_[i], &p2 = control_[i + 1], &p3 = control_[i + 2];
  const double t0 = knots_[i - 1], t1 = knots_[i], t2 = knots_[i + 1], t3 = knots_[i + 2];
  return {p1, ((p1 - p0) / (t1 - t0) - (p2 - p0) / (t2 - t0) + (p2 - p1) / (t2 - t1)) * (t2 - t1), p2,
          ((p2 - p1) / (t2 - t1) - (p3 - p1) / (t3 - t1) + (p3 - p2) / (t3 - t2)) * (t2 - t1)};
}

glm::dvec2 GroundPath::position(int segment, double u) const {
  const Hermite c = hermite(segment);
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * c.p1 + (u3 - 2 * u2 + u) * c.m1 + (-2 * u3 + 3 * u2) * c.p2 + (u3 - u2) * c.m2;
}

glm::dvec2 GroundPath::derivative(int segment, double u) const {
  const Hermite c = hermite(segment);
  const double u2 = u * u;
  return (6 * u2 - 6 * u) * c.p1 + (3 * u2 - 4 * u + 1) * c.m1 + (-6 * u2 + 6 * u) * c.p2 + (3 * u2 - 2 * u) * c.m2;
}

glm::dvec2 GroundPath::second(int segment, double u) const {
  const Hermite c = hermite(segment);
  return (12 * u - 6) * c.p1 + (6 * u - 4) * c.m1 + (-12 * u + 6) * c.p2 + (6 * u - 2) * c.m2;
}

GroundPath::Sample GroundPath::at(double s) const {
  s = std::clamp(std::isfinite(s) ? s : 0.0, 0.0, length_);
  // The table entry at or before s, then the curve parameter interpolated along that chord.
  const auto it = std::upper_bound(table_s_.begin(), table_s_.end(), s);
  std::size_t k = std::size_t(std::max<std::ptrdiff_t>(0, (it - table_s_.begin()) - 1));
  k = std::min(k, table_s_.size() - 2);
  const double chord = table_s_[k + 1] - table_s_[k];
  const double f = chord > 0.0 ? (s - table_s_[k]) / chord : 0.0;
  const int segment = int(k / kSamplesPerSegment);
  const double u0 = double(k % kSamplesPerSegment) / kSamplesPerSegment;
  double u = u0 + f / kSamplesPerSegment;
  // Two Newton steps on the arc length from the table entry (the chord from u0 stands for the arc, a
  // 1/256 of a segment), so |d position / ds| is 1 to a part in a million instead of a thousand.
  const glm::dvec2 p0 = position(segment, u0);
  for (int iteration = 0; iteration < 2; ++iteration) {
    const double speed = glm::length(derivative(segment, u));
    if (!(speed > 1e-12)) break;
    u = std::clamp(u + (s - table_s_[k] - glm::length(position(segment, u) - p0)) / speed, 0.0, 1.0);
  }
  Sample out;
  out.position = position(segment, u);
  const glm::dvec2 d1 = derivative(segment, u), d2 = second(segment, u);
  const double speed = glm::length(d1);
  if (speed > 1e-12) {
    out.tangent = d1 / speed;
    out.curvature = (d1.x * d2.y - d1.y * d2.x) / (speed * speed * speed);
  }
  out.heading_deg = std::atan2(out.tangent.y, out.tangent.x) * kDegreesPerRadian;
  return out;
}

}  // namespace stirrup::rig
