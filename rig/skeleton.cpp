#include "rig/skeleton.h"

#include <stdexcept>

namespace stirrup::rig {

int Skeleton::addJoint(std::string name, int parent, const glm::mat4& rest_local) {
  if (parent < -1 || parent >= static_cast<int>(joints.size()))
    throw std::invalid_argument("skeleton: joint " + name + " has a parent that is not yet defined");
  if (find(name) >= 0) throw std::invalid_argument("skeleton: duplicate joint " + name);
  const glm::mat4 world = parent < 0 ? rest_local : restWorld(parent) * rest_local;
  joints.push_back(Joint{std::move(name), parent, rest_local, glm::inverse(world)});
  return static_cast<int>(joints.size()) - 1;
}

int Skeleton::find(std::string_view name) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  return -1;
}

int Skeleton::require(std::string_view name) const {
  const int i = find(name);
  if (i < 0) throw std::out_of_range("skeleton: no joint named " + std::string(name));
  return i;
}

std::vector<glm::mat4> restLocals(const Skeleton& skeleton) {
  std::vector<glm::mat4> local(skeleton.size());
  for (std::size_t i = 0; i < skeleton.size(); ++i) local[i] = skeleton.joints[i].rest_local;
  return local;
}

std::vector<glm::mat4> restWorlds(const Skeleton& skeleton) {
  std::vector<glm::mat4> world(skeleton.size());
  localToWorld(skeleton, restLocals(skeleton), world);
  return world;
}

void localToWorld(const Skeleton& skeleton, std::span<const glm::mat4> local, std::span<glm::mat4> world) {
  if (local.size() != skeleton.size() || world.size() != skeleton.size())
    throw std::invalid_argument("localToWorld: expected one transform per joint");
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    const int p = skeleton.joints[i].parent;
    world[i] = p < 0 ? local[i] : world[p] * local[i];
  }
}

}  // namespace stirrup::rig
