#include "rig/cubic_spline.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace stirrup::rig {
namespace {

// Gauss–Legendre 5-point nodes and weights on [−1, 1] (Abramowitz & Stegun, table 25.4).
constexpr std::array<double, 5> kGLNodes = {0.0, -0.5384693101056831, 0.5384693101056831,
                                            -0.9061798459386640, 0.9061798459386640};
constexpr std::array<double, 5> kGLWeights = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                              0.2369268850561891, 0.2369268850561891};

// Two curve points closer than this (cm) still get a positive knot interval.
constexpr double kMinKnotSpacing = 1e-9;

}  // namespace

CubicSpline::CubicSpline(const std::array<glm::dvec3, kPointCount>& points, const glm::dvec3& startDirection,
                       const glm::dvec3& endDirection)
    : points_(points) {
  std::array<double, kSegmentCount> h{};
  knots_[0] = 0.0;
  for (int i = 0; i < kSegmentCount; ++i) {
    const double chord = glm::length(points_[i + 1] - points_[i]);
    h[i] = std::max(std::pow(chord, kCentripetalAlpha), kMinKnotSpacing);
    knots_[i + 1] = knots_[i] + h[i];
  }

  // Clamped ends: the speed |dP/dt| at an end equals the end chord over its knot interval, so the
  // end tangent has the same scale as the interior ones.
  derivatives_[0] = startDirection * (glm::length(points_[1] - points_[0]) / h[0]);
  derivatives_[kSegmentCount] =
      endDirection * (glm::length(points_[kSegmentCount] - points_[kSegmentCount - 1]) / h[kSegmentCount - 1]);

  // C² at interior knot i (a = h[i−1], b = h[i]):
  //   m[i−1]/a + 2 m[i] (1/a + 1/b) + m[i+1]/b = 3 ((P[i] − P[i−1])/a² + (P[i+1] − P[i])/b²).
  // A tridiagonal system in m[1..3], solved by the Thomas algorithm (diagonally dominant).
  constexpr int n = kSegmentCount - 1;
  std::array<double, n> lower{}, diag{}, upper{};
  std::array<glm::dvec3, n> rhs{};
  for (int k = 0; k < n; ++k) {
    const int i = k + 1;
    const double a = h[i - 1], b = h[i];
    lower[k] = 1.0 / a;
    diag[k] = 2.0 * (1.0 / a + 1.0 / b);
    upper[k] = 1.0 / b;
    rhs[k] = 3.0 * ((points_[i] - points_[i - 1]) / (a * a) + (points_[i + 1] - points_[i]) / (b * b));
  }
  rhs[0] -= lower[0] * derivatives_[0];
  rhs[n - 1] -= upper[n - 1] * derivatives_[kSegmentCount];
  for (int k = 1; k < n; ++k) {
    const double w = lower[k] / diag[k - 1];
    diag[k] -= w * upper[k - 1];
    rhs[k] -= w * rhs[k - 1];
  }
  derivatives_[n] = rhs[n - 1] / diag[n - 1];
  for (int k = n - 2; k >= 0; --k) derivatives_[k + 1] = (rhs[k] - upper[k] * derivatives_[k + 2]) / diag[k];

  // Arc-length table.
  cumulative_.reserve(kSegmentCount * kArcSubintervals + 1);
  cumulative_.push_back(0.0);
  for (int i = 0; i < kSegmentCount; ++i) {
    for (int j = 0; j < kArcSubintervals; ++j) {
      const double t0 = knots_[i] + h[i] * j / kArcSubintervals;
      const double t1 = knots_[i] + h[i] * (j + 1) / kArcSubintervals;
      cumulative_.push_back(cumulative_.back() + gaussLegendre(t0, t1));
    }
  }
}

CubicSpline::Local CubicSpline::locate(double t) const {
  t = std::clamp(t, 0.0, endParameter());
  int i = 0;
  while (i < kSegmentCount - 1 && t >= knots_[i + 1]) ++i;
  return {i, (t - knots_[i]) / (knots_[i + 1] - knots_[i])};
}

// Cubic Hermite form of segment i: P(u) = h00 P[i] + h10 h m[i] + h01 P[i+1] + h11 h m[i+1].
glm::dvec3 CubicSpline::point(double t) const {
  const auto [i, u] = locate(t);
  const double h = knots_[i + 1] - knots_[i];
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * points_[i] + (u3 - 2 * u2 + u) * h * derivatives_[i] +
         (-2 * u3 + 3 * u2) * points_[i + 1] + (u3 - u2) * h * derivatives_[i + 1];
}

glm::dvec3 CubicSpline::derivative(double t) const {
  const auto [i, u] = locate(t);
  const double h = knots_[i + 1] - knots_[i];
  const double u2 = u * u;
  return ((6 * u2 - 6 * u) * (points_[i] - points_[i + 1])) / h + (3 * u2 - 4 * u + 1) * derivatives_[i] +
         (3 * u2 - 2 * u) * derivatives_[i + 1];
}

glm::dvec3 CubicSpline::secondDerivative(double t) const {
  const auto [i, u] = locate(t);
  const double h = knots_[i + 1] - knots_[i];
  return ((12 * u - 6) * (points_[i] - points_[i + 1])) / (h * h) +
         ((6 * u - 4) * derivatives_[i] + (6 * u - 2) * derivatives_[i + 1]) / h;
}

glm::dvec3 CubicSpline::tangent(double t) const {
  const glm::dvec3 d = derivative(t);
  const double len = glm::length(d);
  // A zero-speed point (never met by the spine's curves) falls back to the chord to a nearby point.
  if (len > 0.0) return d / len;
  const double eps = 1e-6 * endParameter();
  const double tb = std::min(t + eps, endParameter()), ta = std::max(t - eps, 0.0);
  return glm::normalize(point(tb) - point(ta));
}

double CubicSpline::speed(double t) const { return glm::length(derivative(t)); }

double CubicSpline::gaussLegendre(double t0, double t1) const {
  const double half = 0.5 * (t1 - t0), mid = 0.5 * (t0 + t1);
  double sum = 0.0;
  for (int k = 0; k < 5; ++k) sum += kGLWeights[k] * speed(mid + half * kGLNodes[k]);
  return half * sum;
}

double CubicSpline::arcLengthAt(double t) const {
  t = std::clamp(t, 0.0, endParameter());
  const auto [i, u] = locate(t);
  const int piece = std::min(static_cast<int>(u * kArcSubintervals), kArcSubintervals - 1);
  const double h = knots_[i + 1] - knots_[i];
  const double t0 = knots_[i] + h * piece / kArcSubintervals;
  return cumulative_[i * kArcSubintervals + piece] + gaussLegendre(t0, t);
}

double CubicSpline::parameterAtArcLength(double s) const {
  if (s <= 0.0) return 0.0;
  if (s >= length()) return endParameter();
  // The table piece holding s, then Newton on arcLengthAt(t) − s inside it, bisection as the safeguard.
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const int index = static_cast<int>(it - cumulative_.begin()) - 1;
  const int i = index / kArcSubintervals, piece = index % kArcSubintervals;
  const double h = knots_[i + 1] - knots_[i];
  const double pieceStart = knots_[i] + h * piece / kArcSubintervals;
  double lo = pieceStart;
  double hi = knots_[i] + h * (piece + 1) / kArcSubintervals;
  const double base = cumulative_[index];
  double t = lo + (hi - lo) * (s - base) / std::max(cumulative_[index + 1] - base, 1e-300);
  for (int iter = 0; iter < 50; ++iter) {
    const double f = base + gaussLegendre(pieceStart, t) - s;
    if (f > 0.0) hi = t; else lo = t;
    if (std::abs(f) < 1e-12 * std::max(1.0, length())) break;
    const double v = speed(t);
    double next = v > 0.0 ? t - f / v : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    t = next;
  }
  return t;
}

}  // namespace stirrup::rig
