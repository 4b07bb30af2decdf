#include "rig/rider_spine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace stirrup::rig {
namespace {

// The generator's layout (buildRider): controllers parented pelvis -> lowerBack -> waist -> chest,
// straight up; a chain of kChainBones equal bones straight up from the lower back to upperChest.
constexpr int kGeneratorChainBones = 10;  // CurveSpine::kRiderSegments
constexpr float kStraightTolerance = 1e-3f;

bool laidOnCurve(const Character& rider, const RiderSpine& sp, int upper_chest) {
  const Skeleton& s = rider.skeleton;
  if (upper_chest < 0 || static_cast<int>(sp.chain.size()) != kGeneratorChainBones + 1) return false;
  const std::array<int, 3>& c = sp.controllers;
  if (c[0] < 0 || c[1] < 0 || c[2] < 0) return false;
  if (s.joints[c[0]].parent != sp.pelvis || s.joints[c[1]].parent != c[0] || s.joints[c[2]].parent != c[1]) return false;
  const auto straightUp = [&](glm::vec3 d) {
    return d.y > 0.0f && std::abs(d.x) <= kStraightTolerance && std::abs(d.z) <= kStraightTolerance;
  };
  const std::array<int, 4> fk = {c[0], c[1], c[2], upper_chest};
  for (int k = 0; k < 3; ++k)
    if (!straightUp(s.restPosition(fk[k + 1]) - s.restPosition(fk[k]))) return false;
  if (glm::length(s.restPosition(sp.chain[0]) - s.restPosition(c[0])) > kStraightTolerance) return false;
  const float bone = glm::length(s.restPosition(sp.chain[1]) - s.restPosition(sp.chain[0]));
  for (std::size_t i = 0; i + 1 < sp.chain.size(); ++i) {
    const glm::vec3 d = s.restPosition(sp.chain[i + 1]) - s.restPosition(sp.chain[i]);
    if (!straightUp(d) || std::abs(d.y - bone) > kStraightTolerance) return false;
  }
  return true;
}

int optionalRole(const Character& c, const char* role) {
  const auto it = c.roles.find(role);
  return it == c.roles.end() ? -1 : it->second;
}

}  // namespace

RiderSpine riderSpine(const Character& rider) {
  const Skeleton& s = rider.skeleton;
  RiderSpine sp;
  sp.pelvis = rider.role("pelvis");
  sp.neck = rider.role("neck");
  const auto jointName = [&](int j) { return "\"" + s.joints[j].name + "\""; };
  const int upper_chest = optionalRole(rider, "upperChest");
  const std::vector<int> to_neck = s.pathFrom(sp.pelvis, sp.neck);
  if (to_neck.size() < 2)
    throw std::invalid_argument("roles.neck: joint " + jointName(sp.neck) + " is not below the pelvis joint " +
                                jointName(sp.pelvis) + " with at least one spine joint between them (map the neck to a "
                                "joint of the chain that runs up from the pelvis)");
  if (upper_chest >= 0) {
    const auto it = std::find(to_neck.begin(), to_neck.end(), upper_chest);
    if (it == to_neck.end() || upper_chest == sp.neck)
      throw std::invalid_argument("roles.upperChest: joint " + jointName(upper_chest) + " is not between the pelvis " +
                                  jointName(sp.pelvis) + " and the neck " + jointName(sp.neck) +
                                  " (map it to the spine joint the shoulders hang from, or leave it out)");
    sp.chain.assign(to_neck.begin(), it + 1);
  } else {
    // The joint the neck hangs from is the chain's top (its upper chest), as on the generated rider: the
    // curve bends the back below it and the neck rides on its tip. A spine of one joint has no other
    // bone to bend, so its curve runs on to the neck.
    sp.chain.assign(to_neck.begin(), to_neck.end() - 1);
    sp.ends_at_neck = sp.chain.size() == 1;
  }
  const glm::vec3 pelvis_at = s.restPosition(sp.pelvis);
  for (int j : sp.chain) sp.points.push_back(glm::dvec3(s.restPosition(j) - pelvis_at));
  if (sp.ends_at_neck) sp.points.push_back(glm::dvec3(s.restPosition(sp.neck) - pelvis_at));
  sp.arc.assign(sp.points.size(), 0.0);
  for (std::size_t i = 1; i < sp.points.size(); ++i) sp.arc[i] = sp.arc[i - 1] + glm::length(sp.points[i] - sp.points[i - 1]);
  sp.root = glm::vec3(sp.points.front());
  const double length = sp.arc.back();
  if (!(length > 1e-3))
    throw std::invalid_argument("roles.neck: the spine from " + jointName(sp.pelvis) + " to " + jointName(sp.neck) +
                                " has no length at rest");

  // Controllers: joints of their own off the chain are posed as the FK controllers; on the chain
  // they only say where the curve's FK bones meet.
  std::array<double, 3> at = {0.0, length / 3.0, 2.0 * length / 3.0};
  static constexpr std::array<const char*, 3> kControllers = {"lowerBack", "waist", "chest"};
  bool split_on_chain = true;
  for (int k = 0; k < 3; ++k) {
    const int j = optionalRole(rider, kControllers[k]);
    if (j < 0) {
      split_on_chain = false;
      continue;
    }
    const auto on = std::find(sp.chain.begin(), sp.chain.end(), j);
    if (on == sp.chain.end()) {
      sp.controllers[k] = j;
      split_on_chain = false;
    } else {
      at[k] = sp.arc[static_cast<std::size_t>(on - sp.chain.begin())];
    }
  }
  sp.laid_on_curve = laidOnCurve(rider, sp, upper_chest);
  if (sp.laid_on_curve) {
    const std::array<int, 4> fk = {sp.controllers[0], sp.controllers[1], sp.controllers[2], upper_chest};
    for (int k = 0; k < 3; ++k) sp.fk_lengths[k] = s.restPosition(fk[k + 1]).y - s.restPosition(fk[k]).y;
    sp.root = s.restPosition(sp.controllers[0]) - pelvis_at;
    return sp;
  }
  // Controllers named on the chain split it where they are, if in order; else thirds.
  if (!(split_on_chain && at[0] < at[1] && at[1] < at[2] && at[2] < length))
    at = {0.0, length / 3.0, 2.0 * length / 3.0};
  sp.fk_lengths = {at[1], at[2] - at[1], length - at[2]};  // the curve starts at chain[0], arc 0
  return sp;
}

}  // namespace stirrup::rig
