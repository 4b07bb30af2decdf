// A skinned triangle mesh in its bind pose: what the skinning job deforms and the renderer draws.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <numeric>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include "rig/tack_part.h"
#include "rig/texture.h"

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

  // Base colour textures; all three empty for an untextured mesh. A textured triangle's colour at a
  // point is its interpolated vertex colour times its texture at the interpolated uv.
  std::vector<glm::vec2> uvs;                            // per vertex (glTF's: (0, 0) the image's top-left)
  std::vector<std::int32_t> triangle_textures;           // per triangle: index into textures, or -1
  std::vector<std::shared_ptr<const Texture>> textures;  // shared: a character's copies share the images

  // A horse's tack, part by part (rig/tack_part.h): per vertex, the part it belongs to (None: the body);
  // empty for a mesh without tack. A triangle belongs to its first vertex's part, as it takes that
  // vertex's colour. Only the glTF writer reads it (rig/io/gltf_tack.h): nothing drawn depends on it.
  std::vector<TackPart> tack_parts;

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return indices.size() / 3; }
  bool textured() const { return !textures.empty(); }
  // Triangle t's texture, or -1.
  int triangleTexture(std::size_t t) const { return triangle_textures.empty() ? -1 : triangle_textures[t]; }
  TackPart tackPart(std::size_t v) const { return tack_parts.empty() ? TackPart::None : tack_parts[v]; }
  TackPart triangleTackPart(std::size_t t) const { return tackPart(indices[t * 3]); }
  bool hasTack() const {
    return std::any_of(tack_parts.begin(), tack_parts.end(), [](TackPart p) { return p != TackPart::None; });
  }
  // Labels the vertices from `first` to the last as `part`, the others keeping theirs (None where unlabelled).
  void labelTack(std::size_t first, TackPart part) {
    if (tack_parts.empty() && part == TackPart::None) return;
    tack_parts.resize(positions.size(), TackPart::None);
    std::fill(tack_parts.begin() + std::ptrdiff_t(std::min(first, positions.size())), tack_parts.end(), part);
  }
};

// Reorders the triangles so each base colour and texture (a triangle's colour is its first vertex's)
// forms one run, in the order they first appear, triangles in their order within a run. Vertices are
// untouched. A glTF writer then needs one primitive (one material) per run.
inline void groupTrianglesByColor(SkinnedMesh& mesh) {
  const std::size_t nt = mesh.triangleCount();
  std::vector<std::pair<glm::vec3, int>> palette;
  std::vector<int> group(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::pair<glm::vec3, int> c{mesh.colors[mesh.indices[t * 3]], mesh.triangleTexture(t)};
    auto it = std::find(palette.begin(), palette.end(), c);
    if (it == palette.end()) it = palette.insert(palette.end(), c);
    group[t] = static_cast<int>(it - palette.begin());
  }
  std::vector<std::size_t> order(nt);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return group[a] < group[b]; });
  std::vector<std::uint32_t> indices(mesh.indices.size());
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) indices[t * 3 + k] = mesh.indices[order[t] * 3 + k];
  mesh.indices = std::move(indices);
  if (!mesh.triangle_textures.empty()) {
    std::vector<std::int32_t> textures(nt);
    for (std::size_t t = 0; t < nt; ++t) textures[t] = mesh.triangle_textures[order[t]];
    mesh.triangle_textures = std::move(textures);
  }
}

}  // namespace stirrup::rig
