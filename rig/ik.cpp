#include "rig/ik.h"

#include <algorithm>
#include <cmath>

namespace stirrup::rig {
namespace {

// Any unit vector perpendicular to v (v unit).
glm::vec3 anyPerpendicular(glm::vec3 v) {
  const glm::vec3 axis = std::abs(v.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(v, axis));
}

}  // namespace

TwoBoneIkResult solveTwoBoneIk(const TwoBoneIkInput& in) {
  const float a = std::max(in.upper_length, 1e-6f);
  const float b = std::max(in.lower_length, 1e-6f);
  const float full = a + b;
  glm::vec3 to_target = in.target - in.root;
  float d = glm::length(to_target);
  glm::vec3 dir = d > 1e-6f ? to_target / d : glm::vec3(0, -1, 0);

  // Clamp the reach: a hard clamp at full reach is continuous and monotone; softening additionally
  // makes the approach to straight C1 so a limb pulled past reach does not lock with a pop.
  float reach = d;
  const float soften = std::clamp(in.soften, 0.0f, full * 0.5f);
  const float soft_start = full - soften;
  if (soften > 0.0f && d > soft_start)
    reach = soft_start + soften * (1.0f - std::exp(-(d - soft_start) / soften));
  reach = std::min(reach, full);
  const float min_reach = std::min(std::abs(a - b) * in.min_reach_fraction + 1e-4f, full);
  reach = std::max(reach, min_reach);

  // Bend plane: spanned by the reach direction and the pole, projected perpendicular to the reach.
  glm::vec3 to_pole = in.pole - in.root;
  glm::vec3 up = to_pole - dir * glm::dot(to_pole, dir);
  const float up_len = glm::length(up);
  up = up_len > 1e-6f ? up / up_len : anyPerpendicular(dir);

  // Law of cosines: distance of the middle joint along and across the reach line.
  const float along = (a * a - b * b + reach * reach) / (2.0f * reach);
  const float across = std::sqrt(std::max(a * a - along * along, 0.0f));

  TwoBoneIkResult r;
  r.middle = in.root + dir * along + up * across;
  r.end = in.root + dir * reach;
  r.bend_normal = glm::normalize(glm::cross(dir, up));
  r.reached = glm::length(r.end - in.target) <= 1e-3f;
  return r;
}

glm::mat3 boneRotation(glm::vec3 rest_dir, glm::vec3 rest_normal, glm::vec3 dir, glm::vec3 normal) {
  // Orthonormal frames (direction, normal, binormal) before and after; R = after * before^T.
  auto frame = [](glm::vec3 x, glm::vec3 n) {
    x = glm::normalize(x);
    n = n - x * glm::dot(n, x);
    n = glm::length(n) > 1e-6f ? glm::normalize(n) : anyPerpendicular(x);
    return glm::mat3(x, n, glm::cross(x, n));
  };
  const glm::mat3 before = frame(rest_dir, rest_normal);
  const glm::mat3 after = frame(dir, normal);
  return after * glm::transpose(before);
}

}  // namespace stirrup::rig

namespace stirrup::rig {

glm::vec3 restPole(glm::vec3 root, glm::vec3 middle, glm::vec3 end, float distance) {
  const glm::vec3 chord = end - root;
  const float t = glm::dot(middle - root, chord) / std::max(glm::dot(chord, chord), 1e-8f);
  glm::vec3 bend = middle - (root + chord * t);
  if (glm::length(bend) < 1e-5f) bend = glm::cross(chord, glm::vec3(0.0f, 0.0f, 1.0f));
  return middle + glm::normalize(bend) * distance;
}

LimbPose solveLimb(glm::vec3 rest_root, glm::vec3 rest_middle, glm::vec3 rest_end, glm::vec3 rest_pole,
                   glm::vec3 root, glm::vec3 target, glm::vec3 pole, float soften) {
  TwoBoneIkInput rest;
  rest.root = rest_root;
  rest.upper_length = glm::length(rest_middle - rest_root);
  rest.lower_length = glm::length(rest_end - rest_middle);
  rest.target = rest_end;
  rest.pole = rest_pole;
  const glm::vec3 rest_normal = solveTwoBoneIk(rest).bend_normal;

  TwoBoneIkInput in = rest;
  in.root = root;
  in.target = target;
  in.pole = pole;
  in.soften = soften;
  const TwoBoneIkResult r = solveTwoBoneIk(in);
  const auto place = [](glm::vec3 at, const glm::mat3& rotation) {
    glm::mat4 m(rotation);
    m[3] = glm::vec4(at, 1.0f);
    return m;
  };
  LimbPose out;
  out.upper = place(root, boneRotation(rest_middle - rest_root, rest_normal, r.middle - root, r.bend_normal));
  out.middle = place(r.middle, boneRotation(rest_end - rest_middle, rest_normal, r.end - r.middle, r.bend_normal));
  out.end = r.end;
  return out;
}

}  // namespace stirrup::rig
