// Thin round tubes (reins, bridle straps, stirrup leathers and irons) built directly as skinned
// geometry: a grid fine enough to resolve a 1 cm rein in the implicit body would cost more
// triangles than the whole horse.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "rig/mesh.h"

namespace stirrup::rig {

struct TubePoint {
  glm::vec3 position{0.0f};
  int joint = 0;  // the joint this point follows; rings between two points blend the two joints
};

struct TubeParams {
  float radius = 1.0f;
  int sides = 8;
  float ring_spacing = 3.0f;  // cm between rings along the tube
  float sag = 0.0f;           // cm the middle droops (downward, -Y), like a slack rein
  glm::vec3 color{0.0f};
  TackPart part = TackPart::None;  // the part of a horse's tack it is (SkinnedMesh::tack_parts)
};

// Appends a closed tube (capped at both ends) along the polyline to mesh.
void appendTube(SkinnedMesh& mesh, std::span<const TubePoint> points, const TubeParams& params);

}  // namespace stirrup::rig
