// The renderer the shot drives: meshes are added once (topology and colours), their vertices and
// normals are updated every frame, and render() commits the BVH and traces the frame in 16 x 16 tiles
// on a TBB arena of RenderSettings::threads threads.
//
// Determinism: every pixel owns its samples (the reconstruction filter is importance-sampled, not
// splatted) and draws its random numbers from a hash of (pixel, frame, sample, dimension), so the same
// scene and frame give the same bytes at any thread count and tile order.
//
// Cost (tests/render/renderer_benchmark_test.cpp, 98k-triangle deforming stand-in, 640 x 360, on a
// 2-core VM shared with other builds, which gave this process about 0.4 of a core, so CPU time is the
// comparable figure): review quality (16 spp, 4 sun, 4 sky) 2.7-3.0 s CPU per frame; 16 spp with 1 sun
// and 1 sky ray 1.3-1.7 s. Per camera sample that is 1 primary ray plus up to light_samples +
// ao_samples occlusion rays; rays that cannot reach the characters (open ground) are not traced.
// BVH update, same benchmark: full MEDIUM rebuild ~100-380 ms commit (wall, contended), refit about
// 3.5x cheaper to commit with no measurable trace slowdown for this motion; Rebuild stays the default
// because only it makes the BVH, and so tie-breaking, a function of the current frame alone.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "render/camera.h"
#include "render/embree_scene.h"
#include "render/image.h"
#include "render/lights.h"

namespace stirrup::render {

enum class ObjectId : uint32_t { Ground = 0, Horse = 1, Rider = 2 };

struct MeshDesc {
  ObjectId id = ObjectId::Horse;
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
  std::vector<glm::vec3> colors;  // linear base colour per vertex (empty: a neutral grey)
  size_t vertex_count = 0;
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
  float shininess = 48.0f;

  BvhUpdate bvh_update = BvhUpdate::Rebuild;
  bool passes = true;  // also fill Image::depth, matte and object_id
};

// Timings of the last render() in milliseconds.
struct RenderStats {
  double commit_ms = 0;  // BVH rebuild or refit
  double trace_ms = 0;   // tracing and shading
  size_t triangles = 0;
};

class Integrator;

class Renderer {
 public:
  // Throws std::invalid_argument for settings that cannot render (sizes or counts < 1, a zero sun).
  explicit Renderer(const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Adds a mesh (once per mesh). Returns its handle for updateMesh.
  int addMesh(const MeshDesc& mesh);
  // New vertex positions and unit normals for a mesh, vertex_count of each (every frame).
  void updateMesh(int mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);

  // Commits the changes since the last call and traces the frame. Deterministic for (scene, frame).
  Image render(const Camera& camera, int frame);

  const RenderSettings& settings() const { return settings_; }
  const RenderStats& lastStats() const { return stats_; }

 private:
  struct State;
  RenderSettings settings_;
  std::unique_ptr<State> state_;
  RenderStats stats_;
};

}  // namespace stirrup::render
