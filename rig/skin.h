// Linear blend skinning: each vertex moves by the weighted sum of its joints' skinning matrices
// (joint world * skinning bind, Skeleton::skinBind). Normals move by the same blend and are renormalised, which is exact
// for rigid joints and a close approximation where they blend.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "rig/mesh.h"
#include "rig/skeleton.h"

namespace stirrup::rig {

// Skinning matrices, one per joint: jointWorld[i] * inverse_bind[i] * bind_offset[i] (Skeleton::skinBind).
std::vector<glm::mat4> skinningMatrices(const Skeleton& skel, std::span<const glm::mat4> jointWorld);

// Deforms the mesh by the posed joints; positions and normals are resized to the vertex count.
// Parallel over vertices (TBB). Throws std::invalid_argument when jointWorld is not one per joint.
void skinMesh(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld,
              std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

// Vertex v skinned by the skinning matrices `m` (skinningMatrices: one per joint), the reference
// skinMesh keeps to the bit: the joints' matrices blended by the weights (weights <= 0 skipped), the
// position moved by the blend, the normal by the inverse transpose of its 3x3, renormalised (kept as it
// was where that leaves no length). skinMesh runs it a SIMD vector of vertices at a time.
void skinVertex(const SkinnedMesh& mesh, const glm::mat4* m, std::size_t v, glm::vec3& position, glm::vec3& normal);

// The positions alone of every `stride`-th vertex (0, stride, 2 stride, ...), to the bit as skinMesh
// places them: what framing a view from the characters' vertices needs (scene/view.h), without
// the normals' per-vertex inverse. `positions` is resized to ceil(vertices / stride). Throws
// std::invalid_argument when jointWorld is not one per joint or stride < 1.
void skinPositions(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld, int stride,
                   std::vector<glm::vec3>& positions);

}  // namespace stirrup::rig
