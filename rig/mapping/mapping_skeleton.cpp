#include "rig/mapping/mapping_skeleton.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "rig/error.h"
#include "rig/mapping/skeleton_topology.h"
#include "rig/skeleton.h"

namespace stirrup::rig {
namespace {

// Trees of a forest (`members[r]`: the joints of the tree rooted at r) that have a mirror image: another
// tree of as many joints, each joint's reflection through the plane between the two roots landing
// within `tolerance` of one of its joints. A pair of limbs is such; the trunk never is.
std::vector<char> mirroredTrees(const std::vector<std::vector<int>>& members, const std::vector<glm::dvec3>& position,
                                double tolerance) {
  const int n = static_cast<int>(members.size());
  std::vector<char> twin(n, 0);
  const auto mirrors = [&](int a, int b) {
    const glm::dvec3 d = position[a] - position[b];
    if (members[a].size() != members[b].size() || !(glm::length(d) > tolerance)) return false;
    const glm::dvec3 middle = 0.5 * (position[a] + position[b]), normal = glm::normalize(d);
    for (int x : members[a]) {
      const glm::dvec3 image = position[x] - 2.0 * glm::dot(position[x] - middle, normal) * normal;
      bool hit = false;
      for (int y : members[b]) hit = hit || glm::length(position[y] - image) <= tolerance;
      if (!hit) return false;
    }
    return true;
  };
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n && !members[a].empty(); ++b)
      if (!members[b].empty() && mirrors(a, b)) twin[a] = twin[b] = 1;
  return twin;
}

}  // namespace


// A skin of several roots (Blender's Rigify exported with its deform bones only: the limbs and the
// face are roots) made one tree for finding roles: every further root hangs from the joint of the
// trunk's tree whose bone passes nearest it (nearestBoneJoint). The trunk's tree is, of the trees with
// a bone and no mirror image (a pair of loose limbs is mirrored; a lone joint, like Rigify's DEF-chest,
// has no bone), the one whose bones pass nearest the middle of the mesh: a horse's thighs can pass
// nearer its barrel's middle than its spine does. Unlike the importer's hangLooseRoots (which hangs
// each root from the body built so far), a mirror-image pair of loose limbs then hangs from one joint,
// never one from the other, as the topology's rules expect; the roles found lie on the same chains in
// either tree (a limb keeps its own hierarchy).
void hangFromTrunk(std::vector<int>& parent, const std::vector<glm::dvec3>& position, const glm::dvec3& middle,
                   std::vector<char>& hung) {
  const int n = static_cast<int>(parent.size());
  hung.assign(n, 0);
  std::vector<int> root_of(n);
  std::vector<std::vector<int>> members(n);
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (int j = 0; j < n; ++j) {
    int r = j;
    for (int steps = 0; parent[r] >= 0 && steps <= n; ++steps) r = parent[r];
    root_of[j] = r;
    members[r].push_back(j);
    lo = glm::min(lo, position[j]), hi = glm::max(hi, position[j]);
  }
  const glm::dvec3 extent = hi - lo;
  const std::vector<char> twin = mirroredTrees(members, position, kMirrorTolerance * std::max({extent.x, extent.y, extent.z}));
  std::vector<char> candidate(n, 0);  // joints of unmirrored trees, on a bone
  for (int j = 0; j < n; ++j)
    if (parent[j] >= 0 && !twin[root_of[j]]) candidate[j] = candidate[parent[j]] = 1;
  if (std::find(candidate.begin(), candidate.end(), 1) == candidate.end()) candidate.assign(n, 1);
  const int trunk = root_of[nearestBoneJoint(middle, parent, position, candidate)];
  std::vector<char> in_trunk(n, 0);
  for (int j = 0; j < n; ++j) in_trunk[j] = root_of[j] == trunk;
  const std::vector<int> file_parent = parent;
  for (int r = 0; r < n; ++r) {
    if (parent[r] >= 0 || r == trunk) continue;
    parent[r] = nearestBoneJoint(position[r], file_parent, position, in_trunk);
    hung[r] = 1;
  }
}

void MappingSkeleton::finish() {
  const int n = size();
  children.assign(n, {});
  for (int j = 0; j < n; ++j)
    if (parent[j] >= 0) children[parent[j]].push_back(j);
  enter.assign(n, 0);
  leave.assign(n, 0);
  depth.assign(n, 0);
  int clock = 0;
  // Iterative depth-first walk (a chain of thousands of joints must not overflow the stack).
  std::vector<std::pair<int, std::size_t>> stack;
  for (int r = 0; r < n; ++r) {
    if (parent[r] >= 0) continue;
    stack.push_back({r, 0});
    enter[r] = clock++;
    while (!stack.empty()) {
      auto& [j, next] = stack.back();
      if (next < children[j].size()) {
        const int c = children[j][next++];
        depth[c] = depth[j] + 1;
        enter[c] = clock++;
        stack.push_back({c, 0});
      } else {
        leave[j] = clock++;
        stack.pop_back();
      }
    }
  }
}

std::vector<int> MappingSkeleton::pathDown(int ancestor, int j) const {
  std::vector<int> path;
  if (!above(ancestor, j)) return path;
  for (int k = j; k != ancestor; k = parent[k]) path.push_back(k);
  return {path.rbegin(), path.rend()};
}

int MappingSkeleton::find(const std::string& name) const {
  for (int j = 0; j < size(); ++j)
    if (names[j] == name) return j;
  return -1;
}

void rigifyDeformParents(std::vector<int>& parent, const std::vector<std::string>& names) {
  const int n = static_cast<int>(parent.size());
  std::map<std::string, int> by_name;
  for (int j = 0; j < n; ++j) by_name.emplace(names[j], j);
  const auto prefixed = [&](int j, const char* prefix) { return names[j].rfind(prefix, 0) == 0; };
  const auto holds = [&](int a, int j) {  // `a` is `j` or above it
    for (int steps = 0; j >= 0 && steps <= n; j = parent[j], ++steps)
      if (j == a) return true;
    return false;
  };
  for (int j = 0; j < n; ++j) {
    if (!prefixed(j, "DEF-")) continue;
    for (int p = parent[j], steps = 0; p >= 0 && steps <= n && !prefixed(p, "DEF-"); p = parent[p], ++steps) {
      if (!prefixed(p, "ORG-")) continue;
      const auto it = by_name.find("DEF-" + names[p].substr(4));
      if (it == by_name.end() || it->second == j || holds(j, it->second)) continue;
      parent[j] = it->second;
      break;
    }
  }
}

}  // namespace stirrup::rig
