#include "rig/characters/torso_weights.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace stirrup::rig {
namespace {

// Where a height lies along the chain: from joint `lower`'s bone middle toward the next, `along` of
// the way (0..1), and whether the joint above is listed even with no share.
struct ChainPlace {
  int lower = 0;
  float along = 0.0f;
  bool list_upper = false;
};

ChainPlace placeOnChain(const TorsoChain& c, float y) {
  if (c.middles.empty()) {
    const int n = static_cast<int>(c.joints.size()) - 1;
    const float u = std::clamp((y - c.y0) / c.bone - 0.5f, 0.0f, static_cast<float>(n));
    const int i = std::min(static_cast<int>(u), n - 1);
    return {i, u - static_cast<float>(i), true};
  }
  const std::span<const float> middles = c.middles;
  const int n = static_cast<int>(c.joints.size());
  int i = 0;
  float f = 0.0f;
  if (y >= middles[n - 1]) {
    i = n - 1;
  } else if (y > middles[0]) {
    while (i + 1 < n - 1 && y > middles[i + 1]) ++i;
    f = (y - middles[i]) / (middles[i + 1] - middles[i]);
  }
  return {i, f, false};
}

}  // namespace

void spreadTorsoWeights(SkinnedMesh& mesh, const TorsoChain& c) {
  const std::span<const int> chain = c.joints;
  const auto on_chain = [&](int j) { return std::find(chain.begin(), chain.end(), j) != chain.end(); };
  std::vector<std::pair<float, int>> w;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    w.clear();
    float torso = 0.0f;
    for (int k = 0; k < kMaxInfluences; ++k) {
      const float wk = mesh.weights[v][k];
      if (wk <= 0.0f) continue;
      const int j = mesh.joints[v][k];
      if (on_chain(j))
        torso += wk;
      else
        w.emplace_back(wk, j);
    }
    if (torso <= 0.0f) continue;
    const ChainPlace p = placeOnChain(c, mesh.positions[v].y);
    const int i = p.lower;
    const float f = p.along;
    w.emplace_back(torso * (1.0f - f), chain[i]);
    if (p.list_upper || f > 0.0f) w.emplace_back(torso * f, chain[i + 1]);
    // Stable, so equal weights keep the order above (the rider's generator used std::sort, which on
    // these few entries, at most six, libstdc++ insertion-sorts: stably, the same order).
    std::stable_sort(w.begin(), w.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const int count = std::min<int>(kMaxInfluences, static_cast<int>(w.size()));
    float total = 0.0f;
    for (int k = 0; k < count; ++k) total += w[k].first;
    mesh.joints[v] = glm::u16vec4(0);
    mesh.weights[v] = glm::vec4(0.0f);
    for (int k = 0; k < count; ++k) {
      mesh.joints[v][k] = static_cast<std::uint16_t>(w[k].second);
      mesh.weights[v][k] = w[k].first / total;
    }
  }
}

}  // namespace stirrup::rig
