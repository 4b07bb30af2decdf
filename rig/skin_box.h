// The box of a skinned mesh at a pose without skinning every vertex: to the bit the min and max of
// skinPositions' positions (rig/skin.h), found by skinning only the vertices that can reach the box.
//
// Offline, once a mesh (SkinBoxIndex): the vertices are cut into small clusters of neighbours in the
// bind pose, each with its box, the joints its vertices hang from and the range of their
// weights' sums. At a pose (box): every cluster's skinned vertices lie within the bound of its box
// moved by each of its joints (a blend of joints is a weighted mean of their placements), grown by a
// slack that covers the float rounding of the skinning itself. The clusters whose bounds reach
// furthest along each axis are skinned first; every other cluster is skinned only when its bound
// reaches the box found so far. A cluster left out holds no vertex that could change the box, so the
// box is exactly the one every vertex gives (a view framed from it is the same to the bit:
// render/scene/shot_camera.h).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "rig/mesh.h"
#include "rig/skeleton.h"

namespace stirrup::rig {

struct SkinnedBox {
  glm::vec3 lo{0.0f}, hi{0.0f};
  std::size_t skinned = 0;  // vertices skinned to find it (of the mesh's vertexCount())
};

class SkinBoxIndex {
 public:
  // Clusters of the mesh's vertices (the mesh must outlive nothing: the index keeps what it needs).
  explicit SkinBoxIndex(const SkinnedMesh& mesh);

  // The box of `mesh` (the one the index was made from) posed by `jointWorld`: lo and hi are the
  // min and max over every vertex of skinPositions(mesh, skel, jointWorld, 1), to the bit. Throws
  // std::invalid_argument when jointWorld is not one per joint, std::logic_error when the mesh is not
  // the index's (another vertex count) or has no vertices.
  SkinnedBox box(const SkinnedMesh& mesh, const Skeleton& skel, std::span<const glm::mat4> jointWorld) const;

  std::size_t clusterCount() const { return clusters_.size(); }

 private:
  struct Cluster {
    glm::dvec3 centre{0.0}, half{0.0};   // its vertices' box in the bind pose: centre and half sizes
    double weight_sum_lo = 1.0, weight_sum_hi = 1.0;  // the range of the vertices' weight sums
    std::size_t first = 0, count = 0;    // its vertices: order_[first, first + count)
    std::size_t first_joint = 0, joint_count = 0;  // its joints: joints_[first_joint, ...)
  };
  std::size_t vertex_count_ = 0;
  std::vector<std::uint32_t> order_;  // vertex indices, cluster after cluster
  std::vector<std::uint16_t> joints_;
  std::vector<Cluster> clusters_;
};

}  // namespace stirrup::rig
