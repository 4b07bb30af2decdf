// A skinned triangle mesh in its bind pose: what the skinning job deforms and the renderer draws.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

namespace stirrup::rig {

// Up to this many joints move one vertex; more adds cost without visible benefit for these bodies.
inline constexpr int kMaxInfluences = 4;

struct SkinnedMesh {
  std::vector<glm::vec3> positions;   // bind pose, world centimetres
  std::vector<glm::vec3> normals;     // bind pose, unit length
  std::vector<glm::vec3> colors;      // linear base colour per vertex
  std::vector<std::uint32_t> indices; // triangles, three per face, counter-clockwise seen from outside
  std::vector<glm::u16vec4> joints;   // skeleton joint indices, unused slots have weight 0
  std::vector<glm::vec4> weights;     // sum to 1

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return indices.size() / 3; }
};

}  // namespace stirrup::rig
