// Contact between the rider and the horse on every default clip (the scenes in scenes/*.json), every
// frame, with the default characters posed as the shot poses them (rig::poseMounted):
//  - seat: the rider's pelvis stays over the saddle's seat, in the saddle's frame;
//  - feet: the ball of each foot stays on its stirrup tread;
//  - depth: no rider vertex is inside the horse by more than kMaxDepthCm. Inside is measured against
//    the skinned horse mesh as a signed distance: the nearest point on the nearest horse triangle within
//    kSearchRadiusCm (a grid over the posed triangles searched shell by shell, so the radius is
//    guaranteed) is the distance, and the vertex normals interpolated there say which side the rider
//    vertex is on. The thin tack the rider holds or stands in (reins and stirrup irons, the triangles
//    with a vertex bound to lRein, rRein, lStirrup, rStirrup) is left out.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <string>
#include <unordered_map>

#include <gtest/gtest.h>

#include "render/scene.h"
#include "rig/bake.h"
#include "rig/motion/clip_factory.h"
#include "rig/io/frame_range.h"
#include "rig/characters/horse_character.h"
#include "rig/pose.h"
#include "rig/characters/rider_character.h"
#include "rig/rig_profile.h"
#include "rig/skin.h"

namespace stirrup::rig {
namespace {

// Limits, stated: the seat's place in the saddle (cm, saddle frame, from the seat centre), the foot
// on the tread (cm), how deep a rider vertex may sink into the horse (cm: cloth pressed on the saddle).
constexpr float kSeatHalfLengthCm = 20.0f;  // the seat (tree) is 48 cm long: ±24 about its centre
constexpr float kSeatHalfWidthCm = 8.0f;
constexpr float kSeatMaxRiseCm = 22.0f;     // pelvis joint rests 10 cm above the seat centre
constexpr float kFootOnTreadCm = 1.0f;
// Every clip: knees and calves on the flaps, seat and coat skirt against the cantle. Measured deepest
// (docs/characters.md, "Contact"): walk 2.7, trot 2.4, canter 2.6, gallop 2.3, stop 2.3, jump 3.9,
// rear 3.0, buck 3.2 cm.
constexpr float kMaxDepthCm = 4.0f;

// The closest point to p on triangle abc, as barycentric weights of a, b, c (Ericson, Real-Time
// Collision Detection, 5.1.5: the Voronoi regions of the vertices, then the edges, then the face).
glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
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

// The posed horse's surface triangles in a dense grid of cells (cell lists in one array), searched shell
// by shell outward from a query point: the nearest point on the surface within a guaranteed radius.
// A small triangle is listed once, in the cell of its centroid, and the search reaches kReach farther
// (its nearest point is within kReach of the centroid); a larger one in every cell its bounds touch.
// A cell with no listed triangle within the radius is marked far, and a query there stops at once:
// most of the rider (head, arms, upper body) is far from the horse. Only triangles that can be within
// the radius of `region` (the rider's bounds) are kept. A rider vertex deeper inside the horse than the
// radius would have to be reached by the rider's surface crossing the band above it, where its
// vertices (about 1 cm apart) are found.
class NearestSurface {
 public:
  struct Hit {
    int triangle = -1;              // -1: no surface within the radius
    float distance = 0;             // to the nearest point
    glm::vec3 point{0}, normal{0};  // the nearest point; the vertex normals interpolated there
  };

  NearestSurface(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals,
                 const std::vector<std::uint32_t>& indices, const std::vector<bool>& skip, glm::vec3 region_lo,
                 glm::vec3 region_hi, float radius, float cell)
      : points_(points), normals_(normals), indices_(indices), radius_(radius), cell_(cell), reach_(0.5f * cell),
        shells_(static_cast<int>(std::ceil((radius + reach_) / cell))) {
    struct Kept {
      Item item;
      glm::vec3 lo, hi;
    };
    std::vector<Kept> kept;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (std::size_t t = 0; t < indices.size() / 3; ++t) {
      if (skip[indices[t * 3]] || skip[indices[t * 3 + 1]] || skip[indices[t * 3 + 2]]) continue;
      glm::vec3 tlo = corner(t, 0), thi = tlo;
      for (int k = 1; k < 3; ++k) tlo = glm::min(tlo, corner(t, k)), thi = glm::max(thi, corner(t, k));
      if (glm::any(glm::greaterThan(tlo, region_hi + radius)) || glm::any(glm::lessThan(thi, region_lo - radius))) continue;
      const glm::vec3 c = (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0f;
      float r2 = 0.0f;
      for (int k = 0; k < 3; ++k) r2 = std::max(r2, glm::dot(corner(t, k) - c, corner(t, k) - c));
      const float r = std::sqrt(r2);
      if (r <= reach_) tlo = thi = c;  // listed by its centroid
      kept.push_back({{c, r, static_cast<int>(t)}, tlo, thi});
      lo = glm::min(lo, tlo), hi = glm::max(hi, thi);
    }
    if (kept.empty()) return;
    // A margin of shells_ cells: every query within the radius of a triangle falls inside the grid.
    origin_ = lo - float(shells_) * cell;
    dims_ = glm::ivec3(glm::floor((hi - origin_) / cell)) + 1 + shells_;
    std::vector<int> count(cellCount() + 1, 0);
    const auto each_cell = [&](const Kept& k, auto&& f) {
      const glm::ivec3 c0 = cellOf(k.lo), c1 = cellOf(k.hi);
      for (int z = c0.z; z <= c1.z; ++z)
        for (int y = c0.y; y <= c1.y; ++y)
          for (int x = c0.x; x <= c1.x; ++x) f(index({x, y, z}));
    };
    for (const Kept& k : kept) each_cell(k, [&](std::size_t i) { ++count[i + 1]; });
    // Near: a listed cell within shells_ cells (Chebyshev), by a running window along each axis.
    near_.resize(cellCount());
    for (std::size_t i = 0; i < near_.size(); ++i) near_[i] = count[i + 1] > 0;
    const glm::ivec3 step(1, dims_.x, dims_.x * dims_.y);
    for (int axis = 0; axis < 3; ++axis) {
      const int n = dims_[axis];
      std::vector<std::uint8_t> line(static_cast<std::size_t>(n));
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      for (int u = 0; u < dims_[a1]; ++u)
        for (int v = 0; v < dims_[a2]; ++v) {
          const std::size_t base = static_cast<std::size_t>(u) * step[a1] + static_cast<std::size_t>(v) * step[a2];
          for (int i = 0; i < n; ++i) line[i] = near_[base + static_cast<std::size_t>(i) * step[axis]];
          int inside = 0;  // listed cells in the window [i - shells_, i + shells_]
          for (int i = 0; i < std::min(shells_, n); ++i) inside += line[i];
          for (int i = 0; i < n; ++i) {
            if (i + shells_ < n) inside += line[i + shells_];
            if (i - shells_ - 1 >= 0) inside -= line[i - shells_ - 1];
            near_[base + static_cast<std::size_t>(i) * step[axis]] = inside > 0;
          }
        }
    }
    for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    start_ = count;
    items_.resize(static_cast<std::size_t>(count.back()));
    for (const Kept& k : kept) each_cell(k, [&](std::size_t i) { items_[static_cast<std::size_t>(count[i]++)] = k.item; });
  }

  // The nearest surface point to q no farther than the radius.
  Hit nearest(const glm::vec3& q) const {
    Hit hit;
    const glm::ivec3 c = glm::ivec3(glm::floor((q - origin_) / cell_));
    if (items_.empty() || glm::any(glm::lessThan(c, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(c, dims_)) ||
        !near_[index(c)])
      return hit;
    float best_d2 = radius_ * radius_;
    glm::vec3 best_bary(0);
    for (int k = 0; k <= shells_; ++k) {
      // Shell k: the cells whose Chebyshev distance from c is k, clipped to the grid; a cell is looked
      // into only when it can hold a triangle nearer than the best so far.
      const glm::ivec3 lo = glm::max(c - k, glm::ivec3(0)), hi = glm::min(c + k, dims_ - 1);
      const float best = std::sqrt(best_d2), cull = best + reach_;
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y) {
          // Inside the shell's z and y faces every x is on the shell; elsewhere only its two ends.
          const bool face = std::abs(z - c.z) == k || std::abs(y - c.y) == k;
          for (int x = face ? lo.x : c.x - k; x <= (face ? hi.x : c.x + k); x += face ? 1 : 2 * k) {
            if (x < lo.x || x > hi.x) continue;
            const std::size_t i = index({x, y, z});
            if (start_[i] == start_[i + 1]) continue;
            const glm::vec3 box_lo = origin_ + glm::vec3(x, y, z) * cell_;
            const glm::vec3 gap = glm::max(glm::max(box_lo - q, q - (box_lo + cell_)), glm::vec3(0.0f));
            if (glm::dot(gap, gap) >= cull * cull) continue;
            for (int s = start_[i]; s < start_[i + 1]; ++s) {
              const Item& item = items_[static_cast<std::size_t>(s)];
              const float sphere = std::sqrt(best_d2) + item.radius;  // the triangle's bounding sphere
              if (glm::dot(item.centroid - q, item.centroid - q) >= sphere * sphere) continue;
              const int t = item.triangle;
              const glm::vec3 bary = closestOnTriangle(q, corner(t, 0), corner(t, 1), corner(t, 2));
              const glm::vec3 p = bary.x * corner(t, 0) + bary.y * corner(t, 1) + bary.z * corner(t, 2);
              const float d2 = glm::dot(p - q, p - q);
              if (d2 < best_d2) best_d2 = d2, hit.triangle = t, hit.point = p, best_bary = bary;
            }
          }
        }
      // Every cell of a later shell is at least k cells away, a triangle listed there reach_ less.
      const float sure = k * cell_ - reach_;
      if (hit.triangle >= 0 && sure > 0.0f && best_d2 <= sure * sure) break;
    }
    if (hit.triangle < 0) return hit;
    hit.distance = std::sqrt(best_d2);
    for (int k = 0; k < 3; ++k) hit.normal += best_bary[k] * normals_[indices_[hit.triangle * 3 + k]];
    return hit;
  }

 private:
  struct Item {
    glm::vec3 centroid;
    float radius;  // centroid to the farthest corner
    int triangle;
  };
  const glm::vec3& corner(std::size_t t, int k) const { return points_[indices_[t * 3 + k]]; }
  std::size_t cellCount() const { return static_cast<std::size_t>(dims_.x) * dims_.y * dims_.z; }
  glm::ivec3 cellOf(const glm::vec3& p) const { return glm::clamp(glm::ivec3(glm::floor((p - origin_) / cell_)), glm::ivec3(0), dims_ - 1); }
  std::size_t index(const glm::ivec3& c) const { return (static_cast<std::size_t>(c.z) * dims_.y + c.y) * dims_.x + c.x; }

  const std::vector<glm::vec3>& points_;
  const std::vector<glm::vec3>& normals_;
  const std::vector<std::uint32_t>& indices_;
  float radius_, cell_, reach_;  // reach_: how far a triangle listed by its centroid may extend from it
  int shells_;                   // cells out to the radius plus reach_
  glm::vec3 origin_{0};
  glm::ivec3 dims_{0};
  std::vector<Item> items_;
  std::vector<int> start_;
  std::vector<std::uint8_t> near_;
};

// How far from the horse's surface a rider vertex is looked at: past the deepest allowed sinking, so
// anything deeper than a limit is measured, not skipped.
constexpr float kSearchRadiusCm = kMaxDepthCm + 6.0f;
constexpr float kCellCm = 4.0f;  // a few triangles across (the horse is polygonised at about 1 cm)

struct ClipContact {
  float seat_x = 0, seat_z = 0, seat_y_min = 1e9f, seat_y_max = -1e9f, foot = 0, depth = 0;
  int depth_frame = 0;
  std::string depth_joint;
};

ClipContact measure(const std::string& scene_name) {
  static const Character horse = buildDefaultHorse();
  static const Character rider = buildDefaultRider();
  const render::SceneSpec scene = render::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + scene_name + ".json");
  const RigProfile profile = render::resolveProfile(scene);
  const auto clip = makeClip(scene.clip);
  std::vector<bool> tack(horse.mesh.vertexCount(), false);
  for (std::size_t v = 0; v < tack.size(); ++v)
    for (int k = 0; k < 4; ++k)
      for (const char* r : {"lRein", "rRein", "lStirrup", "rStirrup"})
        if (horse.mesh.weights[v][k] > 0.0f && horse.mesh.joints[v][k] == horse.role(r)) tack[v] = true;
  const glm::vec3 rest_pelvis = rider.skeleton.restPosition(rider.role("pelvis"));
  ClipContact out;
  std::vector<glm::vec3> hp, hn, rp, rn;
  const std::vector<int> frames = parseFrameList(scene.frames, "frames");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const int frame = frames[i];
    const BakedFrame b = bakeFrame(*clip, profile, frame, render::frameTime(scene, frame));
    const MountedPose pose = poseMounted(horse, rider, b.horse, b.rider, profile);
    // Seat, in the saddle's frame (the rider is built in saddle space, so rest = rest_pelvis).
    const glm::vec3 pelvis = glm::vec3(glm::inverse(pose.horse[horse.role("saddle")]) * pose.rider[rider.role("pelvis")][3]);
    const glm::vec3 d = pelvis - glm::vec3(rest_pelvis.x, 0.0f, rest_pelvis.z);
    out.seat_x = std::max(out.seat_x, std::abs(d.x));
    out.seat_z = std::max(out.seat_z, std::abs(d.z));
    out.seat_y_min = std::min(out.seat_y_min, d.y);
    out.seat_y_max = std::max(out.seat_y_max, d.y);
    for (const auto& [ball, tread] : {std::pair{"lBall", "lStirrup"}, std::pair{"rBall", "rStirrup"}})
      out.foot = std::max(out.foot, glm::length(glm::vec3(pose.rider[rider.role(ball)][3]) - glm::vec3(pose.horse[horse.role(tread)][3])));
    // Depth of rider vertices inside the skinned horse.
    skinMesh(horse.mesh, horse.skeleton, pose.horse, hp, hn);
    skinMesh(rider.mesh, rider.skeleton, pose.rider, rp, rn);
    glm::vec3 rider_lo(1e30f), rider_hi(-1e30f);
    for (const glm::vec3& p : rp) rider_lo = glm::min(rider_lo, p), rider_hi = glm::max(rider_hi, p);
    const NearestSurface surface(hp, hn, horse.mesh.indices, tack, rider_lo, rider_hi, kSearchRadiusCm, kCellCm);
    for (std::size_t v = 0; v < rp.size(); ++v) {
      const NearestSurface::Hit hit = surface.nearest(rp[v]);
      if (hit.triangle < 0) continue;
      // Inside when the surface's normal there faces away from the rider vertex.
      const float depth = glm::dot(hit.point - rp[v], hit.normal) > 0.0f ? hit.distance : -hit.distance;
      if (depth > out.depth) {
        out.depth = depth;
        out.depth_frame = frame;
        const glm::u16vec4 j = rider.mesh.joints[v];
        const glm::vec4 w = rider.mesh.weights[v];
        int k = 0;
        for (int q = 1; q < 4; ++q)
          if (w[q] > w[k]) k = q;
        out.depth_joint = rider.skeleton.joints[j[k]].name;
      }
    }
  }
  std::printf("%-7s seat |dx| %.1f |dz| %.1f dy %.1f..%.1f cm, feet %.2f cm from the treads, deepest %.2f cm (frame %d, %s)\n",
              scene_name.c_str(), out.seat_x, out.seat_z, out.seat_y_min, out.seat_y_max, out.foot, out.depth,
              out.depth_frame, out.depth_joint.c_str());
  return out;
}

class Contact : public ::testing::TestWithParam<const char*> {};

TEST_P(Contact, SeatInSaddleFeetInStirrupsNothingInsideTheHorse) {
  const ClipContact c = measure(GetParam());
  EXPECT_LE(c.seat_x, kSeatHalfLengthCm);
  EXPECT_LE(c.seat_z, kSeatHalfWidthCm);
  EXPECT_GE(c.seat_y_min, 0.0f);
  EXPECT_LE(c.seat_y_max, kSeatMaxRiseCm);
  EXPECT_LE(c.foot, kFootOnTreadCm);
  EXPECT_LE(c.depth, kMaxDepthCm) << "frame " << c.depth_frame << ", rider joint " << c.depth_joint;
}

INSTANTIATE_TEST_SUITE_P(DefaultClips, Contact,
                         ::testing::Values("walk", "trot", "canter", "gallop", "stop", "jump", "rear", "buck"));

}  // namespace
}  // namespace stirrup::rig
