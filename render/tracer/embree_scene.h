// The Embree side of the renderer: one device and two scenes. The ground scene holds a static quad
// (or, for uneven ground, a static heightfield mesh that camera rays are traced against),
// committed once and never touched again. The character scene holds triangle meshes whose vertex
// buffers are overwritten in place every frame (rtcUpdateGeometryBuffer + rtcCommitGeometry, then
// one rtcCommitScene before tracing). Keeping the ground out of the character BVH means shadow and
// sky rays traverse only the characters (the flat ground never blocks them; on hills, only the sun
// rays the hills might block are also traced against the ground scene, see integrator.cpp), and the
// huge ground triangles never inflate the character BVH's nodes.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

namespace stirrup::render {

// How the acceleration structure follows deforming meshes. Refit over the rest pose is the renderer's
// default: on the trot it measured fastest per frame, BVH update and trace together, against a
// LOW-quality and a MEDIUM rebuild (README "Speed", BM_TrotFrameBvh).
enum class BvhUpdate {
  // One MEDIUM-quality (SAH) BVH over every triangle, rebuilt at each commit. Deterministic: the BVH
  // is a function of the current vertices only, never of earlier frames.
  Rebuild,
  // Two-level: each mesh has its own BVH, rebuilt (MEDIUM) only when that mesh changed.
  RebuildPerMesh,
  // Two-level, each changed mesh rebuilt with Embree's fast LOW-quality (Morton) builder: the cheap
  // rebuild, against which Refit is measured (tests/bench/render_bench.cpp, BM_TrotFrameBvh).
  RebuildPerMeshLow,
  // Two-level, and deforming meshes keep the topology of one build and only refit bounds each frame.
  // Cheapest commit; traversal slows as the pose moves away from the built one. A mesh given rest
  // positions is built once over those, so the tree (and so the order ties are broken in) is the
  // same whatever frames were rendered before, and refitting (a min/max per node) is exact: the
  // result is a pure function of the current vertices. Without rest positions the first committed
  // frame's vertices are used, which makes the tree depend on the frame history.
  Refit,
};

// A hit on the ground mesh (EmbreeScene::setGroundMesh) in the mesh's own terms: the triangle (its index
// among the mesh's triangles) and Embree's barycentrics for it, b1 for its second vertex, b2 its third.
struct GroundTriangleHit {
  uint32_t triangle;
  float b1, b2;
};
// A quad hit as its triangle (inline: every camera ray that meets the hills asks).
inline GroundTriangleHit groundTriangleHit(unsigned cell, float u, float v) {
  // The first triangle (v0 v1 v3) = (c d a) gives its own barycentrics: c 1-u-v, d u, a v. The second
  // (v2 v3 v1) = (b a d) gives u = 1-u', v = 1-v' for its a u', d v': so a 1-u, d 1-v, b u+v-1.
  if (u + v <= 1.0f) return {2 * cell, 1.0f - u - v, u};
  return {2 * cell + 1, 1.0f - v, u + v - 1.0f};
}

class EmbreeScene {
 public:
  // `threads`: how many threads Embree's BVH builds may use (0: every core).
  explicit EmbreeScene(BvhUpdate update = BvhUpdate::Rebuild, int threads = 0);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Sets the ground scene to a horizontal square at y = 0 centred on the origin, 2 * half_extent_cm
  // wide, and commits it.
  void setGround(float half_extent_cm);
  // Sets the ground scene to a heightfield's mesh instead (render/tracer/heightfield_mesh.h), built once
  // (MEDIUM, static) and committed: its triangles in pairs, each cell's (a c d), (a d b) meeting on the
  // diagonal a-d, traced as Embree quads (half the primitives: the BVH builds in about half the time).
  // A hit's primID is the cell and u, v the quad's; groundTriangleHit gives the triangle. Throws
  // std::invalid_argument on indices out of range or triangles not in such pairs.
  void setGroundMesh(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);
  // A character triangle mesh with fixed topology; its vertices start at the origin until
  // setVertices. Returns its geomID in the character scene.
  // Throws std::invalid_argument for a partial triangle or an index out of range.
  // `id` >= 0 attaches it with that geomID (which must be free), else with the next free one.
  unsigned addTriangleMesh(size_t vertex_count, std::span<const uint32_t> indices,
                           std::span<const glm::vec3> rest_positions = {}, int id = -1);
  // Overwrites the mesh's vertices in Embree's own buffer and marks the scene for commit.
  void setVertices(unsigned geom_id, std::span<const glm::vec3> positions);
  // Takes a mesh out of the scene (rays pass it) or puts it back, from the next commit; a crowd's pair
  // shows one of its levels of detail (scene/detail_level.h). Refit: a mesh put back is built over its
  // rest pose again before it is refitted to its vertices, so its tree is the same whatever frames were
  // rendered before.
  void setEnabled(unsigned geom_id, bool enabled);

  // Rebuilds or refits what changed since the last commit; no-op when nothing did. Call it from the
  // task arena the trace will run in, so the build uses the same threads.
  void commit();

  RTCScene characters() const { return scene_; }
  RTCScene ground() const { return ground_; }
  // Bounds of the characters at the last commit (empty, lower > upper, when there are none).
  const RTCBounds& characterBounds() const { return bounds_; }
  size_t triangleCount() const { return triangles_; }      // of every mesh, enabled or not
  size_t enabledTriangleCount() const;                     // of the meshes rays can hit

 private:
  struct Mesh {
    RTCGeometry geometry = nullptr;
    size_t vertex_count = 0;
    std::vector<glm::vec3> rest;  // Refit: the pose the tree is built over
    size_t triangle_count = 0;
    bool enabled = true;
    bool needs_rest_build = true;  // Refit: build over `rest` at the next commit (new or put back)
  };

  std::string last_error_;  // filled by Embree's error callback
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RTCScene ground_ = nullptr;
  RTCGeometry ground_quad_ = nullptr;
  RTCBounds bounds_{};
  BvhUpdate update_;
  std::vector<Mesh> meshes_;  // indexed by geomID
  size_t triangles_ = 0;
  bool dirty_ = true;
};

}  // namespace stirrup::render
