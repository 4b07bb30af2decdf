// Checks of a horse's tack labels (SkinnedMesh::tack_parts, rig/tack_part.h) against what each vertex is:
// the colour the generator painted it and the joints that move it. For the generated horse's own tack and
// the tack the rig adds to a user's horse.
#pragma once

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "rig/character.h"
#include "rig/characters/horse_character.h"

namespace stirrup::rig::test {

// How many vertices each part has (None: the body).
inline std::map<TackPart, std::size_t> tackPartCounts(const SkinnedMesh& m) {
  std::map<TackPart, std::size_t> out;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) ++out[m.tackPart(v)];
  return out;
}

// Every labelled vertex has its part's colours (HorseParams' leather, pad, metal) and is moved most by its
// part's joints: the irons by their stirrup joint, the leathers by the saddle or their stirrup, the bit and
// bridle by the head, the saddle and pad by the saddle joint; the reins run from the head to the rein hand
// ends. Left parts lie left of the midline (z < 0), right ones right of it. Each part has 20 vertices or more.
inline void expectTackLabelsFit(const Character& horse, const HorseParams& p = {}) {
  const SkinnedMesh& m = horse.mesh;
  ASSERT_EQ(m.tack_parts.size(), m.vertexCount());
  const int saddle = horse.role("saddle"), head = horse.role("head");
  const int ls = horse.role("lStirrup"), rs = horse.role("rStirrup"), lr = horse.role("lRein"), rr = horse.role("rRein");
  const std::map<TackPart, std::set<int>> joints = {
      {TackPart::Saddle, {saddle}},          {TackPart::SaddlePad, {saddle}},        {TackPart::Bridle, {head}},
      {TackPart::Bit, {head}},               {TackPart::StirrupLeatherL, {saddle, ls}}, {TackPart::StirrupLeatherR, {saddle, rs}},
      {TackPart::StirrupIronL, {ls}},        {TackPart::StirrupIronR, {rs}}};
  const auto colours = [&](TackPart part) -> std::vector<glm::vec3> {
    switch (part) {
      case TackPart::SaddlePad: return {p.pad, p.leather};
      case TackPart::Bit:
      case TackPart::StirrupIronL:
      case TackPart::StirrupIronR: return {p.metal};
      default: return {p.leather};
    }
  };
  std::map<TackPart, std::string> wrong;
  std::set<int> rein_joints;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const TackPart part = m.tackPart(v);
    if (part == TackPart::None) continue;
    const std::vector<glm::vec3> c = colours(part);
    if (std::find(c.begin(), c.end(), m.colors[v]) == c.end()) wrong[part] = "vertex " + std::to_string(v) + ": not its part's colour";
    int most = 0;
    for (int k = 0; k < kMaxInfluences; ++k) {
      if (m.weights[v][k] > m.weights[v][most]) most = k;
      if (part == TackPart::Reins && m.weights[v][k] > 0.0f) rein_joints.insert(m.joints[v][k]);
    }
    if (const int j = m.joints[v][most]; part != TackPart::Reins && !joints.at(part).count(j))
      wrong[part] = "vertex " + std::to_string(v) + ": moved most by " + horse.skeleton.joints[std::size_t(j)].name;
    const bool left = part == TackPart::StirrupLeatherL || part == TackPart::StirrupIronL;
    const bool right = part == TackPart::StirrupLeatherR || part == TackPart::StirrupIronR;
    if ((left && !(m.positions[v].z < 0.0f)) || (right && !(m.positions[v].z > 0.0f))) wrong[part] = "vertex " + std::to_string(v) + ": on the other side";
  }
  for (const auto& [part, what] : wrong) ADD_FAILURE() << tackPartName(part) << ": " << what;
  for (const int j : {head, lr, rr}) EXPECT_TRUE(rein_joints.count(j)) << "the reins are moved by " << horse.skeleton.joints[std::size_t(j)].name;
  const std::map<TackPart, std::size_t> counts = tackPartCounts(m);
  for (TackPart part : kTackParts) EXPECT_GT(counts.count(part) ? counts.at(part) : 0u, 20u) << tackPartName(part);
}

}  // namespace stirrup::rig::test
