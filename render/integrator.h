// Shading for the review look: per camera sample, one primary ray, then direct sun through
// `light_samples` shadow rays into the sun's cone and sky light through `ao_samples` cosine-weighted
// occlusion rays. Surfaces are diffuse plus a small normalised Blinn-Phong lobe, smooth-shaded from the
// vertex normals; the ground is a filtered checker. No indirect bounces except a constant ground
// bounce seen by downward sky rays (so bellies are not black).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/camera.h"
#include "render/embree_scene.h"
#include "render/lights.h"
#include "render/renderer.h"
#include "render/sampler.h"

namespace stirrup::render {

// What the integrator needs of a mesh: its id for the passes, and the per-vertex data Embree does
// not keep (Embree has the positions and the triangles).
struct ShadingMesh {
  ObjectId id = ObjectId::Horse;
  std::vector<uint32_t> indices;
  std::vector<glm::vec3> colors;
  std::vector<glm::vec3> normals;
};

// One pixel's result: filtered colour and coverage, and the passes.
struct PixelResult {
  glm::vec4 rgba{0.0f};
  float depth = 0.0f;
  float matte = 0.0f;
  glm::vec3 normal{0.0f};  // mean world-space shading normal of the samples that hit (0 over sky)
  uint32_t object_id = 0;
};

// Counts the rays a pixel casts and, when the vectors are set, keeps them as Embree rays for
// replaying through Embree alone (stirrup bench's bound). One per tile: no sharing between threads.
struct RayTally {
  uint64_t rays = 0;                        // camera rays + shadow and sky rays
  std::vector<RTCRay>* camera = nullptr;    // camera rays as cast, tfar = infinity
  std::vector<RTCRay>* occlusion = nullptr; // shadow and sky rays as cast
};

// Fraction of the area within a box of `width` (in squares) around (s, t) (in squares) that falls on
// the odd squares of a checker: 0 or 1 when sharp, tending to 0.5 as the box grows (pbrt's closed-form
// box-filtered checkerboard).
float filteredChecker(float s, float t, float width);

class Integrator {
 public:
  // `meshes_by_geometry[geomID]` is the mesh of each geometry of the scene's character BVH. The
  // scene must be committed.
  Integrator(const RenderSettings& settings, const EmbreeScene& scene,
             std::span<const ShadingMesh* const> meshes_by_geometry);

  // All samples of pixel (x, y). Allocates nothing.
  PixelResult renderPixel(const CameraFrame& camera, int x, int y, int frame, RayTally& tally) const;

 private:
  struct Surface;
  struct Sample {
    glm::vec3 radiance{0.0f};
    bool hit = false;
    ObjectId id = ObjectId::Ground;
    float depth = 0.0f;
    glm::vec3 normal{0.0f};
  };
  // The stratified points of one pixel, set up once per pixel.
  struct PixelPoints {
    const Stratified2D& sun;
    const Stratified2D& sky;
  };
  Sample traceCameraSample(const CameraFrame& camera, float px, float py, uint32_t sample,
                           const PixelPoints& points, RayTally& tally) const;
  glm::vec3 shade(const Surface& s, uint32_t sample, const PixelPoints& points, RayTally& tally) const;
  bool mayHitCharacters(const glm::vec3& origin, const glm::vec3& direction, float t_far) const;
  // Occlusion of up to 4 rays from one origin: a bit per ray, set when blocked. Rays with t_far <= 0
  // or that miss the characters' bounds are not traced and count as open. Single rtcOccluded1 rays:
  // 4-wide rtcOccluded4 packets of the same rays measured no faster (2.99 vs 2.95 s CPU per
  // review-quality frame of the 100k-triangle stand-in).
  unsigned occluded4(const glm::vec3& origin, const glm::vec3* directions, const float* t_far, int count,
                     RayTally& tally) const;
  bool sunMayBeBlocked(const glm::vec3& origin) const;
  float distanceToCharacters(const glm::vec3& p) const;

  const RenderSettings& settings_;
  RTCScene characters_, ground_;
  glm::vec3 bounds_lower_, bounds_upper_;  // of the characters: occlusion rays missing it skip Embree
  glm::vec3 bounds_centre_;
  float bounds_radius_;                    // of the sphere around the bounds; < 0: no characters
  std::span<const ShadingMesh* const> meshes_;
  // Derived once per frame.
  Frame sun_frame_;
  float sun_cos_max_, sun_angle_, sun_tan_;
  glm::vec3 sun_radiance_;     // of a white matte surface facing the sun
  glm::vec3 ground_bounce_;    // radiance of the lit ground, seen by downward sky rays
  float ground_extent_;        // the ground is the square |x|, |z| <= this at y = 0, hit analytically
  float blinn_norm_;           // (n + 8) / 8: Blinn-Phong lobe normalised for energy
  uint32_t spp_, light_spp_, ao_spp_;
};

}  // namespace stirrup::render
