// How far a posed rider sinks into a posed horse, however deep: the deepest rider vertex inside the
// horse's surface and its index. For `stirrup check` (rig/frame_check.h) and the tests: the default clips' contact (tests/rig/contact_test.cpp),
// and any rider a user brings ("no leg vertex more than 2 cm inside the horse").
//
//   const ContactDepth d = deepestRiderVertexInside(horse_points, horse_normals, horse.mesh.indices,
//                                                   horseLooseTack(horse), rider_points);
//   // d.depth_cm: how deep the deepest rider vertex is (0 when none is inside); d.vertex: its index
//
// The inputs are skinned meshes (rig::skinMesh): the horse's positions, its vertex normals (outward)
// and its triangles; `horse_skip` marks horse vertices whose triangles are not part of the surface a
// rider must stay out of (rig::horseLooseTack in rig/loose_tack.h: the reins she holds, the
// stirrup irons she stands in and the leathers her legs lie over);
// the rider's positions.
//
// Inside, and how deep, for a rider vertex q: p is the nearest point to q on the horse's surface, at
// any distance (a bounding-volume hierarchy over the posed triangles, searched nearest box first), and
// n the horse's vertex normals interpolated there. q is inside when it lies behind the surface at p,
// dot(p - q, n) > 0, and its depth is |p - q|. A leg 14 cm inside the barrel measures 14 cm: nothing
// is cut off at a search radius.
//
// Cost, so a test can measure every frame of every clip: the hierarchy is built afresh for each pose
// (Morton-ordered, about 5 ms for the default horse's 70 k triangles). Rider vertices are looked up
// by the kSideCellCm cube they fall in: one unbounded lookup at each cube's centre gives the surface's
// distance and side there. A vertex within kNearBandCm of the surface is then looked up alone, its
// search bounded by that band (few boxes are that close) and started from its neighbour's triangle.
// Most of a rider (head, arms, upper body) is farther than that, and for those only the side
// matters: the surface cannot pass between a far vertex and its cube's centre (the cube's half
// diagonal is less than the band), so the centre's side is theirs. Only far vertices on the inside
// (a limb deep in the horse) are measured one by one. The default pair (a rider of 23 k vertices):
// about 18 ms a pose, a little less than the 10 cm search this replaced.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"

namespace stirrup::rig {

struct ContactDepth {
  float depth_cm = 0.0f;  // how far the deepest rider vertex is inside the horse; 0 when none is
  int vertex = -1;        // that vertex's index in the rider's mesh; -1 when none is inside
};

namespace contact_detail {

// The closest point to p on triangle abc, as barycentric weights of a, b, c (Ericson, Real-Time
// Collision Detection, 5.1.5: the Voronoi regions of the vertices, then the edges, then the face).
inline glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return {1, 0, 0};
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return {0, 1, 0};
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return {0, 0, 1};
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f) {
    const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const float denom = 1.0f / (va + vb + vc);
  const float v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

// The nearest point on a triangle mesh to a query point: a binary hierarchy of boxes over the
// triangles (split at the median centroid along the longest axis, a few triangles a leaf), searched
// nearest box first and pruned by the best distance so far.
class NearestSurface {
 public:
  struct Hit {
    int triangle = -1;              // -1: no triangle within the distance asked for
    float distance = 0.0f;
    glm::vec3 point{0.0f}, normal{0.0f};  // the nearest point; the vertex normals interpolated there
  };

  NearestSurface(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals,
                 const std::vector<std::uint32_t>& indices, const std::vector<bool>& skip)
      : points_(points), normals_(normals), indices_(indices) {
    // Each surface triangle keyed by where its centroid falls on a Morton (Z-order) curve through
    // the surface's bounds, 10 bits an axis: sorting the keys puts triangles near in space near in
    // the order (Karras 2012, "Maximizing parallelism in the construction of BVHs, octrees, and k-d
    // trees": a node splits its range where the keys' highest differing bit changes).
    std::vector<glm::vec3> centroid;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::size_t t = 0; t < indices.size() / 3; ++t) {
      if (skip[indices[t * 3]] || skip[indices[t * 3 + 1]] || skip[indices[t * 3 + 2]]) continue;
      const int ti = static_cast<int>(t);
      order_.push_back(ti);
      centroid.push_back((corner(ti, 0) + corner(ti, 1) + corner(ti, 2)) / 3.0f);
      lo = glm::min(lo, centroid.back()), hi = glm::max(hi, centroid.back());
    }
    if (order_.empty()) return;
    const glm::vec3 scale = 1023.0f / glm::max(hi - lo, glm::vec3(1e-6f));
    const auto spread = [](std::uint32_t x) {  // the 10 bits of x to every third bit
      x = (x | (x << 16)) & 0x030000FFu;
      x = (x | (x << 8)) & 0x0300F00Fu;
      x = (x | (x << 4)) & 0x030C30C3u;
      x = (x | (x << 2)) & 0x09249249u;
      return x;
    };
    std::vector<std::uint64_t> keyed(order_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) {
      const glm::uvec3 c = glm::uvec3((centroid[i] - lo) * scale);
      const std::uint32_t code = (spread(c.x) << 2) | (spread(c.y) << 1) | spread(c.z);
      keyed[i] = (std::uint64_t(code) << 32) | std::uint32_t(order_[i]);
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < keyed.size(); ++i) order_[i] = static_cast<int>(keyed[i] & 0xffffffffu);
    const auto code = [&](int i) { return static_cast<std::uint32_t>(keyed[static_cast<std::size_t>(i)] >> 32); };
    nodes_.reserve(4 * order_.size() / kLeafSize + 2);
    nodes_.push_back({glm::vec3(0), glm::vec3(0), 0, static_cast<int>(order_.size()), -1});
    std::vector<int> todo = {0};
    while (!todo.empty()) {
      const int n = todo.back();
      todo.pop_back();
      const int start = nodes_[n].start, count = nodes_[n].count;
      if (count <= kLeafSize) continue;
      const int last = start + count - 1;
      int split = start + count / 2;  // equal keys: halve
      if (const std::uint32_t differ = code(start) ^ code(last); differ != 0) {
        // The first key with the highest differing bit set: all keys in the range share the bits
        // above it, so those with it clear come first.
        const std::uint32_t bit = 1u << (31 - __builtin_clz(differ));
        const auto begin = keyed.begin() + start, end = keyed.begin() + start + count;
        split = start + static_cast<int>(std::partition_point(begin, end, [bit](std::uint64_t k) {
                                            return ((k >> 32) & bit) == 0;
                                          }) - begin);
      }
      const int left = static_cast<int>(nodes_.size());
      nodes_.push_back({glm::vec3(0), glm::vec3(0), start, split - start, -1});
      nodes_.push_back({glm::vec3(0), glm::vec3(0), split, start + count - split, -1});
      nodes_[n].left = left;
      nodes_[n].count = 0;  // an inner node
      todo.push_back(left);
      todo.push_back(left + 1);
    }
    // Bottom up: children come after their parent, so in reverse every child's box is ready.
    for (int n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n) {
      Node& node = nodes_[n];
      if (node.count > 0) {
        node.lo = glm::vec3(std::numeric_limits<float>::max()), node.hi = -node.lo;
        for (int i = node.start; i < node.start + node.count; ++i)
          for (int k = 0; k < 3; ++k) node.lo = glm::min(node.lo, corner(order_[i], k)), node.hi = glm::max(node.hi, corner(order_[i], k));
      } else {
        node.lo = glm::min(nodes_[node.left].lo, nodes_[node.left + 1].lo);
        node.hi = glm::max(nodes_[node.left].hi, nodes_[node.left + 1].hi);
      }
    }
  }

  // The nearest surface point to q no farther than max_distance (unbounded by default). `guess`, a
  // triangle likely to be near (a neighbouring vertex's), is tried first: the search then prunes
  // from a good bound at once.
  Hit nearest(const glm::vec3& q, float max_distance = std::numeric_limits<float>::infinity(), int guess = -1) const {
    Hit hit;
    if (nodes_.empty()) return hit;
    float best_d2 = std::isinf(max_distance) ? std::numeric_limits<float>::infinity() : max_distance * max_distance;
    glm::vec3 best_bary(0.0f);
    if (guess >= 0) {
      const glm::vec3 bary = closestOnTriangle(q, corner(guess, 0), corner(guess, 1), corner(guess, 2));
      const glm::vec3 p = bary.x * corner(guess, 0) + bary.y * corner(guess, 1) + bary.z * corner(guess, 2);
      const float pd2 = glm::dot(p - q, p - q);
      if (pd2 < best_d2) best_d2 = pd2, hit.triangle = guess, hit.point = p, best_bary = bary;
    }
    std::pair<int, float> stack[96];  // deeper than the tree (32 key bits, then halving)
    int top = 0;
    stack[top++] = {0, boxDistance2(nodes_[0], q)};
    while (top > 0) {
      const auto [n, d2] = stack[--top];
      if (d2 >= best_d2) continue;
      const Node& node = nodes_[n];
      if (node.count > 0) {
        for (int i = node.start; i < node.start + node.count; ++i) {
          const int t = order_[i];
          const glm::vec3 bary = closestOnTriangle(q, corner(t, 0), corner(t, 1), corner(t, 2));
          const glm::vec3 p = bary.x * corner(t, 0) + bary.y * corner(t, 1) + bary.z * corner(t, 2);
          const float pd2 = glm::dot(p - q, p - q);
          if (pd2 < best_d2) best_d2 = pd2, hit.triangle = t, hit.point = p, best_bary = bary;
        }
        continue;
      }
      const float a = boxDistance2(nodes_[node.left], q), b = boxDistance2(nodes_[node.left + 1], q);
      // The nearer child is searched first (pushed last).
      if (a <= b) {
        if (b < best_d2) stack[top++] = {node.left + 1, b};
        if (a < best_d2) stack[top++] = {node.left, a};
      } else {
        if (a < best_d2) stack[top++] = {node.left, a};
        if (b < best_d2) stack[top++] = {node.left + 1, b};
      }
    }
    if (hit.triangle < 0) return hit;
    hit.distance = std::sqrt(best_d2);
    for (int k = 0; k < 3; ++k) hit.normal += best_bary[k] * normals_[indices_[hit.triangle * 3 + k]];
    return hit;
  }

 private:
  static constexpr int kLeafSize = 8;
  struct Node {
    glm::vec3 lo, hi;
    int start, count;  // a leaf's triangles, order_[start, start + count); count 0: an inner node
    int left;          // an inner node's children: left and left + 1
  };
  static float boxDistance2(const Node& n, const glm::vec3& q) {
    const glm::vec3 d = glm::max(glm::max(n.lo - q, q - n.hi), glm::vec3(0.0f));
    return glm::dot(d, d);
  }
  const glm::vec3& corner(int t, int k) const { return points_[indices_[static_cast<std::size_t>(t) * 3 + k]]; }

  const std::vector<glm::vec3>& points_;
  const std::vector<glm::vec3>& normals_;
  const std::vector<std::uint32_t>& indices_;
  std::vector<int> order_;  // the surface's triangles, leaf by leaf
  std::vector<Node> nodes_;
};

// Rider vertices nearer the surface than this are measured alone (see the header comment).
inline constexpr float kNearBandCm = 6.0f;
// The cubes that share one lookup at their centre: their half diagonal (5.2 cm) is less than the
// band, so the surface cannot pass between a vertex farther than the band and its cube's centre.
// (Band and cube measured fastest on the default pair among 4 to 10 cm.)
inline constexpr float kSideCellCm = 6.0f;
inline constexpr float kSideCellHalfDiagonalCm = kSideCellCm * 0.8660255f;  // sqrt(3) / 2, rounded up
static_assert(kSideCellHalfDiagonalCm < kNearBandCm);

// Behind the surface at the hit: inside.
inline bool behind(const NearestSurface::Hit& hit, const glm::vec3& q) { return glm::dot(hit.point - q, hit.normal) > 0.0f; }

}  // namespace contact_detail

// The deepest rider vertex inside the horse, however deep (see the header comment for the inputs and
// how inside is judged).
inline ContactDepth deepestRiderVertexInside(const std::vector<glm::vec3>& horse_points,
                                             const std::vector<glm::vec3>& horse_normals,
                                             const std::vector<std::uint32_t>& horse_indices,
                                             const std::vector<bool>& horse_skip,
                                             const std::vector<glm::vec3>& rider_points) {
  using namespace contact_detail;
  const NearestSurface surface(horse_points, horse_normals, horse_indices, horse_skip);
  // What the surface is like around each cube that holds rider vertices, looked up once at its centre.
  struct Cube {
    float distance;  // from the centre to the surface
    bool inside;     // the centre's side
  };
  std::unordered_map<std::uint64_t, Cube> cubes;
  ContactDepth deepest;
  int guess = -1;  // the last vertex's nearest triangle: mesh neighbours are mostly neighbours in order
  for (std::size_t v = 0; v < rider_points.size(); ++v) {
    const glm::vec3& q = rider_points[v];
    const glm::ivec3 cell = glm::ivec3(glm::floor(q / kSideCellCm));
    const std::uint64_t key = (std::uint64_t(std::uint32_t(cell.x) & 0x1fffff) << 42) |
                              (std::uint64_t(std::uint32_t(cell.y) & 0x1fffff) << 21) |
                              std::uint64_t(std::uint32_t(cell.z) & 0x1fffff);
    auto it = cubes.find(key);
    if (it == cubes.end()) {
      const glm::vec3 centre = (glm::vec3(cell) + 0.5f) * kSideCellCm;
      const NearestSurface::Hit hit = surface.nearest(centre);
      const Cube cube = hit.triangle < 0 ? Cube{std::numeric_limits<float>::infinity(), false}
                                         : Cube{hit.distance, behind(hit, centre)};
      it = cubes.emplace(key, cube).first;
    }
    const Cube& cube = it->second;
    // The surface is no farther from q than from the centre plus the half diagonal (and a little
    // for rounding, so a search bounded by it always finds the surface).
    constexpr float kSlackCm = 0.01f;
    const float reach = cube.distance + kSideCellHalfDiagonalCm;
    float depth = 0.0f;
    const NearestSurface::Hit near = cube.distance > kNearBandCm + kSideCellHalfDiagonalCm
                                         ? NearestSurface::Hit{}
                                         : surface.nearest(q, std::min(kNearBandCm, reach + kSlackCm), guess);
    if (near.triangle >= 0) guess = near.triangle;
    if (near.triangle >= 0) {
      if (!behind(near, q)) continue;
      depth = near.distance;
    } else {
      // Farther than the band from the surface: on the centre's side.
      if (!cube.inside) continue;
      depth = surface.nearest(q, reach + kSlackCm).distance;  // deep inside: measured alone
    }
    if (depth > deepest.depth_cm) deepest = {depth, static_cast<int>(v)};
  }
  return deepest;
}

}  // namespace stirrup::rig
