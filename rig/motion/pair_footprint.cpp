#include "rig/motion/pair_footprint.h"

#include "rig/units.h"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>

#include "rig/horse_pose.h"
#include "rig/skeleton.h"
#include "rig/skin.h"

namespace stirrup::rig {
namespace {

// The tail's thickest capsule radius (9 cm) and its blend (5 cm), as buildHorse makes the tail
// (rig/characters/horse_character.cpp; not HorseParams, so not scaled).
constexpr double kTailHairCm = 14.0;

// The rotation of rig/pose_transforms.h's rot(degrees, axis) for a point, about the X, Y or Z axis, in double.
glm::dvec3 rotX(glm::dvec3 p, double deg) {
  const double c = std::cos(deg * kRadiansPerDegree), s = std::sin(deg * kRadiansPerDegree);
  return {p.x, c * p.y - s * p.z, s * p.y + c * p.z};
}
glm::dvec3 rotY(glm::dvec3 p, double deg) {
  const double c = std::cos(deg * kRadiansPerDegree), s = std::sin(deg * kRadiansPerDegree);
  return {c * p.x + s * p.z, p.y, -s * p.x + c * p.z};
}
glm::dvec3 rotZ(glm::dvec3 p, double deg) {
  const double c = std::cos(deg * kRadiansPerDegree), s = std::sin(deg * kRadiansPerDegree);
  return {c * p.x - s * p.y, s * p.x + c * p.y, p.z};
}

glm::dvec3 d3(glm::vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace

PairExtent pairExtent(const HorseParams& h, const RiderParams& r) {
  PairExtent e;
  // Head: the neck turns at its base, its middle and the poll, so everything ahead of the base stays
  // within the chain's lengths of it (the triangle inequality along neck1, neck2, head).
  const glm::dvec3 base = d3(h.neck_base), mid = d3(h.neck_mid), poll = d3(h.poll), muzzle = d3(h.muzzle);
  const double head_reach = std::max(glm::length(muzzle - poll) + h.muzzle_radius, double(h.ear_length) + h.head_radius);
  const double neck_reach = glm::length(mid - base) + glm::length(poll - mid) + head_reach;
  e.front_cm = std::max({base.x + neck_reach, double(h.chest_center.x + h.chest_radii.x)});
  // Tail: hair about its root, as long as the tail and as thick as its thickest capsule with its blend.
  e.tail_root = d3(h.tail_root);
  e.tail_reach_cm = h.tail_length + kTailHairCm;
  e.back_cm = std::min({e.tail_root.x - e.tail_reach_cm, double(h.buttock_center.x - h.buttock_radii.x),
                        double(h.croup_center.x - h.croup_radii.x)});
  // Width: the horse's trunk and quarters, and the rider's boot around the stirrup tread with her calf
  // and knee outside it.
  const double horse_w = std::max({double(h.barrel_radii.z), double(h.chest_radii.z), double(h.croup_radii.z),
                                   double(std::abs(h.buttock_center.z) + h.buttock_radii.z),
                                   double(std::abs(h.quarter_center.z) + h.quarter_radii.z),
                                   double(std::abs(h.fore_hoof.z) + h.forearm_radius),
                                   double(std::abs(h.hind_hoof.z) + h.gaskin_radius)});
  const double rider_w = std::abs(h.mount.stirrup.z) + 2.0 * std::max({r.calf_radius, r.knee_radius, r.ankle_radius});
  e.half_width_cm = std::max(horse_w, rider_w);
  // Height: the seat (as buildHorse places it, on the back behind the withers), the rider's head pivot
  // above it and her head; or the horse's ears.
  const double bx = (h.saddle_x - h.barrel_center.x) / h.barrel_radii.x;
  const double back_top = h.barrel_center.y + h.barrel_radii.y * std::sqrt(std::max(0.0, 1.0 - bx * bx));
  const double seat_y = back_top + h.saddle_seat_height;
  e.top_cm = std::max(seat_y + r.head.y + r.head_height, poll.y + h.ear_length);
  e.pivot = d3(h.hips);
  e.hoof_rest = {glm::dvec2{h.fore_hoof.x, h.fore_hoof.z}, glm::dvec2{h.fore_hoof.x, -h.fore_hoof.z},
                 glm::dvec2{h.hind_hoof.x, h.hind_hoof.z}, glm::dvec2{h.hind_hoof.x, -h.hind_hoof.z}};
  e.hoof_radius_cm = std::max(h.hoof_radius, h.fetlock_radius);
  return e;
}

PairExtent pairExtent(const Character& horse, const Character& rider) {
  std::vector<glm::vec3> hp, rp;
  skinPositions(horse.mesh, horse.skeleton, restWorlds(horse.skeleton), 1, hp);
  skinPositions(rider.mesh, rider.skeleton, restWorlds(rider.skeleton), 1, rp);
  const auto restOf = [&](const char* role) { return d3(horse.skeleton.restPosition(horse.role(role))); };
  PairExtent e;
  const glm::dvec3 neck = restOf("neck1");
  const int tail_role = horse.roles.count("tail1") ? horse.role("tail1") : -1;
  e.tail_root = tail_role >= 0 ? d3(horse.skeleton.restPosition(tail_role)) : glm::dvec3(1e300);
  double neck_reach = 0.0, tail_reach = 0.0;
  e.back_cm = 1e300, e.front_cm = -1e300;
  for (const glm::vec3& v : hp) {
    const glm::dvec3 p = d3(v);
    e.back_cm = std::min(e.back_cm, p.x), e.front_cm = std::max(e.front_cm, p.x);
    if (p.x > neck.x) neck_reach = std::max(neck_reach, glm::length(p - neck));
    if (tail_role >= 0 && p.x < e.tail_root.x) tail_reach = std::max(tail_reach, glm::length(p - e.tail_root));
    e.half_width_cm = std::max(e.half_width_cm, std::abs(p.z));
    e.top_cm = std::max(e.top_cm, p.y);
  }
  e.front_cm = std::max(e.front_cm, neck.x + neck_reach);
  if (tail_role >= 0) {
    e.tail_reach_cm = tail_reach;
    e.back_cm = std::min(e.back_cm, e.tail_root.x - tail_reach);
  } else {
    e.tail_root = restOf("root"), e.tail_reach_cm = 0.0;
  }
  // The rider's rest is in saddle space (rig/rider_pose.cpp: the posed saddle is her frame).
  const glm::dmat4 saddle(horse.skeleton.restWorld(horse.role("saddle")));
  for (const glm::vec3& rv : rp) {
    const glm::dvec3 v(saddle * glm::dvec4(d3(rv), 1.0));
    e.back_cm = std::min(e.back_cm, v.x), e.front_cm = std::max(e.front_cm, v.x);
    e.half_width_cm = std::max(e.half_width_cm, std::abs(v.z));
    e.top_cm = std::max(e.top_cm, v.y);
  }
  e.pivot = restOf("root");
  e.hoof_rest = restHoofPlaces(horse);
  // A hoof's reach about its joint: the farthest of the vertices its joint carries, seen from above.
  static constexpr std::array<const char*, 4> kHooves = {"lfHoof", "rfHoof", "lbHoof", "rbHoof"};
  for (const char* role : kHooves) {
    const int joint = horse.role(role);
    const glm::dvec3 at = d3(horse.skeleton.restPosition(joint));
    for (std::size_t i = 0; i < hp.size(); ++i)
      for (int k = 0; k < 4; ++k)
        if (horse.mesh.joints[i][k] == joint && horse.mesh.weights[i][k] > 0.5f)
          e.hoof_radius_cm = std::max(e.hoof_radius_cm, std::hypot(hp[i].x - at.x, hp[i].z - at.z));
  }
  return e;
}

GroundRect pairFootprint(const PairExtent& e, const HorseFrame& f) {
  using C = HorseChannel;
  const HorseChannels& c = f.controls;
  const glm::dvec3 pivot_move{c[C::rearPivotTx], c[C::rearPivotTy], c[C::rearPivotTz]};
  // poseHorse's body: travel · T(pivot move) · T(hips) · Ry(-ry) · Rz(rz) · Rx(rx) · T(-hips), the
  // travel frame pitched by the ground.
  const auto body = [&](glm::dvec3 p) {
    const glm::dvec3 q = rotY(rotZ(rotX(p - e.pivot, c[C::rearPivotRx]), c[C::rearPivotRz]), -c[C::rearPivotRy]);
    return rotZ(pivot_move + e.pivot + q, f.ground_pitch_deg);
  };
  double x0 = 1e300, x1 = -1e300, z0 = 1e300, z1 = -1e300;
  const auto add = [&](glm::dvec3 p) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z), z1 = std::max(z1, p.z);
  };
  for (const double x : {e.back_cm, e.front_cm})
    for (const double y : {0.0, e.top_cm})
      for (const double z : {-e.half_width_cm, e.half_width_cm}) add(body({x, y, z}));
  // The tail swung sideways by its angle about its root.
  const double swing = e.tail_reach_cm * std::abs(std::sin(f.tail_ry * kRadiansPerDegree));
  for (const double z : {-swing, swing}) add(body(e.tail_root + glm::dvec3{0.0, 0.0, z}));
  // The hooves, where their channels put them in the travel frame.
  static constexpr std::array<std::array<C, 3>, 4> kHoof = {{{C::lfHoofTx, C::lfHoofTy, C::lfHoofTz},
                                                             {C::rfHoofTx, C::rfHoofTy, C::rfHoofTz},
                                                             {C::lbHoofTx, C::lbHoofTy, C::lbHoofTz},
                                                             {C::rbHoofTx, C::rbHoofTy, C::rbHoofTz}}};
  for (std::size_t i = 0; i < 4; ++i) {
    const glm::dvec3 p = rotZ({e.hoof_rest[i].x + c[kHoof[i][0]], c[kHoof[i][1]], e.hoof_rest[i].y + c[kHoof[i][2]]},
                              f.ground_pitch_deg);
    add(p + glm::dvec3{e.hoof_radius_cm, 0.0, e.hoof_radius_cm});
    add(p - glm::dvec3{e.hoof_radius_cm, 0.0, e.hoof_radius_cm});
  }
  GroundRect g;
  const double h = f.heading_deg * kRadiansPerDegree;
  g.axis = {std::cos(h), std::sin(h)};
  const glm::dvec2 right{-g.axis.y, g.axis.x};
  const double cx = 0.5 * (x0 + x1), cz = 0.5 * (z0 + z1);
  g.center = glm::dvec2{f.travel_cm, f.travel_z_cm} + g.axis * cx + right * cz;
  g.half_length = 0.5 * (x1 - x0) + kPoseMarginCm;
  g.half_width = 0.5 * (z1 - z0) + kPoseMarginCm;
  return g;
}

bool overlaps(const GroundRect& a, const GroundRect& b) {
  const glm::dvec2 d = b.center - a.center;
  for (const GroundRect* r : {&a, &b})
    for (const glm::dvec2 n : {r->axis, glm::dvec2{-r->axis.y, r->axis.x}}) {
      const auto radius = [&n](const GroundRect& q) {
        return q.half_length * std::abs(glm::dot(q.axis, n)) +
               q.half_width * std::abs(glm::dot(glm::dvec2{-q.axis.y, q.axis.x}, n));
      };
      if (std::abs(glm::dot(d, n)) > radius(a) + radius(b)) return false;
    }
  return true;
}

std::optional<FootprintOverlap> firstOverlap(std::span<const Clip* const> clips, std::span<const double> offsets,
                                             std::span<const PairExtent> extents, double fps, int frames) {
  if (clips.size() != offsets.size() || clips.size() != extents.size())
    throw std::invalid_argument("firstOverlap: clips, offsets and extents differ in length");
  const std::size_t n = clips.size();
  std::vector<GroundRect> rects(n);
  struct Span {
    double x0, x1;
    std::size_t i;
  };
  std::vector<Span> spans(n);
  for (int frame = 1; frame <= frames; ++frame) {
    const double t = (frame - 1) / fps;
    for (std::size_t i = 0; i < n; ++i) {
      rects[i] = pairFootprint(extents[i], clips[i]->sample(t + offsets[i]));
      // The rectangle's extent along world x.
      const GroundRect& r = rects[i];
      const double half_x = r.half_length * std::abs(r.axis.x) + r.half_width * std::abs(r.axis.y);
      spans[i] = {r.center.x - half_x, r.center.x + half_x, i};
    }
    // Sweep along x: only rectangles whose x extents meet can meet.
    std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.x0 < b.x0 || (a.x0 == b.x0 && a.i < b.i); });
    std::optional<FootprintOverlap> found;
    for (std::size_t k = 0; k < n; ++k)
      for (std::size_t m = k + 1; m < n && spans[m].x0 <= spans[k].x1; ++m) {
        const std::size_t a = std::min(spans[k].i, spans[m].i), b = std::max(spans[k].i, spans[m].i);
        if (!overlaps(rects[a], rects[b])) continue;
        // The lowest-numbered pair of a frame, so the message does not depend on the sweep's order.
        if (!found || a < found->a || (a == found->a && b < found->b)) found = FootprintOverlap{a, b, frame, t};
      }
    if (found) return found;
  }
  return std::nullopt;
}

}  // namespace stirrup::rig
