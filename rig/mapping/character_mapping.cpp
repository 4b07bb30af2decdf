#include "rig/mapping/character_mapping.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "rig/characters/rider_character.h"
#include "rig/error.h"

namespace stirrup::rig {

std::string_view characterKindName(CharacterKind kind) { return kind == CharacterKind::Horse ? "horse" : "rider"; }

const std::vector<std::string>& requiredRoles(CharacterKind kind) {
  static const std::vector<std::string> horse = [] {
    std::vector<std::string> r = {"root", "neck1", "head"};
    for (const char* leg : {"lf", "rf", "lb", "rb"})
      for (const char* part : {"Upper", "Middle", "Fetlock", "Hoof"}) r.push_back(std::string(leg) + part);
    return r;
  }();
  static const std::vector<std::string> rider = [] {
    std::vector<std::string> r = {"pelvis", "neck", "head"};
    for (const char* side : {"l", "r"})
      for (const char* part : {"Shoulder", "Elbow", "Wrist", "Hip", "Knee", "Ankle"}) r.push_back(std::string(side) + part);
    return r;
  }();
  return kind == CharacterKind::Horse ? horse : rider;
}

const std::vector<std::string>& optionalRoles(CharacterKind kind) {
  static const std::vector<std::string> horse = {"backMid", "chest",    "withers",  "neck2", "tail1", "tail2",
                                                 "tail3",   "saddle",   "lStirrup", "rStirrup", "lRein", "rRein",
                                                 "lfPivot", "rfPivot", "lbPivot", "rbPivot"};
  static const std::vector<std::string> rider = [] {
    std::vector<std::string> r = {"lowerBack", "waist", "chest", "upperChest", "hipCentre", "braid1", "braid2", "braid3", "coatTail"};
    for (const char* side : {"l", "r"})
      for (const char* part : {"Hand", "Ball"}) r.push_back(std::string(side) + part);
    for (int i = 0; i <= kRiderSpineSegments; ++i) r.push_back("spine" + std::to_string(i));
    return r;
  }();
  return kind == CharacterKind::Horse ? horse : rider;
}

namespace {

// `role` must lie below `above` (or on it, where `may_share`); `what` says where it belongs.
struct RoleBelow {
  std::string role, above;
  bool may_share;
  std::string what;
};

const std::vector<RoleBelow>& roleChains(CharacterKind kind) {
  static const std::vector<RoleBelow> rider = [] {
    std::vector<RoleBelow> r = {{"head", "neck", false, "the head above the neck on the spine's chain"},
                                {"upperChest", "pelvis", false, "upperChest on the spine between the pelvis and the neck"},
                                {"neck", "upperChest", false, "upperChest on the spine between the pelvis and the neck"}};
    for (const std::string side : {"l", "r"}) {
      r.push_back({side + "Elbow", side + "Shoulder", false, "the elbow on the arm's chain below the shoulder"});
      r.push_back({side + "Wrist", side + "Elbow", false, "the wrist on the arm's chain below the elbow"});
      r.push_back({side + "Hand", side + "Wrist", true, "the grip at or below the wrist"});  // shared: the rig adds the grip
      r.push_back({side + "Knee", side + "Hip", false, "the knee on the leg's chain below the hip"});
      r.push_back({side + "Ankle", side + "Knee", false, "the ankle on the leg's chain below the knee"});
      r.push_back({side + "Ball", side + "Ankle", true, "the ball of the foot at or below the ankle"});  // shared: the rig adds the sole
    }
    return r;
  }();
  // A horse's roles may share joints (a user's horse with fewer joints than roles: the Fox's fore legs
  // have no joint between the knee and the ground), so only a joint off the chain is refused.
  static const std::vector<RoleBelow> horse = [] {
    std::vector<RoleBelow> r = {{"head", "neck1", false, "the head beyond the neck's first joint"},
                                {"neck2", "neck1", true, "the neck's joints in order from the chest"},
                                {"head", "neck2", true, "the head at or beyond the neck"},
                                {"tail2", "tail1", true, "the tail's joints in order from its root"},
                                {"tail3", "tail2", true, "the tail's joints in order from its root"},
                                {"tail3", "tail1", true, "the tail's joints in order from its root"}};
    for (const std::string leg : {"lf", "rf", "lb", "rb"}) {
      r.push_back({leg + "Upper", leg + "Pivot", true, "the leg's upper joint at or below its pivot"});
      r.push_back({leg + "Middle", leg + "Upper", true, "the leg's joints in order down to the hoof"});
      r.push_back({leg + "Fetlock", leg + "Middle", true, "the leg's joints in order down to the hoof"});
      r.push_back({leg + "Hoof", leg + "Fetlock", true, "the leg's joints in order down to the hoof"});
    }
    return r;
  }();
  return kind == CharacterKind::Horse ? horse : rider;
}

}  // namespace

std::string roleChainProblem(CharacterKind kind, const std::map<std::string, int>& roles, const std::vector<int>& parent,
                             const std::vector<std::string>& names, const std::string& hint) {
  const std::string tail = hint.empty() ? ")" : "; " + hint + ")";
  const int n = static_cast<int>(parent.size());
  const auto name = [&](int j) { return "\"" + (j >= 0 && j < static_cast<int>(names.size()) ? names[j] : std::to_string(j)) + "\""; };
  // Bones from `a` down to `j`, or -1 when `a` is not `j` or above it.
  const auto bonesBelow = [&](int a, int j) {
    int steps = 0;
    for (int k = j; k >= 0 && k < n && steps <= n; k = parent[k], ++steps)
      if (k == a) return steps;
    return -1;
  };
  const auto at = [&](const std::string& role) {
    const auto it = roles.find(role);
    return it == roles.end() ? -1 : it->second;
  };
  if (kind == CharacterKind::Rider) {
    const int pelvis = at("pelvis"), neck = at("neck");
    if (pelvis >= 0 && neck >= 0 && bonesBelow(pelvis, neck) < 2)
      return "roles.neck: joint " + name(neck) + " is not above pelvis " + name(pelvis) +
             " with a spine joint between them (expected the neck on the chain that runs up from the pelvis" + tail;
  }
  if (kind == CharacterKind::Horse) {
    // The tail swings with all it holds: it must not hold the body (the tail's first joint mapped to the
    // hips or a back joint would swing the whole horse).
    const int tail1 = at("tail1");
    for (const char* held : {"root", "neck1"})
      if (const int j = at(held); tail1 >= 0 && j >= 0 && bonesBelow(tail1, j) >= 0)
        return "roles.tail1: joint " + name(tail1) + " holds " + held + " " + name(j) +
               " (expected the tail's first joint, on a chain of its own behind the hips" + tail;
  }
  for (const RoleBelow& c : roleChains(kind)) {
    const int j = at(c.role), a = at(c.above);
    if (j < 0 || a < 0) continue;
    const int steps = bonesBelow(a, j);
    if (steps > 0 || (steps == 0 && c.may_share)) continue;
    return "roles." + c.role + ": joint " + name(j) + " is not below " + c.above + " " + name(a) + " (expected " + c.what + tail;
  }
  return "";
}

std::vector<int> hangLegsFromPivots(const std::map<std::string, int>& roles, std::vector<int>& parent,
                                    const std::vector<char>& file_root) {
  const int n = static_cast<int>(parent.size());
  const auto holds = [&](int a, int j) {  // `a` is `j` or above it
    for (int steps = 0; j >= 0 && steps <= n; j = parent[j], ++steps)
      if (j == a) return true;
    return false;
  };
  std::vector<int> hung;
  for (const char* leg : {"lf", "rf", "lb", "rb"}) {
    const auto pivot = roles.find(std::string(leg) + "Pivot"), upper = roles.find(std::string(leg) + "Upper");
    if (pivot == roles.end() || upper == roles.end() || holds(pivot->second, upper->second)) continue;
    int top = upper->second;
    for (int steps = 0; !file_root[top] && parent[top] >= 0 && steps <= n; ++steps) top = parent[top];
    if (!file_root[top] || holds(top, pivot->second)) continue;
    parent[top] = pivot->second;
    hung.push_back(top);
  }
  return hung;
}

std::pair<std::string, std::string> mappingAxesProblem(const std::array<double, 3>& forward, const std::array<double, 3>& up) {
  const auto len = [](const std::array<double, 3>& a) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; };
  const double dot = forward[0] * up[0] + forward[1] * up[1] + forward[2] * up[2];
  if (!(len(forward) > 1e-12)) return {"forward", "expected a non-zero direction"};
  if (!(len(up) > 1e-12)) return {"up", "expected a non-zero direction"};
  if (std::abs(dot) > 1e-6 * std::sqrt(len(forward) * len(up))) return {"up", "expected a direction at right angles to forward"};
  return {};
}

glm::dmat4 mappingToRig(const CharacterMapping& m) {
  const glm::dvec3 fw = glm::normalize(glm::dvec3(m.forward[0], m.forward[1], m.forward[2]));
  const glm::dvec3 up = glm::normalize(glm::dvec3(m.up[0], m.up[1], m.up[2]));
  const glm::dmat3 rows(fw, up, glm::cross(fw, up));  // columns; transposed, the rows
  glm::dmat4 to_rig(glm::transpose(rows) * m.scale_cm);
  to_rig[3] = glm::dvec4(m.offset_cm[0], m.offset_cm[1], m.offset_cm[2], 1.0);
  return to_rig;
}

}  // namespace stirrup::rig
