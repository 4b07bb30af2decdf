#include "rig/skeleton.h"

#include <algorithm>
#include <limits>
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

std::vector<int> Skeleton::pathFrom(int ancestor, int joint) const {
  std::vector<int> path;
  for (int j = joint; j >= 0; j = joints[j].parent) {
    if (j == ancestor) {
      std::reverse(path.begin(), path.end());
      return path;
    }
    path.push_back(j);
  }
  return {};
}

int nearestBoneJoint(const glm::dvec3& p, const std::vector<int>& parent, const std::vector<glm::dvec3>& position,
                     const std::vector<char>& usable, double* distance) {
  int best = -1;
  double bd = std::numeric_limits<double>::infinity();
  const auto consider = [&](int owner, double d) {
    if (d < bd) bd = d, best = owner;
  };
  const int n = static_cast<int>(parent.size());
  for (int j = 0; j < n; ++j) {
    if (!usable[j]) continue;
    consider(j, glm::length(p - position[j]));
    const int a = parent[j];
    if (a < 0 || !usable[a]) continue;
    const glm::dvec3 bone = position[j] - position[a];
    const double len2 = glm::dot(bone, bone);
    if (!(len2 > 0.0)) continue;
    const double t = glm::dot(p - position[a], bone) / len2;
    if (t > 0.0 && t < 1.0) consider(a, glm::length(p - (position[a] + t * bone)));  // the ends are the joints' own points
  }
  if (distance) *distance = bd;
  return best;
}

std::vector<char> hangLooseRoots(std::vector<int>& parent, const std::vector<glm::vec3>& position, int core) {
  const int n = static_cast<int>(parent.size());
  if (n == 0) return {};
  std::vector<int> root_of(n);
  for (int j = 0; j < n; ++j) {
    int r = j;
    for (int steps = 0; parent[r] >= 0 && steps <= n; ++steps) r = parent[r];
    root_of[j] = r;
  }
  if (core < 0 || core >= n) {
    glm::vec3 middle(0.0f);
    for (const glm::vec3& p : position) middle += p / float(n);
    core = 0;
    for (int j = 1; j < n; ++j)
      if (glm::length(position[j] - middle) < glm::length(position[core] - middle)) core = j;
  }
  const std::vector<glm::dvec3> at(position.begin(), position.end());
  const std::vector<int> file_parent = parent;  // bones are the file's: a root's hanging is no bone
  const int main_root = root_of[core];
  std::vector<char> attached(n, 0), hung(n, 0);
  for (int j = 0; j < n; ++j) attached[j] = root_of[j] == main_root;
  for (;;) {
    int best_root = -1, best_to = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < n; ++r) {
      if (parent[r] >= 0 || attached[r]) continue;
      double d = 0.0;
      const int to = nearestBoneJoint(at[r], file_parent, at, attached, &d);
      if (to >= 0 && d < best) best = d, best_root = r, best_to = to;
    }
    if (best_root < 0) break;
    parent[best_root] = best_to;
    hung[best_root] = 1;
    for (int j = 0; j < n; ++j)
      if (root_of[j] == best_root) attached[j] = 1;
  }
  return hung;
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
