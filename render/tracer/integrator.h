// Shading for the review look: per camera sample, one primary ray, then direct sun through
// `light_samples` shadow rays into the sun's cone and sky light through `ao_samples` cosine-weighted
// occlusion rays. The lights are render/tracer/light.h's Sun and Sky; the characters' surfaces are
// render/tracer/material.h's Materials (diffuse plus a small normalised Blinn-Phong lobe, smooth-shaded
// from the vertex normals, coloured by the vertices or a texture); the ground is a filtered checker. No
// indirect bounces except a constant ground bounce seen by downward sky rays (so bellies are not black).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/tracer/embree_scene.h"
#include "render/tracer/heightfield_mesh.h"
#include "render/tracer/light.h"
#include "render/tracer/lights.h"
#include "render/tracer/material.h"
#include "render/tracer/renderer.h"
#include "render/tracer/sample_lanes.h"
#include "render/tracer/sampler.h"
#include "render/tracer/shading_lanes.h"
#include "rig/motion/terrain.h"
#include "rig/texture.h"
#include "scene/camera.h"

namespace stirrup::render {

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

// The reusable buffers of one thread's tiles. They grow to the largest batch on the first tile and are
// then reused, so tracing allocates nothing per pixel or per tile.
struct TileScratch {
  TileScratch();
  ~TileScratch();
  TileScratch(TileScratch&&) noexcept;
  TileScratch& operator=(TileScratch&&) noexcept;
  std::vector<uint32_t> pixel_x, pixel_y;  // the batch's pixels (padded for the lanes)
  StratifiedLanes pixel_parts;             // their sequences, with more than one sample a pixel
  std::vector<uint32_t> light_x, light_y;  // the pixels whose samples see surfaces (padded)
  StratifiedLanes sun_parts, sky_parts;    // their sun and sky sequences
  std::vector<int32_t> surface_light;      // per surface: its pixel's entry in light_x and the parts
  std::vector<uint32_t> surface_slot;      // per surface: its sample's index within its pixel
  std::vector<RTCRayHit> camera_rays;  // the samples that may hit the characters, traced as one stream
  std::vector<int32_t> ray_samples;    // each camera ray's sample
  // Uneven ground: what Embree's structure-of-arrays stream reads and writes beside the camera lanes
  // (which it reads in place): the rays' constant fields and the hits.
  struct GroundStream {
    void resize(std::size_t n);  // keeps the capacity
    std::vector<float> time, ng_x, ng_y, ng_z, u, v;
    std::vector<unsigned> mask, id, flags, prim, geom, inst;
  } ground;
  std::vector<RTCRay> sun_rays;        // traced as one stream (nearly parallel, but not as coherent: occlusionPass)
  std::vector<RTCRay> sky_rays;        // traced as one stream
  std::vector<int32_t> sun_list, sky_list;  // each traced ray's index in the surface lanes' per-ray arrays
  std::vector<RTCRay> hill_rays;       // uneven ground: the sun rays the hills may block, against the heightfield
  std::vector<int32_t> hill_list;      // each one's index among the sun rays of the surface lanes
  StratifiedLanes pixel_points;        // the samples' sequences, for their points in lanes
  StratifiedLanes sun_points, sky_points;  // the surfaces' sun and sky sequences
  CameraLanes lanes;                   // the batch's samples as arrays, for the SIMD kernels
  SurfaceLanes surfaces;               // the surfaces its samples see, for the shading kernels
  std::vector<int32_t> surface_samples;  // per surface: the sample that sees it (ascending)
  std::vector<ObjectId> surface_ids;     // per surface: what it is of, for the object id pass
};

class Integrator {
 public:
  // `meshes_by_geometry[geomID]` is the mesh of each geometry of the scene's character BVH. The
  // scene must be committed. With `terrain` (uneven ground) the scene's ground is its heightfield mesh:
  // camera rays are traced against it, the ground is shaded with the terrain's normal, and
  // `ground_floor` is its lowest height. Without, the ground is the plane y = 0, hit analytically.
  // The hills shadow the ground and the characters: wherever `hills` (this sun's horizon map of the
  // heightfield) cannot promise the sun is open, its shadow rays are also traced against the
  // heightfield. Sky rays meet only the characters. `ground_mesh` is that heightfield (the mesh in the
  // scene's ground): a camera ray is traced only where it crosses the slab between its lowest and
  // highest points, and a hit is shaded with its vertex normals; without it, with the terrain's normal.
  Integrator(const RenderSettings& settings, const EmbreeScene& scene,
             std::span<const ShadingMesh* const> meshes_by_geometry, const rig::Terrain* terrain = nullptr,
             float ground_floor = 0.0f, const SunHorizon* hills = nullptr, const TerrainMesh* ground_mesh = nullptr);

  // Every pixel of the tile [x0, x1) x [y0, y1), written row by row to `out` ((x1 - x0) * (y1 - y0)
  // results; only their rgba unless RenderSettings::passes is set). The tile is traced in batches of pixels as ray streams, in three passes: all camera
  // samples of the batch (one rtcIntersect1M), then all shadow and sky rays their shading needs (one
  // rtcOccluded1M each), then the sums. Each pixel's result depends on its own samples only, so it is
  // the same whatever tile or batch the pixel falls in.
  void renderTile(const scene::CameraFrame& camera, int x0, int x1, int y0, int y1, int frame, TileScratch& scratch,
                  RayTally& tally, PixelResult* out) const;

  // What the SIMD kernels read (render/tracer/sample_lanes.h, render/tracer/shading_lanes.h), for this frame's camera.
  LaneConstants laneConstants(const scene::CameraFrame& camera) const;

  // Whether any ray of the sun's cone from `origin` can meet the characters' box (false: the sun is
  // certainly unblocked there and needs no shadow rays).
  bool sunMayBeBlocked(const glm::vec3& origin) const;
  // The same answer for a point on or just above the ground, mostly from a rectangle worked out once
  // per frame.
  bool groundSunMayBeBlocked(const glm::vec3& origin) const;
  // True when the point is outside that rectangle (so the sun is certainly unblocked there).
  bool groundSunRegionExcludes(const glm::vec3& origin) const;

 private:
  // Traces the camera rays of pixels [first, first + count) of the tile and shades them into `out`.
  void renderBatch(const LaneConstants& constants, int x0, int tile_width, int y0, int first,
                   int count, int frame, TileScratch& scratch, RayTally& tally, PixelResult* out) const;
  // renderBatch's passes, in order (integrator.cpp says what each does); each reads what the ones before
  // left in the scratch.
  void cameraPass(const LaneConstants& constants, int x0, int tile_width, int y0, int first, int count, int frame,
                  TileScratch& scratch, RayTally& tally) const;
  void groundPass(TileScratch& scratch) const;
  void characterPass(TileScratch& scratch) const;
  void surfacePass(const LaneConstants& constants, int frame, TileScratch& scratch, RayTally& tally) const;
  // surfacePass's steps, in order: the ground and the sky in lanes, the other surfaces gathered into the
  // surface lanes (returns how many), and after the shading kernels, the shadow and sky rays queued.
  void groundAndSkyLanes(const LaneConstants& constants, TileScratch& scratch) const;
  std::size_t gatherSurfaces(int frame, TileScratch& scratch) const;
  void queueOcclusionRays(const LaneConstants& constants, TileScratch& scratch, RayTally& tally) const;
  void occlusionPass(const LaneConstants& constants, TileScratch& scratch) const;
  void resolvePass(int count, TileScratch& scratch, PixelResult* out) const;
  // A sample's surface into the surface lanes at m: a character's hit (rh) and its triangle's
  // vertices, or the ground's surface (the plane's from the lanes at sample j, or the terrain's).
  // Returns what it is of.
  ObjectId gatherSurface(const RTCRayHit* rh, const CameraLanes& lanes, std::size_t j, SurfaceLanes& surfaces,
                         std::size_t m) const;
  // The camera rays that may meet the characters' box, for their stream.
  void queueCharacterRays(TileScratch& scratch) const;
  // The shadow and sky rays the surface lanes made, into a RayLog's list in the order a surface makes them.
  void logOcclusionRays(const SurfaceLanes& surfaces, std::vector<RTCRay>& log) const;
  // Without the heightfield's mesh (tests that give the terrain alone): the terrain's own normal at
  // camera sample k's ground hit (its ray at the lanes' t_ground), into the lanes. With it,
  // groundHitLanes interpolates the mesh's vertex normals.
  void terrainNormal(CameraLanes& lanes, std::size_t k) const;
  // Whether the hills may block some ray of the sun's disc from a surface at p (true with terrain and no
  // horizon map). `on_ground`: p is a hit on the heightfield (so on or above it).
  bool hillsMayBlockSun(const glm::vec3& p, bool on_ground) const;
  // hillsMayBlockSun(p, false) for a point above the ground mesh's height there, `mesh_height` (the
  // horizon map is of that mesh: Renderer::setTerrain).
  bool hillsMayBlockSunAbove(const glm::vec3& p, double mesh_height) const;
  // How far along a camera ray the ground is seen before the haze ends it.
  float visibleDistance(const scene::CameraFrame& camera) const;

  const RenderSettings& settings_;
  RTCScene characters_;
  glm::vec3 bounds_lower_, bounds_upper_;  // of the characters: occlusion rays missing it skip Embree
  float bounds_radius_;                    // of the sphere around the bounds; < 0: no characters
  std::span<const ShadingMesh* const> meshes_;
  float ground_floor_;         // no ground point lies below this height
  // Derived once per frame.
  Sun sun_;
  Sky sky_;                    // its ground bounce: the radiance of the lit ground, seen by downward sky rays
  Brdf brdf_;                  // the characters' (the ground is matte)
  float ground_extent_;        // the ground is the square |x|, |z| <= this at y = 0, hit analytically
  const rig::Terrain* terrain_;  // or, when set, this terrain's mesh in ground_
  const SunHorizon* hills_;      // with terrain_: where the hills certainly leave the sun open (null: nowhere)
  const TerrainMesh* ground_mesh_;  // with terrain_: the heightfield as traced (null: unknown)
  float slab_low_, slab_high_;   // with terrain_: every ground point's height is within these
  RTCScene ground_;
  uint32_t spp_, light_spp_, ao_spp_;
  Stratified2D::Layout pixel_layout_, sun_layout_, sky_layout_;  // spp, spp * light, spp * ao points
};

}  // namespace stirrup::render
