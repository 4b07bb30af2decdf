#include "rig/loose_tack.h"

#include <algorithm>
#include <cstdint>

namespace stirrup::rig {

std::vector<bool> horseLooseTack(const Character& horse) {
  const std::size_t n = horse.mesh.vertexCount();
  std::vector<int> joints;
  const auto saddle = horse.roles.find("saddle");
  for (const char* role : {"lStirrup", "rStirrup", "lRein", "rRein"})
    if (const auto it = horse.roles.find(role);
        it != horse.roles.end() && (saddle == horse.roles.end() || it->second != saddle->second))
      joints.push_back(it->second);
  // Pieces: union-find over the triangles.
  std::vector<std::uint32_t> root(n);
  for (std::size_t v = 0; v < n; ++v) root[v] = static_cast<std::uint32_t>(v);
  const auto find = [&](std::uint32_t v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  const std::vector<std::uint32_t>& idx = horse.mesh.indices;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
    for (int k = 1; k < 3; ++k) root[find(idx[t + k])] = find(idx[t]);
  std::vector<bool> piece(n, false), loose(n, false);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < kMaxInfluences; ++k)
      if (horse.mesh.weights[v][k] > 0.0f && std::find(joints.begin(), joints.end(), horse.mesh.joints[v][k]) != joints.end())
        piece[find(static_cast<std::uint32_t>(v))] = true;
  for (std::size_t v = 0; v < n; ++v) loose[v] = piece[find(static_cast<std::uint32_t>(v))];
  return loose;
}

}  // namespace stirrup::rig
