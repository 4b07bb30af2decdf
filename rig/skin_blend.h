// A vertex's blended skinning matrix and skinned position: one definition, so that skinMesh,
// skinPositions (rig/skin.h) and skinnedBox (rig/skin_box.h) place every vertex to the same bits.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "rig/mesh.h"

namespace stirrup::rig {

inline glm::mat4 skinBlendAt(const SkinnedMesh& mesh, const std::vector<glm::mat4>& m, std::size_t v) {
  const glm::u16vec4 j = mesh.joints[v];
  const glm::vec4 w = mesh.weights[v];
  glm::mat4 blend(0.0f);
  for (int i = 0; i < kMaxInfluences; ++i)
    if (w[i] > 0.0f) blend += w[i] * m[j[i]];
  return blend;
}

inline glm::vec3 skinPositionAt(const SkinnedMesh& mesh, const std::vector<glm::mat4>& m, std::size_t v) {
  return glm::vec3(skinBlendAt(mesh, m, v) * glm::vec4(mesh.positions[v], 1.0f));
}

}  // namespace stirrup::rig
