// One step of a rotation-minimizing frame along a curve by the double-reflection method (Wang, Jüttler,
// Zheng & Liu 2008, "Computation of rotation minimizing frames", ACM TOG 27(1):2). Unlike the Frenet
// frame it is defined on straight pieces (a spine at rest is straight) and never flips when the
// curvature changes sign, and it adds no twist of its own: twist is added on top as a scalar.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace stirrup::rig {

// `frame` maps local axes to world with its x axis the unit tangent at `from`. Returns the frame at
// `to`, whose x axis is `toTangent` (unit): reflect in the bisector plane of from→to, then in the plane
// that takes the reflected tangent onto `toTangent`. The step's rotation is composed onto `frame` as a
// quaternion with non-negative real part, so the result changes continuously with the curve.
glm::dquat transportFrame(const glm::dquat& frame, const glm::dvec3& from, const glm::dvec3& to,
                          const glm::dvec3& toTangent);

// The rotation with the smallest angle that turns unit vector `a` onto unit vector `b` (a ≠ −b).
glm::dquat shortestArc(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace stirrup::rig
