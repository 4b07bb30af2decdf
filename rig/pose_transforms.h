// The small transforms that posing the horse, the rider and the tack share (rig/horse_pose.cpp,
// rig/rider_pose.cpp, rig/tack_pose.cpp, rig/pose.cpp; the leg IK and the seating take a point's move and
// a translation from here too): for the rig's own files, not a public interface.
#pragma once

#include <span>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "rig/character.h"
#include "rig/skeleton.h"

namespace stirrup::rig::pose_transforms {

inline constexpr glm::vec3 kX{1.0f, 0.0f, 0.0f}, kY{0.0f, 1.0f, 0.0f}, kZ{0.0f, 0.0f, 1.0f};

// Joints below the ones a solve placed (`solved`), which it did not place themselves, follow their
// parents by their local transforms (parents come before children in the skeleton).
inline void carryUnsolved(const Skeleton& s, std::span<const glm::mat4> local, const std::vector<char>& solved,
                          std::span<glm::mat4> world) {
  std::vector<char> moved = solved;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int p = s.joints[j].parent;
    if (solved[j] || p < 0 || !moved[p]) continue;
    world[j] = world[p] * local[j];
    moved[j] = 1;
  }
}

inline glm::mat4 rot(double degrees, glm::vec3 axis) {
  return glm::rotate(glm::mat4(1.0f), glm::radians(static_cast<float>(degrees)), axis);
}

inline glm::mat4 translate(glm::vec3 t) { return glm::translate(glm::mat4(1.0f), t); }
inline glm::vec3 position(const glm::mat4& m) { return glm::vec3(m[3]); }
inline glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

// Rest local with an extra translation (in the parent's frame) and rotation.
inline glm::mat4 offsetLocal(const Joint& j, glm::vec3 extra_translation, const glm::mat4& rotation) {
  return translate(extra_translation) * j.rest_local * rotation;
}

// The rigid motion a joint has made from its bind pose: world * inverse bind.
inline glm::mat4 motion(const Skeleton& s, std::span<const glm::mat4> world, int joint) {
  return world[joint] * s.joints[joint].inverse_bind;
}

inline void checkSize(const Character& c, std::span<const glm::mat4> world) {
  if (world.size() != c.skeleton.size())
    throw std::invalid_argument("pose: expected one world matrix per joint of " + c.name);
}

}  // namespace stirrup::rig::pose_transforms
