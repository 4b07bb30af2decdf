// A stick-figure horse laid out by hand for the mapping's tests, in centimetres, +Y up, facing +Z, its
// left at +X, shaped like Blender's Rigify horse meta-rig (character-notes section 4): a back of six
// joints from spine1 over the croup (the tail's parent) to spine6 behind the withers, a neck of
// three, the head with ears, a jaw and nostrils, a mane along the neck reaching higher than the head,
// pelvis wings the thighs hang from (beside the midline, so they mirror each other, unlike Rigify's),
// scapulae, breast bones, a saddle joint on the back, a tail of three. The roles its anatomy gives are written out by hand (stickHorseRoles), never taken from the
// mapping.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig::test {


struct StickHorseOptions {
  // Which joints the mesh weights: the legs, back, neck, head and tail (thin); every joint, the mane,
  // ears, jaw, nostrils, breast, pelvis wings and saddle too (full); the back alone (trunk).
  enum class Weights { Thin, Full, Trunk } weights = Weights::Thin;
  bool split_legs = false;  // every leg bone cut into two equal segments in line ("thighL" and "thighL.001"), as Rigify's
  bool three_legs = false;  // no right hind leg (nor its pelvis wing)
};

struct StickHorse {
  MappingSkeleton s;

  int add(const std::string& name, int parent, glm::dvec3 at, bool weighted) {
    s.names.push_back(name);
    s.parent.push_back(parent);
    s.position.push_back(at);
    s.weighted.push_back(weighted ? 1 : 0);
    s.hung.push_back(0);
    return static_cast<int>(s.names.size()) - 1;
  }
};

inline MappingSkeleton stickHorse(const StickHorseOptions& o = {}) {
  using W = StickHorseOptions::Weights;
  StickHorse h;
  const bool thin = o.weights != W::Trunk, full = o.weights == W::Full;
  // The back, rear to front.
  int spine[7] = {-1};
  const glm::dvec3 back[6] = {{0, 130, -70}, {0, 130, -30}, {0, 128, 0}, {0, 128, 20}, {0, 130, 40}, {0, 135, 50}};
  for (int i = 0; i < 6; ++i) spine[i + 1] = h.add("spine" + std::to_string(i + 1), i ? spine[i] : -1, back[i], true);
  // Neck and head; a mane along the neck's crest ending higher than the head; ears, jaw, nostrils.
  const int neck1 = h.add("neck1", spine[6], {0, 140, 80}, thin);
  const int neck2 = h.add("neck2", neck1, {0, 160, 100}, thin);
  const int neck3 = h.add("neck3", neck2, {0, 175, 115}, thin);
  const int head = h.add("head", neck3, {0, 180, 125}, thin);
  const int mane2 = h.add("mane2", neck2, {0, 178, 96}, full);
  h.add("mane2Top", mane2, {0, 196, 94}, full);
  const int mane3 = h.add("mane3", neck3, {0, 192, 112}, full);
  h.add("mane3Top", mane3, {0, 210, 110}, full);
  for (const double side : {1.0, -1.0}) {
    const std::string n = side > 0 ? "L" : "R";
    const int ear = h.add("ear" + n, head, {side * 7, 190, 124}, full);
    h.add("ear" + n + "Tip", ear, {side * 9, 202, 122}, full);
    h.add("nostril" + n, head, {side * 4, 160, 160}, full);
  }
  const int jaw = h.add("jaw", head, {0, 168, 135}, full);
  h.add("jawTip", jaw, {0, 158, 158}, full);
  // Tail.
  int t = h.add("tail1", spine[1], {0, 134, -80}, thin);
  t = h.add("tail2", t, {0, 120, -95}, thin);
  h.add("tail3", t, {0, 100, -105}, thin);
  h.add("saddle", spine[3], {0, 150, 0}, full);
  // Legs, top down; a split bone's second segment halfway along it.
  const auto leg = [&](int from, const std::vector<std::pair<std::string, glm::dvec3>>& joints) {
    int at = from;
    for (std::size_t i = 0; i < joints.size(); ++i) {
      at = h.add(joints[i].first, at, joints[i].second, thin);
      if (o.split_legs && i + 1 < joints.size())
        at = h.add(joints[i].first + ".001", at, 0.5 * (joints[i].second + joints[i + 1].second), thin);
    }
  };
  for (const double side : {1.0, -1.0}) {
    const std::string n = side > 0 ? "L" : "R";
    h.add("breast" + n, spine[5], {side * 8, 100, 48}, full);
    leg(spine[5], {{"scapula" + n, {side * 10, 150, 58}},
                   {"shoulder" + n, {side * 15, 112, 72}},
                   {"elbow" + n, {side * 15, 85, 58}},
                   {"knee" + n, {side * 15, 45, 60}},
                   {"foreFetlock" + n, {side * 15, 18, 61}},
                   {"foreHoof" + n, {side * 15, 5, 64}}});
    if (o.three_legs && side < 0) continue;
    const int pelvis = h.add("pelvis" + n, spine[2], {side * 6, 132, -60}, full);
    leg(pelvis, {{"thigh" + n, {side * 18, 128, -45}},
                 {"stifle" + n, {side * 18, 90, -32}},
                 {"hock" + n, {side * 18, 55, -50}},
                 {"hindFetlock" + n, {side * 18, 18, -48}},
                 {"hindHoof" + n, {side * 18, 5, -45}}});
  }
  MappingSkeleton& s = h.s;
  s.file = "horse.glb";
  // The mesh: a point at every joint, and the ground under the hooves.
  for (const glm::dvec3& p : s.position) s.vertices.push_back(p), s.vertex_joint.push_back(0);
  s.vertices.push_back({0, 0, 0});
  s.vertex_joint.push_back(0);
  s.finish();
  return s;
}

// The roles the stick horse's anatomy gives: the thighs hang from the pelvis wings, so the hips are the
// back's joint whose bone passes over the hip joints (spine1, the spine1-spine2 bone over them); the
// scapulae hang from spine5 (the chest); backMid the middle of spine1..spine5; the neck from neck1
// (ahead of the scapulae; spine6 behind them is the withers' back joint), neck2 its middle; the head;
// the tail spread over its three joints; each leg's pivot, elbow or stifle, knee or hock, fetlock and
// hoof (the first segment of a split bone).
inline std::map<std::string, std::string> stickHorseRoles() {
  std::map<std::string, std::string> r = {{"root", "spine1"},   {"backMid", "spine3"}, {"chest", "spine5"}, {"neck1", "neck1"},
                                          {"neck2", "neck2"},   {"head", "head"},       {"tail1", "tail1"},  {"tail2", "tail2"},
                                          {"tail3", "tail3"}};
  for (const char* side : {"L", "R"}) {
    const std::string s = side, l = side[0] == 'L' ? "l" : "r";
    r[l + "fPivot"] = "scapula" + s, r[l + "fUpper"] = "elbow" + s, r[l + "fMiddle"] = "knee" + s;
    r[l + "fFetlock"] = "foreFetlock" + s, r[l + "fHoof"] = "foreHoof" + s;
    r[l + "bPivot"] = "thigh" + s, r[l + "bUpper"] = "stifle" + s, r[l + "bMiddle"] = "hock" + s;
    r[l + "bFetlock"] = "hindFetlock" + s, r[l + "bHoof"] = "hindHoof" + s;
  }
  return r;
}

}  // namespace stirrup::rig::test
