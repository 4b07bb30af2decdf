// The renderer the shot drives: meshes are added once (topology and colours), their vertices and
// normals are updated every frame, and render() commits the BVH and traces the frame in 16 x 16 tiles
// on a TBB arena of RenderSettings::threads threads.
//
// Determinism: every pixel owns its samples (the reconstruction filter is importance-sampled, not
// splatted) and draws its random numbers from a hash of (pixel, frame, sample, dimension), so the same
// scene and frame give the same bytes at any thread count and tile order.
//
// Cost: `stirrup bench` measures it per quality preset (docs/performance.md). Per camera sample there is
// 1 camera ray plus up to light_samples + ao_samples occlusion rays; flat ground is intersected
// analytically (uneven ground, a heightfield mesh, through Embree) and rays that cannot reach the characters' box never call into Embree. The rest go to
// Embree as streams, a batch of a tile at a time (integrator.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/tracer/embree_scene.h"
#include "render/tracer/heightfield_mesh.h"
#include "render/tracer/image.h"
#include "render/tracer/lights.h"
#include "rig/motion/terrain.h"
#include "rig/texture.h"
#include "scene/camera.h"

namespace stirrup::render {

enum class ObjectId : uint32_t { Ground = 0, Horse = 1, Rider = 2 };

struct MeshDesc {
  ObjectId id = ObjectId::Horse;
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
  std::vector<glm::vec3> colors;  // linear base colour per vertex (empty: a neutral grey)
  size_t vertex_count = 0;
  // The mesh in its rest (bind) pose, vertex_count positions, or empty. With BvhUpdate::Refit the BVH
  // is built once over these and refitted every frame, so its topology never depends on which frames
  // were rendered before (see embree_scene.h).
  std::vector<glm::vec3> rest_positions{};
  // The mesh's geomID in Embree's scene, or -1 for the next free one. A mesh added while frames are
  // rendered (a crowd's level of detail, built when first needed) takes a fixed id, so the scene is the
  // same whichever frames were rendered before.
  int geometry_id = -1;
  // Base colour textures (rig::SkinnedMesh's): per-vertex uvs, per-triangle texture (-1: none) and the
  // textures; all empty for an untextured mesh. A textured triangle's colour is its interpolated vertex
  // colour times its texture at the interpolated uv.
  std::vector<glm::vec2> uvs{};
  std::vector<int32_t> triangle_textures{};
  std::vector<std::shared_ptr<const rig::Texture>> textures{};
};

struct RenderSettings {
  int width = 640, height = 360;
  // Camera samples per pixel: a jittered sqrt x sqrt grid when square, else Latin hypercube, warped
  // through a tent filter of radius 1 pixel (a 2-pixel footprint). Each sample weighs the same.
  int samples_per_pixel = 16;
  int light_samples = 4;  // sun shadow rays per camera sample (stratified over the pixel's samples)
  int ao_samples = 4;     // sky rays per camera sample (cosine-weighted, stratified likewise)
  int threads = 0;        // 0 = all cores

  glm::dvec3 sun_direction{0.45, 0.75, 0.5};  // toward the sun; normalised by the renderer
  double sun_angular_radius_deg = 2.0;         // the real sun is 0.27 deg; larger softens shadows
  glm::vec3 sun_color{1.0f, 0.96f, 0.88f};
  float sun_strength = 1.8f;  // radiance of a white matte surface facing the sun (linear units)
  SkyGradient sky;
  AerialPerspective haze;  // the ground fading into the horizon with distance

  // Ground: a 50 cm checker of two close colours (low contrast: it should read, not distract),
  // box-filtered by each sample's footprint so it never crawls.
  glm::vec3 ground_color_a{0.30f, 0.29f, 0.26f};
  glm::vec3 ground_color_b{0.34f, 0.33f, 0.295f};
  float ground_square_cm = 50.0f;
  float ground_half_extent_cm = 100000.0f;  // the ground quad spans +-1 km around the origin

  // Sky rays longer than this count as unoccluded: about a horse's height, so the belly darkens the
  // ground under it, without tracing (or waiting for) the whole scene for every sky ray.
  float ao_distance_cm = 300.0f;
  float specular = 0.04f;         // Blinn-Phong weight on the characters (the ground is matte)
  int shininess = 48;              // a whole power: the lobe is the same bits on every SIMD target

  BvhUpdate bvh_update = BvhUpdate::Refit;  // built over the rest poses (MeshDesc::rest_positions)
  // Open ground whose sun axis misses the characters' bounding box, or farther than ao_distance_cm from
  // it, takes the sun along its axis and the sky's exact mean, with no rays; the rest samples the sun's
  // disc and the sky with rays. Both are estimates of the same light, but not the same bits, so which
  // one a ground point gets depends on the one box around every character. With several pairs that
  // box couples them: one pair's pose would change the ground's pixels far from it. A crowd turns this
  // off and samples every ground point (rays that miss the box still never reach Embree).
  bool open_ground_shortcuts = true;
  bool passes = true;  // also fill Image::depth, matte, normal and object_id
};

// Timings of the last render() in milliseconds.
struct RenderStats {
  double commit_ms = 0;  // BVH rebuild or refit
  double trace_ms = 0;   // tracing and shading
  double wait_ms = 0;    // after the trace, waiting for render()'s `alongside` to finish
  size_t triangles = 0;  // of the meshes shown (a crowd's pairs at their levels of detail)
  uint64_t rays = 0;     // camera, shadow and sky rays of the frame (including those culled before Embree)
};

// The rays of one frame as Embree rays, kept by Renderer::render for Renderer::replay: what Embree
// alone would have to trace for the frame, with no shading, sampling or film work around it.
struct RayLog {
  int pixel_stride = 1;              // keep the rays of every Nth pixel (row-major index), to bound memory
  std::vector<RTCRay> camera;        // against the ground, then the characters up to the ground
  std::vector<RTCRay> occlusion;     // shadow and sky rays against the characters
  uint64_t rays = 0;                 // camera.size() + occlusion.size()
};

class Integrator;

class Renderer {
 public:
  // Throws std::invalid_argument for settings that cannot render (sizes or counts < 1, a zero sun).
  explicit Renderer(const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uneven ground (issue 15): the ground becomes `terrain`'s heightfield mesh, fine over `region` (the
  // horse's track; render/tracer/heightfield_mesh.h), in place of the flat plane. Build once per shot, before
  // rendering. Null or flat terrain keeps the analytic plane (and so the frames of before).
  void setTerrain(std::shared_ptr<const rig::Terrain> terrain, const GroundRegion& region,
                  const TerrainMeshParams& params = {});

  // Adds a mesh (once per mesh). Returns its handle for updateMesh.
  int addMesh(const MeshDesc& mesh);
  // New vertex positions and unit normals for a mesh, vertex_count of each (every frame).
  void updateMesh(int mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);
  // Shows or hides a mesh from the next frame on (a crowd's pair shows one of its levels of detail).
  void setMeshEnabled(int mesh, bool enabled);

  // Commits the changes since the last call and traces the frame. Deterministic for (scene, frame).
  // With `log`, also keeps the frame's rays in it (slower; for benchmarks only).
  // With `alongside`, also runs it as one more task on the renderer's threads once the BVH is
  // committed, while the frame traces, and returns when both are done (its exception is rethrown
  // here). The threads stay as many as RenderSettings::threads (frames overlapped: the shot evaluates
  // its next frame so, render/shot.h). It must not touch the renderer.
  Image render(const scene::Camera& camera, int frame, RayLog* log = nullptr, const std::function<void()>& alongside = {});

  // Casts the logged rays through Embree alone on the renderer's threads, in streams of 256
  // consecutive rays with rtcIntersect1M / rtcOccluded1M as the integrator does, and returns the wall-clock
  // seconds. The scene must be committed for the logged frame (call right after render()).
  double replay(const RayLog& log);

  // Whether the next frames also fill Image::depth, matte, normal and object_id (RenderSettings::passes):
  // EXR frames and a matte layer need them, a PNG's colour does not (they are a quarter of a frame's
  // memory traffic at one sample a pixel). The colour is the same either way.
  void setPasses(bool passes) { settings_.passes = passes; }
  const RenderSettings& settings() const { return settings_; }
  const RenderStats& lastStats() const { return stats_; }

 private:
  struct State;
  RenderSettings settings_;
  std::unique_ptr<State> state_;
  RenderStats stats_;
};

}  // namespace stirrup::render
