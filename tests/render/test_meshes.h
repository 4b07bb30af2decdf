// Small procedural meshes for the renderer tests: a UV sphere with exact normals.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace stirrup::render::testing {

struct TestMesh {
  std::vector<glm::vec3> positions, normals, colors;
  std::vector<uint32_t> indices;
};

// A sphere of `rings` latitude bands and `segments` longitude slices: 2 * rings * segments triangles
// (degenerate ones at the poles included, which Embree skips).
inline TestMesh makeSphere(glm::vec3 center, float radius, int rings, int segments, glm::vec3 color) {
  TestMesh m;
  for (int r = 0; r <= rings; ++r) {
    const float theta = std::numbers::pi_v<float> * float(r) / float(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * std::numbers::pi_v<float> * float(s) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(center + radius * n);
      m.normals.push_back(n);
      m.colors.push_back(color);
    }
  }
  const auto at = [segments](int r, int s) { return uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      // Counter-clockwise seen from outside.
      m.indices.insert(m.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s)});
      m.indices.insert(m.indices.end(), {at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
    }
  }
  return m;
}

}  // namespace stirrup::render::testing
