#include "rig/skin_box.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rig/skin.h"
#include "rig/skin_blend.h"

namespace stirrup::rig {
namespace {

// Vertices a cluster (our choice): small enough that a cluster is a cell or two across on a
// character, so few clusters reach a box's faces; large enough that the bounds cost little beside
// skinning (measured on the generated horse and rider, bent at every third joint: 8 skins a fifth to a
// twentieth of the vertices, a few hundredths in the bind pose).
constexpr std::size_t kClusterVertices = 8;
// The float rounding of a skinned coordinate (a blend of four matrices, then a product with the
// position: a few dozen roundings of 2^-24 each, relative to the size of the terms) is covered by
// this fraction of the terms' size, ten times over, plus an absolute floor (centimetres).
constexpr double kRoundingSlack = 1e-5;
constexpr double kRoundingSlackCm = 1e-3;

// Bits of a coordinate quantised to 10 bits, spread for a Morton code.
std::uint32_t spread(std::uint32_t x) {
  x &= 0x3FF;
  x = (x | (x << 16)) & 0x030000FF;
  x = (x | (x << 8)) & 0x0300F00F;
  x = (x | (x << 4)) & 0x030C30C3;
  x = (x | (x << 2)) & 0x09249249;
  return x;
}

}  // namespace

SkinBoxIndex::SkinBoxIndex(const SkinnedMesh& mesh) : vertex_count_(mesh.positions.size()) {
  const std::size_t n = vertex_count_;
  if (mesh.joints.size() != n || mesh.weights.size() != n)
    throw std::invalid_argument("SkinBoxIndex: expected joints and weights for every vertex");
  glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  // Neighbours in the bind pose: the vertices in Morton order, cut into runs.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(n);
  const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
  for (std::size_t v = 0; v < n; ++v) {
    const glm::vec3 q = (mesh.positions[v] - lo) / size * 1023.0f;
    const auto c = [&](int a) { return spread(std::uint32_t(std::clamp(q[a], 0.0f, 1023.0f))); };
    keyed[v] = {c(0) | (c(1) << 1) | (c(2) << 2), std::uint32_t(v)};
  }
  std::sort(keyed.begin(), keyed.end());
  order_.resize(n);
  for (std::size_t v = 0; v < n; ++v) order_[v] = keyed[v].second;
  for (std::size_t first = 0; first < n; first += kClusterVertices) {
    Cluster c;
    c.first = first;
    c.count = std::min(kClusterVertices, n - first);
    glm::dvec3 clo(std::numeric_limits<double>::infinity()), chi(-std::numeric_limits<double>::infinity());
    for (std::size_t k = first; k < first + c.count; ++k) {
      const glm::dvec3 p(mesh.positions[order_[k]]);
      clo = glm::min(clo, p), chi = glm::max(chi, p);
    }
    c.centre = 0.5 * (clo + chi);
    c.half = 0.5 * (chi - clo);
    c.first_joint = joints_.size();
    c.weight_sum_lo = std::numeric_limits<double>::infinity();
    c.weight_sum_hi = -std::numeric_limits<double>::infinity();
    for (std::size_t k = first; k < first + c.count; ++k) {
      const std::size_t v = order_[k];
      double sum = 0.0;
      for (int i = 0; i < kMaxInfluences; ++i) {
        if (!(mesh.weights[v][i] > 0.0f)) continue;  // skinBlendAt reads only positive weights
        sum += mesh.weights[v][i];
        const std::uint16_t j = mesh.joints[v][i];
        if (std::find(joints_.begin() + long(c.first_joint), joints_.end(), j) == joints_.end()) joints_.push_back(j);
      }
      c.weight_sum_lo = std::min(c.weight_sum_lo, sum), c.weight_sum_hi = std::max(c.weight_sum_hi, sum);
    }
    c.joint_count = joints_.size() - c.first_joint;
    clusters_.push_back(c);
  }
}

SkinnedBox SkinBoxIndex::box(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld) const {
  if (mesh.positions.size() != vertex_count_) throw std::logic_error("SkinBoxIndex::box: not the mesh the index was made from");
  if (vertex_count_ == 0) throw std::logic_error("SkinBoxIndex::box: the mesh has no vertices");
  const std::vector<glm::mat4> m = skinningMatrices(skel, jointWorld);
  // Each cluster's bound: a vertex's coordinate a is sum_i w_i (M_i p)_a with every w_i > 0, and
  // (M_i p)_a lies within the joint's placement of the cluster's box, c_ia -+ e_ia (e_ia the box's
  // half sizes times the absolute values of row a of M_i's 3x3); so it is at most S max_i (c_ia + e_ia)
  // for the vertex's weight sum S (and at least S min_i (c_ia - e_ia)).
  // Each joint's matrix in doubles, and the absolute values of its 3x3, once a pose.
  struct Placement {
    glm::dmat3 linear, magnitude;  // magnitude: |linear|, entry by entry
    glm::dvec3 offset;
  };
  std::vector<Placement> placed(m.size());
  for (std::size_t j = 0; j < m.size(); ++j) {
    const glm::dmat4 mj(m[j]);
    placed[j].linear = glm::dmat3(mj);
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) placed[j].magnitude[col][row] = std::abs(mj[col][row]);
    placed[j].offset = glm::dvec3(mj[3]);
  }
  const std::size_t nc = clusters_.size();
  std::vector<glm::dvec3> blo(nc), bhi(nc);
  for (std::size_t k = 0; k < nc; ++k) {
    const Cluster& c = clusters_[k];
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    glm::dvec3 scale(0.0);  // the size of the terms a skinned coordinate sums, for the rounding slack
    const glm::dvec3 reach = glm::abs(c.centre) + c.half;
    for (std::size_t q = c.first_joint; q < c.first_joint + c.joint_count; ++q) {
      const Placement& p = placed[joints_[q]];
      const glm::dvec3 at = p.linear * c.centre + p.offset;
      const glm::dvec3 e = p.magnitude * c.half;
      lo = glm::min(lo, at - e), hi = glm::max(hi, at + e);
      scale = glm::max(scale, glm::abs(p.offset) + p.magnitude * reach);
    }
    for (int a = 0; a < 3; ++a) {
      const double slack = kRoundingSlack * scale[a] + kRoundingSlackCm;
      bhi[k][a] = (hi[a] >= 0.0 ? c.weight_sum_hi : c.weight_sum_lo) * hi[a] + slack;
      blo[k][a] = (lo[a] <= 0.0 ? c.weight_sum_hi : c.weight_sum_lo) * lo[a] - slack;
    }
  }
  SkinnedBox out;
  out.lo = glm::vec3(std::numeric_limits<float>::infinity());
  out.hi = glm::vec3(-std::numeric_limits<float>::infinity());
  std::vector<char> skinned(nc, 0);
  const auto skin = [&](std::size_t k) {
    skinned[k] = 1;
    const Cluster& c = clusters_[k];
    for (std::size_t i = c.first; i < c.first + c.count; ++i) {
      const glm::vec3 p = skinPositionAt(mesh, m, order_[i]);
      out.lo = glm::min(out.lo, p), out.hi = glm::max(out.hi, p);
    }
    out.skinned += c.count;
  };
  // The clusters reaching furthest along each axis first, so the box is nearly whole at once.
  for (int a = 0; a < 3; ++a) {
    std::size_t far_lo = 0, far_hi = 0;
    for (std::size_t k = 1; k < nc; ++k) {
      if (blo[k][a] < blo[far_lo][a]) far_lo = k;
      if (bhi[k][a] > bhi[far_hi][a]) far_hi = k;
    }
    if (!skinned[far_lo]) skin(far_lo);
    if (!skinned[far_hi]) skin(far_hi);
  }
  // Then every cluster whose bound reaches the box so far (which only grows, so one left out stays
  // out).
  for (std::size_t k = 0; k < nc; ++k) {
    if (skinned[k]) continue;
    bool reaches = false;
    for (int a = 0; a < 3; ++a) reaches = reaches || bhi[k][a] >= double(out.hi[a]) || blo[k][a] <= double(out.lo[a]);
    if (reaches) skin(k);
  }
  return out;
}

}  // namespace stirrup::rig
