// A clamped C² cubic spline through five points, with an exact arc-length table: the curve a curve
// spine (rig/curve_spine.h) lays its chain on, through the root of bone 1, the three bone midpoints and
// the tip of bone 3 (Raisani 2004, Part III §1).
//
// Parameterisation: centripetal knots (knot spacing |P[i+1] − P[i]|^½, Lee 1989; Yuksel, Schaefer &
// Keyser 2011), which keeps the curve from cusping or looping when controller bends squeeze two points
// together. End conditions: clamped ("complete" spline) — the curve leaves the root along bone 1 and
// arrives at the tip along bone 3, so the chain starts in the lower controller's direction and ends in
// the top controller's. The spline is C² at the three interior knots.
//
// Arc length: 5-point Gauss–Legendre on each of kArcSubintervals pieces of every cubic segment, summed
// into a table; s → t is inverted by a table lookup and a safeguarded Newton iteration (ds/dt = |P'|).
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

namespace stirrup::rig {

class CubicSpline {
 public:
  static constexpr int kPointCount = 5;
  static constexpr int kSegmentCount = kPointCount - 1;
  // Centripetal parameterisation exponent (Lee 1989; 0 = uniform, 1 = chord length).
  static constexpr double kCentripetalAlpha = 0.5;
  // Gauss–Legendre pieces per cubic segment: 5-point GL is exact for polynomials of degree 9, and
  // |P'| of a cubic is smooth but not polynomial; 16 pieces keep the error below 1e-9 of the length
  // even for the hairpins of ±179° bends (tests/rig/curve_spine_test.cpp checks it against 2e5 chords).
  static constexpr int kArcSubintervals = 16;

  // `points` are interpolated in order; `startDirection` and `endDirection` (unit) fix the tangents.
  CubicSpline(const std::array<glm::dvec3, kPointCount>& points, const glm::dvec3& startDirection,
             const glm::dvec3& endDirection);

  // The curve parameter runs over [0, endParameter()]; knot i is at knot(i).
  double endParameter() const { return knots_[kSegmentCount]; }
  double knot(int i) const { return knots_[i]; }

  glm::dvec3 point(double t) const;
  glm::dvec3 derivative(double t) const;
  glm::dvec3 secondDerivative(double t) const;
  // Unit tangent dP/dt / |dP/dt|.
  glm::dvec3 tangent(double t) const;

  // Exact (to quadrature precision) length of the whole curve and of [0, t].
  double length() const { return cumulative_.back(); }
  double arcLengthAt(double t) const;
  // The parameter t with arcLengthAt(t) = s (s clamped to [0, length()]).
  double parameterAtArcLength(double s) const;
  glm::dvec3 pointAtArcLength(double s) const { return point(parameterAtArcLength(s)); }

 private:
  struct Local {
    int segment;
    double u;  // in [0, 1]
  };
  Local locate(double t) const;
  double speed(double t) const;
  double gaussLegendre(double t0, double t1) const;

  std::array<glm::dvec3, kPointCount> points_;
  std::array<glm::dvec3, kPointCount> derivatives_;  // dP/dt at the knots
  std::array<double, kPointCount> knots_;
  // Arc length at the start of every Gauss–Legendre piece, plus the total at the end.
  std::vector<double> cumulative_;
};

}  // namespace stirrup::rig
