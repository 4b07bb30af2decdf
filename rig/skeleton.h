// A joint hierarchy with its rest (bind) pose. Joints are stored parents first, so one forward pass
// turns local transforms into world transforms without recursion.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace stirrup::rig {

struct Joint {
  std::string name;
  int parent = -1;                // index of the parent joint (always lower than this joint's), -1 for a root
  glm::mat4 rest_local{1.0f};     // rest transform relative to the parent
  glm::mat4 inverse_bind{1.0f};   // inverse of the rest world transform: bind-pose mesh -> joint space
};

struct Skeleton {
  std::vector<Joint> joints;

  // Appends a joint and returns its index. Throws std::invalid_argument on a bad parent or a
  // duplicate name: a malformed character is a programming error, not user input.
  int addJoint(std::string name, int parent, const glm::mat4& rest_local);
  // Index of the joint called name, or -1.
  int find(std::string_view name) const;
  // Index of the joint called name; throws std::out_of_range when there is none.
  int require(std::string_view name) const;
  std::size_t size() const { return joints.size(); }

  glm::mat4 restWorld(int joint) const { return glm::inverse(joints[joint].inverse_bind); }
  glm::vec3 restPosition(int joint) const { return glm::vec3(restWorld(joint)[3]); }
};

// Rest local transforms, one per joint: the starting point of every posing job.
std::vector<glm::mat4> restLocals(const Skeleton& skeleton);
// Rest world transforms, one per joint.
std::vector<glm::mat4> restWorlds(const Skeleton& skeleton);
// world[i] = world[parent] * local[i]; roots take their local as world. Spans are one per joint.
void localToWorld(const Skeleton& skeleton, std::span<const glm::mat4> local, std::span<glm::mat4> world);

}  // namespace stirrup::rig
