// A path on the ground for a horse to follow (issue 15): points in the ground plane (cm, world x and z)
// joined by a centripetal Catmull-Rom curve, parametrised by arc length.
//
// Centripetal Catmull-Rom (knot spacing |Δp|^0.5; Yuksel, Schaefer and Keyser 2011, "Parameterization
// and applications of Catmull-Rom curves", Computer-Aided Design 43(7)) passes through every point, is
// C1, and never forms a cusp or a self-intersection inside a segment, whatever the spacing of the
// points: a rider's waypoints are drawn by hand, unevenly. The ends are extended by reflecting the
// second and next-to-last points, so the curve starts and ends heading toward its neighbours.
//
// Arc length: each segment is sampled densely (kSamplesPerSegment chords) once at construction; at(s)
// finds the chord by binary search and refines the curve parameter within it by Newton steps, so the
// position's speed along s is 1 to a part in a million. Built once, then pure lookups.
#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>

namespace stirrup::rig {

class GroundPath {
 public:
  // Points in the ground plane, cm: (world x, world z). Throws rig::InputError "SOURCE: points[i]:
  // expected ..." for fewer than two points, a non-finite coordinate, or a point repeating the one
  // before it (closer than kMinSegmentCm: a zero-length segment has no heading).
  GroundPath(std::vector<glm::dvec2> points, const std::string& source);

  static constexpr double kMinSegmentCm = 1.0;
  // A point's coordinates lie within this of the origin (cm): 100 km, past any shot's ground (our
  // choice: a coordinate of 1e308 would overflow the path's lengths to infinity).
  static constexpr double kMaxCoordinateCm = 1e7;
  static constexpr int kSamplesPerSegment = 256;

  struct Sample {
    glm::dvec2 position{0.0};   // cm, (x, z)
    glm::dvec2 tangent{1.0, 0.0};  // unit
    // The tangent's heading, degrees from +X toward +Z: + is a turn to the right, in the sense of the
    // contract's rearPivot.ry (a horse heading along +X has its right side toward +Z).
    double heading_deg = 0;
    double curvature = 0;       // 1/cm, + turning right, − turning left
  };

  double length() const { return length_; }
  // Arc length at points()[i].
  double distanceAtPoint(std::size_t i) const { return table_s_[i * kSamplesPerSegment]; }
  // The path at arc length s (cm from the first point), clamped to [0, length]: beyond the ends the
  // horse stands at the end, heading along the end tangent.
  Sample at(double s) const;
  const std::vector<glm::dvec2>& points() const { return points_; }

 private:
  struct Hermite {
    glm::dvec2 p1, m1, p2, m2;  // end points and end tangents over u in [0, 1]
  };
  Hermite hermite(int segment) const;
  glm::dvec2 position(int segment, double u) const;      // u in [0, 1] within segment
  glm::dvec2 derivative(int segment, double u) const;    // d position / du
  glm::dvec2 second(int segment, double u) const;        // d² position / du²

  std::vector<glm::dvec2> points_;
  std::vector<glm::dvec2> control_;  // points_ with one reflected point before and after
  std::vector<double> knots_;        // centripetal knot values of control_
  std::vector<double> table_s_;      // arc length at each table entry, (segments × kSamplesPerSegment + 1)
  double length_ = 0;
};

}  // namespace stirrup::rig
