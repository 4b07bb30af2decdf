#include "rig/horse_body.h"

#include <algorithm>
#include <limits>

namespace stirrup::rig {

HorseBody horseBody(const Character& horse) {
  const Skeleton& s = horse.skeleton;
  HorseBody b;
  const int root = horse.role("root"), neck1 = horse.role("neck1"), head = horse.role("head");
  if (const auto it = horse.roles.find("backMid"); it != horse.roles.end()) {
    b.back_turn = it->second;
    b.back_from_role = true;
  } else {
    std::vector<int> back = s.pathFrom(root, neck1);  // root's child .. neck1
    if (!back.empty()) back.pop_back();
    const auto withers = horse.roles.find("withers");
    const glm::vec3 front = s.restPosition(withers != horse.roles.end() ? withers->second : neck1);
    const glm::vec3 middle = 0.5f * (s.restPosition(root) + front);
    float best = std::numeric_limits<float>::infinity();
    for (int j : back)
      if (const float d = glm::length(s.restPosition(j) - middle); d < best) best = d, b.back_turn = j;
  }
  b.neck.push_back(neck1);
  std::vector<int> up = s.pathFrom(neck1, head);  // neck1's child .. head
  if (!up.empty()) up.pop_back();
  b.neck.insert(b.neck.end(), up.begin(), up.end());
  if (const auto it = horse.roles.find("tail1"); it != horse.roles.end()) {
    // Joints are stored parents first: one pass finds the descendants and their depth below tail1.
    std::vector<int> depth(s.size(), 0);
    depth[it->second] = 1;
    for (std::size_t j = 0; j < s.size(); ++j) {
      const int p = s.joints[j].parent;
      if (static_cast<int>(j) == it->second) {
        b.tail.push_back(it->second);
      } else if (p >= 0 && depth[p] > 0) {
        depth[j] = depth[p] + 1;
        b.tail.push_back(static_cast<int>(j));
      }
    }
    for (int j : b.tail) b.tail_length = std::max(b.tail_length, depth[j]);
  }
  return b;
}

}  // namespace stirrup::rig
