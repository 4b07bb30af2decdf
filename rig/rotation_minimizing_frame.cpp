#include "rig/rotation_minimizing_frame.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace stirrup::rig {
namespace {

// Reflection of v in the plane through the origin with normal n (c = n·n).
glm::dvec3 reflect(const glm::dvec3& v, const glm::dvec3& n, double c) { return v - (2.0 / c) * glm::dot(n, v) * n; }

// Reflections with a normal shorter than this (relative) are skipped: the points or tangents coincide.
constexpr double kTinyReflection = 1e-24;

}  // namespace

glm::dquat transportFrame(const glm::dquat& frame, const glm::dvec3& from, const glm::dvec3& to,
                          const glm::dvec3& toTangent) {
  const glm::dvec3 t = frame * glm::dvec3(1, 0, 0);
  const glm::dvec3 r = frame * glm::dvec3(0, 1, 0);
  // Wang et al. 2008, Algorithm: v1 = x[i+1] − x[i]; rL, tL reflected; v2 = t[i+1] − tL; r[i+1].
  const glm::dvec3 v1 = to - from;
  const double c1 = glm::dot(v1, v1);
  glm::dvec3 rL = r, tL = t;
  if (c1 > kTinyReflection) {
    rL = reflect(r, v1, c1);
    tL = reflect(t, v1, c1);
  }
  const glm::dvec3 v2 = toTangent - tL;
  const double c2 = glm::dot(v2, v2);
  glm::dvec3 rNext = c2 > kTinyReflection ? reflect(rL, v2, c2) : rL;
  // Remove round-off so the new frame is exactly orthonormal.
  rNext = glm::normalize(rNext - glm::dot(rNext, toTangent) * toTangent);

  const glm::dmat3 before(t, r, glm::cross(t, r));
  const glm::dmat3 after(toTangent, rNext, glm::cross(toTangent, rNext));
  glm::dquat step = glm::quat_cast(after * glm::transpose(before));
  if (step.w < 0.0) step = -step;
  return glm::normalize(step * frame);
}

glm::dquat shortestArc(const glm::dvec3& a, const glm::dvec3& b) {
  // q = (1 + a·b, a×b) normalised: half the angle between a and b, about their common normal.
  const glm::dvec3 axis = glm::cross(a, b);
  return glm::normalize(glm::dquat(1.0 + glm::dot(a, b), axis.x, axis.y, axis.z));
}

}  // namespace stirrup::rig
