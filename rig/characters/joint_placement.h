// How the character generators place joints, shared by the horse and the rider.
#pragma once

#include <string>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/vec3.hpp>

#include "rig/skeleton.h"

namespace stirrup::rig {

// A point on the character's left (side = -1) or right (side = +1) from its right-side position.
inline glm::vec3 mirrorZ(glm::vec3 v, float side) { return {v.x, v.y, v.z * side}; }

// Joints are placed by bind-pose world position with identity orientation: the local rest
// transform is the offset from the parent, which keeps posing maths in world terms.
inline int addJointAt(Skeleton& s, std::string name, int parent, glm::vec3 world) {
  const glm::vec3 parent_pos = parent < 0 ? glm::vec3(0.0f) : s.restPosition(parent);
  return s.addJoint(std::move(name), parent, glm::translate(glm::mat4(1.0f), world - parent_pos));
}

}  // namespace stirrup::rig
