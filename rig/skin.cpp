#include "rig/skin.h"

#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace stirrup::rig {

std::vector<glm::mat4> skinningMatrices(const Skeleton& skel, std::span<const glm::mat4> jointWorld) {
  if (jointWorld.size() != skel.size())
    throw std::invalid_argument("skinning: expected one world matrix per joint");
  std::vector<glm::mat4> m(skel.size());
  for (std::size_t i = 0; i < skel.size(); ++i) m[i] = jointWorld[i] * skel.skinBind(static_cast<int>(i));
  return m;
}

namespace {

// A vertex's blended skinning matrix: skinMesh and skinPositions share it, so they agree to the bit.
inline glm::mat4 blendAt(const SkinnedMesh& mesh, const std::vector<glm::mat4>& m, std::size_t v) {
  const glm::u16vec4 j = mesh.joints[v];
  const glm::vec4 w = mesh.weights[v];
  glm::mat4 blend(0.0f);
  for (int i = 0; i < kMaxInfluences; ++i)
    if (w[i] > 0.0f) blend += w[i] * m[j[i]];
  return blend;
}

}  // namespace

void skinMesh(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld,
              std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  const std::vector<glm::mat4> m = skinningMatrices(skel, jointWorld);
  const std::size_t n = mesh.positions.size();
  positions.resize(n);
  normals.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      const glm::mat4 blend = blendAt(mesh, m, v);
      positions[v] = glm::vec3(blend * glm::vec4(mesh.positions[v], 1.0f));
      // Inverse transpose of the blended 3x3 keeps normals perpendicular under non-rigid blends.
      const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(blend)));
      const glm::vec3 nrm = nm * mesh.normals[v];
      const float len = glm::length(nrm);
      normals[v] = len > 1e-12f ? nrm / len : mesh.normals[v];
    }
  });
}

void skinPositions(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld, int stride,
                   std::vector<glm::vec3>& positions) {
  if (stride < 1) throw std::invalid_argument("skinPositions: expected a stride of 1 or more");
  const std::vector<glm::mat4> m = skinningMatrices(skel, jointWorld);
  const std::size_t step = std::size_t(stride);
  const std::size_t n = (mesh.positions.size() + step - 1) / step;
  positions.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const std::size_t v = k * step;
      positions[k] = glm::vec3(blendAt(mesh, m, v) * glm::vec4(mesh.positions[v], 1.0f));
    }
  });
}

}  // namespace stirrup::rig
