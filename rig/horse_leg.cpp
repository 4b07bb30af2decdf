#include "rig/horse_leg.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "rig/ik.h"
#include "rig/pose_transforms.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {

// Bisection steps for the stretch fraction: 2^-24 of the stretch, far below a micron of reach.
constexpr int kStretchSteps = 24;

float angleAt(glm::vec3 at, glm::vec3 p, glm::vec3 q) {
  const glm::vec3 a = glm::normalize(p - at), b = glm::normalize(q - at);
  return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
}
// The third side of a triangle with sides l1, l2 and the angle between them.
float span(float l1, float l2, float angle) {
  return std::sqrt(std::max(l1 * l1 + l2 * l2 - 2.0f * l1 * l2 * std::cos(angle), 0.0f));
}
glm::mat4 placed(glm::vec3 at, const glm::mat3& rotation) {
  glm::mat4 m(rotation);
  m[3] = glm::vec4(at, 1.0f);
  return m;
}
using pose_transforms::transformPoint;

// The virtual chain of a leg at rest and at full stretch: a (pivot to upper), b (upper to fetlock),
// gamma (the angle at upper), each a function of the stretch fraction t.
struct VirtualChain {
  bool two_part_upper = false;
  float l_ps = 0, l_su = 0, sigma0 = 0, sigma1 = 0;  // fore: scapula, humerus, shoulder angle rest/open
  float a_rigid = 0;                                 // hind: the femur
  float l_um = 0, l_mf = 0, kappa0 = 0, kappa1 = 0;  // the two bones below, their angle rest/open
  float gamma0 = 0, gamma1 = 0;

  float a(float t) const { return two_part_upper ? span(l_ps, l_su, sigma0 + t * (sigma1 - sigma0)) : a_rigid; }
  float b_max = 0;  // kept clear of the two-bone solve's softening, so a reached target is exact
  float b(float t) const { return std::min(span(l_um, l_mf, kappa0 + t * (kappa1 - kappa0)), std::max(b_max, b0())); }
  float b0() const { return span(l_um, l_mf, kappa0); }
  float gamma(float t) const { return gamma0 + t * (gamma1 - gamma0); }
  float reach(float t) const { return span(a(t), b(t), gamma(t)); }
};

struct RestLeg {
  glm::vec3 pivot, shoulder, upper, middle, fetlock, hoof;
};

RestLeg restLeg(const Skeleton& s, const HorseLegJoints& j) {
  RestLeg r;
  r.pivot = s.restPosition(j.pivot);
  r.shoulder = j.shoulder >= 0 ? s.restPosition(j.shoulder) : r.pivot;
  r.upper = s.restPosition(j.upper);
  r.middle = s.restPosition(j.middle);
  r.fetlock = s.restPosition(j.fetlock);
  r.hoof = s.restPosition(j.hoof);
  return r;
}

VirtualChain virtualChain(const RestLeg& r, bool two_part_upper, bool fore, const HorseLegParams& p) {
  VirtualChain c;
  c.two_part_upper = two_part_upper;
  if (two_part_upper) {
    c.l_ps = glm::length(r.shoulder - r.pivot);
    c.l_su = glm::length(r.upper - r.shoulder);
    c.sigma0 = angleAt(r.shoulder, r.pivot, r.upper);
    c.sigma1 = std::max(c.sigma0, p.shoulder_open_deg * kRadiansPerDegreeF);
  } else {
    c.a_rigid = glm::length(r.upper - r.pivot);
  }
  c.l_um = glm::length(r.middle - r.upper);
  c.l_mf = glm::length(r.fetlock - r.middle);
  c.kappa0 = angleAt(r.middle, r.upper, r.fetlock);
  c.kappa1 = std::max(c.kappa0, (fore ? p.knee_open_deg : p.hock_open_deg) * kRadiansPerDegreeF);
  c.b_max = c.l_um + c.l_mf - 2.0f * p.soften_cm;
  c.gamma0 = angleAt(r.upper, r.pivot, r.fetlock);
  c.gamma1 = std::max(c.gamma0, p.line_open_deg * kRadiansPerDegreeF);
  return c;
}

// Rolls the hoof about its toe (target behind the pivot: breakover) or its heel (ahead: landing)
// until the fetlock comes within `reach` of the pivot, at most roll_max_deg. The edges lie on the sole,
// `sole_cm` below the hoof joint in the hoof's own frame (the joint's rest height above the ground: 0
// for the default horse, whose hoof joint is its sole's centre; a user's horse may have it above the
// sole, and rolled about a point that high its sole would slide). Returns the rotation about the
// contact edge (identity when the leg reaches without it).
glm::mat4 hoofRoll(const HorseLegTarget& t, glm::vec3 n, glm::vec3 forward, glm::vec3 pivot, glm::vec3 fetlock,
                   float reach, float sole_cm, const HorseLegParams& p) {
  if (glm::length(fetlock - pivot) <= reach) return glm::mat4(1.0f);
  const bool behind = glm::dot(fetlock - pivot, forward) < 0.0f;
  const glm::vec3 edge = behind ? glm::vec3(p.toe_cm, -sole_cm, 0.0f) : glm::vec3(-p.heel_cm, -sole_cm, 0.0f);
  const glm::vec3 contact = t.hoof + glm::vec3(t.fold * glm::vec4(edge, 0.0f));
  const glm::vec3 f = fetlock - contact, q = pivot - contact;
  const glm::vec3 f_p = f - n * glm::dot(n, f), q_p = q - n * glm::dot(n, q);
  const float dn = glm::dot(n, f - q);  // unchanged by a turn about n
  const float r = glm::length(f_p), d = glm::length(q_p);
  if (r < 1e-4f || d < 1e-4f) return glm::mat4(1.0f);
  const float want = std::max(reach * reach - dn * dn, 0.0f);
  const float cos_psi = (r * r + d * d - want) / (2.0f * r * d);
  const float psi = std::acos(std::clamp(cos_psi, -1.0f, 1.0f));
  const float psi0 = std::atan2(glm::dot(n, glm::cross(q_p, f_p)), glm::dot(q_p, f_p));
  if (std::abs(psi0) <= psi) return glm::mat4(1.0f);
  const float roll = std::clamp((psi0 > 0 ? psi : -psi) - psi0, -p.roll_max_deg * kRadiansPerDegreeF, p.roll_max_deg * kRadiansPerDegreeF);
  return glm::translate(glm::mat4(1.0f), contact) * glm::rotate(glm::mat4(1.0f), roll, n) *
         glm::translate(glm::mat4(1.0f), -contact);
}

// Joints on the way from `top` down to `below` (both excluded) carried rigidly by `top`'s motion, as
// they hang at rest: a split bone's further segments.
void carryBetween(const Skeleton& s, int top, int below, std::span<glm::mat4> world) {
  std::vector<int> path = s.pathFrom(top, below);
  if (!path.empty()) path.pop_back();
  for (int j : path) {
    const int p = s.joints[j].parent;
    world[j] = world[p] * s.joints[p].inverse_bind * s.restWorld(j);
  }
}

}  // namespace

int horseLegShoulder(const Skeleton& s, int pivot, int upper) {
  const std::vector<int> path = s.pathFrom(pivot, upper);  // pivot's child .. upper
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const glm::vec3 before = s.restPosition(s.joints[path[i]].parent), at = s.restPosition(path[i]);
    const glm::vec3 after = s.restPosition(path[i + 1]);
    if (glm::length(at - before) <= 0.0f || glm::length(after - at) <= 0.0f) continue;
    if (kPiF - angleAt(at, before, after) > kInLineDeg * kRadiansPerDegreeF) return path[i];
  }
  return -1;
}

float horseLegFullReach(const Skeleton& s, const HorseLegJoints& leg, const HorseLegParams& params) {
  return virtualChain(restLeg(s, leg), leg.shoulder >= 0, leg.fore, params).reach(1.0f);
}

float solveHorseLeg(const Skeleton& s, const HorseLegJoints& leg, const HorseLegTarget& target,
                    const HorseLegParams& params, std::span<glm::mat4> world) {
  const RestLeg r = restLeg(s, leg);
  const bool two_part = leg.shoulder >= 0;
  const VirtualChain chain = virtualChain(r, two_part, leg.fore, params);
  const int parent = s.joints[leg.pivot].parent;
  const glm::mat4 parent_motion = world[parent] * s.joints[parent].inverse_bind;
  const glm::vec3 pivot = transformPoint(parent_motion, r.pivot);
  // The leg plane turns and rolls with the body.
  const glm::vec3 body_side = glm::normalize(glm::mat3(parent_motion) * glm::vec3(0.0f, 0.0f, 1.0f));
  const glm::vec3 body_forward = glm::normalize(glm::mat3(parent_motion) * glm::vec3(1.0f, 0.0f, 0.0f));

  // Targets, the hoof rolled over an edge if even the stretched leg falls short.
  glm::vec3 fetlock = target.hoof + glm::vec3(target.fold * glm::vec4(r.fetlock - r.hoof, 0.0f));
  const float full = chain.reach(1.0f);
  const glm::mat4 roll = hoofRoll(target, body_side, body_forward, pivot, fetlock, full, r.hoof.y, params);
  fetlock = transformPoint(roll, fetlock);
  const glm::mat4 fold = glm::mat4(glm::mat3(roll)) * target.fold;

  // The stretch: none up to the rest reach (the upper part swings rigidly), then by bisection.
  const float rest_reach = chain.reach(0.0f);
  const float d = glm::length(fetlock - pivot);
  float t = 0.0f;
  if (d >= full) {
    t = 1.0f;
  } else if (d > rest_reach) {
    float lo = 0.0f, hi = 1.0f;
    for (int i = 0; i < kStretchSteps; ++i) {
      const float mid = 0.5f * (lo + hi);
      (chain.reach(mid) < d ? lo : hi) = mid;
    }
    t = 0.5f * (lo + hi);
  }
  const float a = chain.a(t), b = chain.b(t);
  // Angles at the pivot, from the fetlock line toward the side the upper part lies on at rest. The
  // upper part turns with upper_swing of the line's swing (the two bones below take the rest), but
  // never so far off the line that the bones below would have to span more than b.
  const glm::vec3 rest_u = glm::normalize(r.fetlock - r.pivot);
  const glm::vec3 rest_v = glm::normalize(glm::cross(glm::vec3(0.0f, 0.0f, 1.0f), rest_u));
  const glm::vec3 rest_upper = r.upper - r.pivot;
  const float side = glm::dot(rest_upper, rest_v) >= 0.0f ? 1.0f : -1.0f;
  const float theta0 = std::atan2(side * glm::dot(rest_upper, rest_v), glm::dot(rest_upper, rest_u));
  const glm::vec3 u = d > 1e-4f ? (fetlock - pivot) / d : -glm::normalize(glm::vec3(parent_motion[1]));
  const glm::vec3 w = side * glm::normalize(glm::cross(body_side, u));
  const glm::vec3 carried_u = glm::mat3(parent_motion) * rest_u;  // the rest line, carried by the body
  const float swing = -std::atan2(glm::dot(carried_u, w), glm::dot(carried_u, u));
  const float theta_max = std::acos(std::clamp((a * a + d * d - b * b) / (2.0f * a * std::max(d, 1e-4f)), -1.0f, 1.0f));
  const float theta = std::clamp(theta0 - (1.0f - params.upper_swing) * swing, -theta_max, theta_max);
  const glm::vec3 upper = pivot + a * (std::cos(theta) * u + std::sin(theta) * w);

  // The upper part: the scapula and humerus as a two-bone chain bending as at rest, or the femur.
  const glm::vec3 rest_side(0.0f, 0.0f, 1.0f);
  if (two_part) {
    // The pole swings with the leg, so the shoulder keeps its side of the scapula-elbow line.
    const glm::vec3 rest_pole = restPole(r.pivot, r.shoulder, r.upper, 40.0f);
    const glm::mat3 swing = boneRotation(rest_u, rest_side, u, body_side);
    const glm::vec3 pole = pivot + swing * (rest_pole - r.pivot);
    const LimbPose top = solveLimb(r.pivot, r.shoulder, r.upper, rest_pole, pivot, upper, pole, 0.0f);
    world[leg.pivot] = top.upper;
    world[leg.shoulder] = top.middle;
  } else {
    world[leg.pivot] = placed(pivot, boneRotation(r.upper - r.pivot, rest_side, upper - pivot, body_side));
  }

  carryBetween(s, two_part ? leg.shoulder : leg.pivot, leg.upper, world);

  // The two bones below, bending toward their rest pole carried by the upper part.
  const int upper_parent = s.joints[leg.upper].parent;
  const glm::mat4 upper_motion = world[upper_parent] * s.joints[upper_parent].inverse_bind;
  const glm::vec3 rest_pole = restPole(r.upper, r.middle, r.fetlock, 40.0f);
  const glm::vec3 upper_pos = transformPoint(upper_motion, r.upper);
  const LimbPose limb = solveLimb(r.upper, r.middle, r.fetlock, rest_pole, upper_pos, fetlock,
                                  transformPoint(upper_motion, rest_pole), params.soften_cm);
  world[leg.upper] = limb.upper;
  world[leg.middle] = limb.middle;
  world[leg.fetlock] = placed(limb.end, glm::mat3(fold));
  world[leg.hoof] = placed(limb.end + glm::vec3(fold * glm::vec4(r.hoof - r.fetlock, 0.0f)), glm::mat3(fold));
  return glm::length(limb.end - fetlock);
}

}  // namespace stirrup::rig
