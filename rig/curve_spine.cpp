#include "rig/curve_spine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/mat3x3.hpp>

#include "rig/rotation_minimizing_frame.h"

namespace stirrup::rig {
namespace {

const glm::dvec3 kBoneAxis(1.0, 0.0, 0.0);

double radians(double degrees) { return degrees * glm::pi<double>() / 180.0; }

// Chain layout: Newton iterations and the residual (relative to the curve length) that stops them.
constexpr int kLayoutIterations = 100;
constexpr double kLayoutTolerance = 1e-13;
// Rotation-minimizing frame: double-reflection steps per cubic segment (its error is O(h^4)).
constexpr int kFrameStepsPerSegment = 64;

// Solves A x = b in place by Gaussian elimination with partial pivoting (n ≤ 33); false if singular.
bool solveLinear(std::vector<double>& a, std::vector<double>& b, int n) {
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int row = col + 1; row < n; ++row)
      if (std::abs(a[row * n + col]) > std::abs(a[pivot * n + col])) pivot = row;
    if (std::abs(a[pivot * n + col]) < 1e-300) return false;
    if (pivot != col) {
      for (int k = 0; k < n; ++k) std::swap(a[col * n + k], a[pivot * n + k]);
      std::swap(b[col], b[pivot]);
    }
    for (int row = col + 1; row < n; ++row) {
      const double f = a[row * n + col] / a[col * n + col];
      if (f == 0.0) continue;
      for (int k = col; k < n; ++k) a[row * n + k] -= f * a[col * n + k];
      b[row] -= f * b[col];
    }
  }
  for (int row = n - 1; row >= 0; --row) {
    double sum = b[row];
    for (int k = row + 1; k < n; ++k) sum -= a[row * n + k] * b[k];
    b[row] = sum / a[row * n + row];
  }
  return true;
}

// Equal chords with every joint on the curve: the arc lengths s[1..N−1] of the inner joints and the
// chord c solving |P(s[j]) − P(s[j−1])| = c for j = 1..N, with s[0] = 0 and s[N] = L. Newton's method
// from the equal-arc-length layout, which is off by only the chord-vs-arc deficit; starting there
// keeps the solution on the branch that moves continuously with the pose (a sphere-marching layout
// jumps where the curve folds back within one bone). Returns c, or a negative value if Newton fails,
// in which case `s` keeps the equal-arc-length layout.
double layEqualChords(const CubicSpline& curve, std::vector<double>& s) {
  const int n = static_cast<int>(s.size()) - 1;
  const double length = curve.length();
  for (int j = 0; j <= n; ++j) s[j] = length * j / n;

  // Joint positions, unit tangents dP/ds and residuals g[j−1] = |P(s[j]) − P(s[j−1])| − c.
  struct State {
    std::vector<glm::dvec3> p, tangent;
    std::vector<double> g;
    double norm = 0.0;
  };
  const auto evaluate = [&](const std::vector<double>& at, double chord) {
    State st{std::vector<glm::dvec3>(n + 1), std::vector<glm::dvec3>(n + 1), std::vector<double>(n), 0.0};
    for (int j = 0; j <= n; ++j) {
      const double t = curve.parameterAtArcLength(at[j]);
      st.p[j] = curve.point(t);
      st.tangent[j] = curve.tangent(t);
    }
    for (int j = 1; j <= n; ++j) {
      st.g[j - 1] = glm::length(st.p[j] - st.p[j - 1]) - chord;
      st.norm = std::max(st.norm, std::abs(st.g[j - 1]));
    }
    return st;
  };

  std::vector<double> x = s;
  double chord = length / n;
  State st = evaluate(x, chord);
  for (int iter = 0; iter < kLayoutIterations; ++iter) {
    if (st.norm < kLayoutTolerance * length) {
      s = x;
      return chord;
    }
    // Unknowns (s[1], …, s[N−1], c); Jacobian of g, then a Newton step halved until it helps.
    std::vector<double> jac(n * n, 0.0), step(n);
    for (int j = 1; j <= n; ++j) {
      const glm::dvec3 d = st.p[j] - st.p[j - 1];
      const double len = glm::length(d);
      if (len <= 0.0) return -1.0;
      const glm::dvec3 u = d / len;
      if (j < n) jac[(j - 1) * n + (j - 1)] = glm::dot(u, st.tangent[j]);
      if (j > 1) jac[(j - 1) * n + (j - 2)] = -glm::dot(u, st.tangent[j - 1]);
      jac[(j - 1) * n + (n - 1)] = -1.0;
      step[j - 1] = -st.g[j - 1];
    }
    if (!solveLinear(jac, step, n)) return -1.0;
    bool improved = false;
    for (double damping = 1.0; damping > 1e-9 && !improved; damping *= 0.5) {
      std::vector<double> trial = x;
      for (int j = 1; j < n; ++j) trial[j] += damping * step[j - 1];
      const double trialChord = chord + damping * step[n - 1];
      bool ordered = trialChord > 0.0;
      for (int j = 1; j <= n && ordered; ++j) ordered = trial[j] > trial[j - 1];
      if (!ordered) continue;
      State next = evaluate(trial, trialChord);
      if (next.norm < st.norm) {
        x = std::move(trial), chord = trialChord, st = std::move(next);
        improved = true;
      }
    }
    if (!improved) return -1.0;
  }
  return -1.0;
}

}  // namespace

glm::dquat controllerRotation(const glm::dvec3& degrees) {
  const glm::dquat rx = glm::angleAxis(radians(degrees.x), glm::dvec3(1, 0, 0));
  const glm::dquat ry = glm::angleAxis(radians(degrees.y), glm::dvec3(0, 1, 0));
  const glm::dquat rz = glm::angleAxis(radians(degrees.z), glm::dvec3(0, 0, 1));
  return rz * ry * rx;
}

glm::dquat restBoneFrame() {
  // Columns: where bone x, y, z go in the world.
  return glm::quat_cast(glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1)));
}

double tenNullLengthEstimate(const CubicSpline& curve) {
  const int gaps = kRaisaniLengthNulls - 1;
  const glm::dvec3 n1 = curve.point(0.0);
  const glm::dvec3 n2 = curve.pointAtArcLength(curve.length() / gaps);
  return glm::length(n2 - n1) * gaps;
}

CurveSpine::CurveSpine(std::array<double, 3> boneLengths, int segments, ChainLayout layout)
    : lengths_(boneLengths), segments_(segments), layout_(layout) {
  for (double l : lengths_)
    if (!(std::isfinite(l) && l > 0.0))
      throw std::invalid_argument("CurveSpine: bone length " + std::to_string(l) + " is not positive");
  if (segments < kMinSegments || segments > kMaxSegments)
    throw std::invalid_argument("CurveSpine: segments " + std::to_string(segments) + " is outside 3..32");
}

std::array<glm::dquat, 3> CurveSpine::controllerFrames(const SpineControllers& c) const {
  std::array<glm::dquat, 3> frames;
  frames[0] = restBoneFrame() * controllerRotation(c.lower);
  frames[1] = frames[0] * controllerRotation(c.middle);
  frames[2] = frames[1] * controllerRotation(c.top);
  return frames;
}

std::array<glm::dvec3, 4> CurveSpine::fkJoints(const SpineControllers& c, double stretch) const {
  const std::array<glm::dquat, 3> frames = controllerFrames(c);
  std::array<glm::dvec3, 4> p{};
  for (int k = 0; k < 3; ++k) p[k + 1] = p[k] + (stretch * lengths_[k]) * (frames[k] * kBoneAxis);
  return p;
}

CubicSpline CurveSpine::curve(const SpineControllers& c, double stretch) const {
  const std::array<glm::dquat, 3> frames = controllerFrames(c);
  const std::array<glm::dvec3, 4> p = fkJoints(c, stretch);
  // Raisani 2004, Part III §1: the points sit at the bone centres "to avoid the curve bending on the
  // hinge of two bones".
  const std::array<glm::dvec3, 5> points = {p[0], 0.5 * (p[0] + p[1]), 0.5 * (p[1] + p[2]),
                                            0.5 * (p[2] + p[3]), p[3]};
  return CubicSpline(points, frames[0] * kBoneAxis, frames[2] * kBoneAxis);
}

std::vector<glm::dquat> CurveSpine::framesAt(const SpineControllers& c, double stretch,
                                             const std::vector<double>& fractions) const {
  if (!(std::isfinite(stretch) && stretch > 0.0))
    throw std::invalid_argument("CurveSpine: stretch " + std::to_string(stretch) + " is not positive");
  const CubicSpline spline = curve(c, stretch);
  const double length = spline.length(), end = spline.endParameter();
  const double step = end / (kFrameStepsPerSegment * CubicSpline::kSegmentCount);
  std::vector<glm::dquat> out;
  out.reserve(fractions.size());
  glm::dquat frame = controllerFrames(c)[0];
  double at = 0.0, previous = 0.0;
  glm::dvec3 here = spline.point(at);  // spline.point(at), carried from step to step
  for (const double f : fractions) {
    if (!(f >= previous && f <= 1.0))
      throw std::invalid_argument("CurveSpine::framesAt: fractions must ascend within 0..1");
    previous = f;
    const double target = f >= 1.0 ? end : spline.parameterAtArcLength(length * f);
    while (at < target) {
      const double next = std::min(at + step, target);
      const glm::dvec3 there = spline.point(next);
      frame = transportFrame(frame, here, there, spline.tangent(next));
      at = next, here = there;
    }
    const glm::dvec3 axis = spline.tangent(at);
    out.push_back(glm::normalize(glm::angleAxis(radians(c.top.x * f), axis) * frame));
  }
  return out;
}

SpineResult CurveSpine::solve(const SpineControllers& c, double stretch, SpineDetail detail) const {
  if (!(std::isfinite(stretch) && stretch > 0.0))
    throw std::invalid_argument("CurveSpine: stretch " + std::to_string(stretch) + " is not positive");
  const int n = segments_;
  const std::array<glm::dquat, 3> frames = controllerFrames(c);
  const CubicSpline spline = curve(c, stretch);

  SpineResult r;
  r.fk = fkJoints(c, stretch);
  r.curve_points = {r.fk[0], 0.5 * (r.fk[0] + r.fk[1]), 0.5 * (r.fk[1] + r.fk[2]), 0.5 * (r.fk[2] + r.fk[3]),
                    r.fk[3]};
  r.length = spline.length();
  if (detail == SpineDetail::Full) {
    r.ten_null_length = tenNullLengthEstimate(spline);
    r.samples.reserve(kSampleCount);
    for (int k = 0; k < kSampleCount; ++k) r.samples.push_back(spline.pointAtArcLength(r.length * k / (kSampleCount - 1)));
  }

  // Every joint on the curve, the first and last at its ends; bones equal in the layout's measure.
  r.layout = layout_;
  r.joint_arc_lengths.assign(n + 1, 0.0);
  for (int j = 0; j <= n; ++j) r.joint_arc_lengths[j] = r.length * j / n;
  double chord = r.length / n;
  if (layout_ == ChainLayout::EqualChord) {
    chord = layEqualChords(spline, r.joint_arc_lengths);
    r.layout_converged = chord > 0.0;
  }
  std::vector<double> t(n + 1);
  for (int j = 0; j <= n; ++j) t[j] = spline.parameterAtArcLength(r.joint_arc_lengths[j]);
  const double end = spline.endParameter();
  t[0] = 0.0;
  t[n] = end;
  double sum = 0.0;
  r.bone_chords.resize(n);
  for (int j = 0; j < n; ++j) sum += r.bone_chords[j] = glm::length(spline.point(t[j + 1]) - spline.point(t[j]));
  if (layout_ == ChainLayout::EqualArcLength) {
    r.bone_length = r.length / n;
  } else {
    r.bone_length = r.layout_converged ? chord : sum / n;
  }
  r.chain_length = layout_ == ChainLayout::EqualArcLength ? r.length : sum;
  r.chain_deficit = 1.0 - sum / r.length;

  // Where frames are needed: the arc-length middle of every bone, and the end of the curve.
  std::vector<double> targets(n + 1);
  for (int j = 0; j < n; ++j)
    targets[j] = spline.parameterAtArcLength(0.5 * (r.joint_arc_lengths[j] + r.joint_arc_lengths[j + 1]));
  targets[n] = end;

  // Transport the lower controller's frame along the curve. The clamped start tangent is bone 1's
  // axis, so the first frame is the controller's frame itself.
  std::vector<glm::dquat> rmf(n + 1);
  glm::dquat frame = frames[0];
  double at = 0.0;
  glm::dvec3 here = spline.point(at);  // spline.point(at), carried from step to step
  const double step = end / (kFrameStepsPerSegment * CubicSpline::kSegmentCount);
  for (int j = 0; j <= n; ++j) {
    while (at < targets[j]) {
      const double next = std::min(at + step, targets[j]);
      const glm::dvec3 there = spline.point(next);
      frame = transportFrame(frame, here, there, spline.tangent(next));
      at = next, here = there;
    }
    rmf[j] = frame;
  }

  // Joint frames: the RMF at the bone's middle turned onto the chord, then the scalar twist.
  const double topTwist = c.top.x;
  r.joints.resize(n + 1);
  r.untwisted_rotations.resize(n + 1);
  r.twist_deg.resize(n + 1);
  for (int j = 0; j <= n; ++j) {
    r.joints[j].position = spline.point(t[j]);
    glm::dvec3 axis;
    if (j < n) {
      axis = glm::normalize(spline.point(t[j + 1]) - spline.point(t[j]));
      r.untwisted_rotations[j] = glm::normalize(shortestArc(rmf[j] * kBoneAxis, axis) * rmf[j]);
      r.twist_deg[j] = topTwist * (j + 1) / n;  // bone j+1 carries (j+1)·rx/N
    } else {
      axis = spline.tangent(end);
      r.untwisted_rotations[j] = rmf[j];
      r.twist_deg[j] = topTwist;
    }
    r.joints[j].rotation =
        glm::normalize(glm::angleAxis(radians(r.twist_deg[j]), axis) * r.untwisted_rotations[j]);
  }
  return r;
}

}  // namespace stirrup::rig
