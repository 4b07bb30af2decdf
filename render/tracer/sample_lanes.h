// The integrator's per-sample arithmetic over a whole batch at once, in SIMD lanes (Google Highway,
// with runtime dispatch to the best instruction set the CPU has: SSE4.2, AVX2 or AVX-512).
//
// A batch's camera samples are kept as structure-of-arrays (CameraLanes) and each kernel below runs
// over all of them, a vector at a time: camera rays from the stratified points (tent filter, film to
// ray), the analytic ground plane, the slab test against the characters' box, the ground's surface
// (filtered checker, aerial perspective, view depth) with the whole light of open ground, and the sky
// behind the samples that miss. The surfaces the samples see and the shadow and sky rays they need are
// the kernels of render/tracer/shading_lanes.h. The samples are sorted in lanes too: lists of the rays for
// Embree and of the samples that see a surface (CompressStore). What needs per-sample branching
// (gathering a hit triangle's vertices, writing the listed rays into Embree's, each pixel's sum) stays scalar.
//
// Determinism: every kernel uses only operations IEEE 754 rounds exactly (add, subtract, multiply,
// divide, square root, min, max, floor, compare, select), in the order the scalar expressions give, and
// the renderer is compiled with -ffp-contract=off, so no target fuses a multiply-add: the same frame
// gives the same bytes on every dispatch target (Renderer.SameBytesOnEveryDispatchTarget).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "render/tracer/heightfield_mesh.h"
#include "render/tracer/sampler.h"

namespace stirrup::render {

// The ground checker's contrast fades between these footprints, in squares (filteredChecker).
constexpr float kCheckerFadeStart = 0.25f, kCheckerFadeEnd = 1.0f;

// The batch's samples as arrays, each padded to a whole number of the widest vectors (16 floats), so
// the kernels need no scalar tail. Index i is the batch's i-th camera sample.
struct CameraLanes {
  static constexpr std::size_t kPad = 16;
  // n rounded up to a whole number of kPad: the length the kernels run over.
  static constexpr std::size_t paddedSize(std::size_t n) { return (n + kPad - 1) / kPad * kPad; }
  void resize(std::size_t n);  // keeps the capacity: a batch allocates nothing once the buffers grew
  std::size_t size = 0, padded = 0;
  // Inputs: the sample's stratified point in [0, 1)^2 and its pixel's centre (x + 0.5, y + 0.5).
  std::vector<float> ux, uy, cx, cy;
  // The camera ray, the ground's distance along it (infinity: none within the visible distance) and
  // whether it may meet the characters' box (all bits set) or certainly does not (0).
  std::vector<float> ox, oy, oz, dx, dy, dz, t_ground;
  std::vector<int32_t> may_hit;
  // Set by the caller after the characters' stream: the sample's index in it where its ray hit a
  // character, else -1.
  std::vector<int32_t> hit_ray;
  glm::vec3 origin(std::size_t k) const { return {ox[k], oy[k], oz[k]}; }
  glm::vec3 direction(std::size_t k) const { return {dx[k], dy[k], dz[k]}; }
  // Uneven ground: the part [t_enter, t_leave] of each camera ray within the heightfield's slab (and
  // the visible distance); t_enter > t_leave where there is none.
  std::vector<float> t_enter, t_leave;
  // Shading: `t_shade` is the ground's distance where the sample sees the ground (set by the caller:
  // t_ground unless a character is nearer, else infinity). The ground kernel fills its albedo, aerial
  // perspective and view depth, and for open ground (sun certainly unblocked, sky certainly open) its
  // whole radiance and open = all bits; the sky kernel fills the radiance of every sample as if it
  // missed (read only where it did).
  std::vector<float> t_shade;
  std::vector<float> albedo_r, albedo_g, albedo_b, haze, depth;
  std::vector<float> radiance_r, radiance_g, radiance_b;
  std::vector<int32_t> open;
  std::vector<float> sky_r, sky_g, sky_b;
  // Uneven ground, set by the caller where t_shade is finite before terrainGroundLanes: the ground's
  // normal at the hit (the heightfield's vertex normals interpolated; the kernel makes it unit in place).
  // The kernel sets whether the hills certainly leave the sun open there (all bits) or may not (0).
  std::vector<float> gnx, gny, gnz;
  std::vector<int32_t> hills_open;
};

// Points of Stratified2D sequences that share a Layout, as arrays: point k is point `index[k]` of the
// sequence whose pixel part (Stratified2D::pixelPart) is at k. Sized by the caller (resize), padded.
struct StratifiedLanes {
  void resize(std::size_t n);  // keeps the capacity; n a whole number of CameraLanes::kPad
  std::vector<uint64_t> pixel_hash;
  std::vector<uint32_t> index, seed, row_seed, offset, row_offset;
  void set(std::size_t k, const Stratified2D::PixelPart& part, uint32_t i) {
    pixel_hash[k] = part.pixel_hash, seed[k] = part.seed, row_seed[k] = part.row_seed, offset[k] = part.offset;
    row_offset[k] = part.row_offset, index[k] = i;
  }
  Stratified2D::PixelPart part(std::size_t k) const {
    return {pixel_hash[k], seed[k], row_seed[k], offset[k], row_offset[k]};
  }
};

// What the kernels read of the camera, the ground, the lights and the characters' box: plain numbers,
// set once per frame by the integrator.
struct LaneConstants {
  // Camera (CameraFrame::rayFromPixel).
  bool perspective = true;
  float pixel_dx = 0, pixel_dy = 0, half_width = 0, half_height = 0;
  glm::vec3 position{0.0f}, forward{0.0f}, right{0.0f}, up{0.0f};
  float footprint_at_0 = 0, footprint_per_cm = 0;
  float target_distance = 0;
  // Ground plane y = 0 within |x|, |z| <= extent, seen up to t_visible along a ray.
  float ground_extent = 0, t_visible = 0;
  // Uneven ground: every point of the heightfield lies between these heights.
  float slab_low = 0, slab_high = 0;
  // Uneven ground: where the hills certainly leave the sun open (SunHorizon::laneView; the default,
  // no map and not everywhere open: nowhere).
  SunHorizon::LaneView hills;
  float square_cm = 50.0f;
  glm::vec3 color_a{0.0f}, color_b{0.0f};
  float haze_visibility = 1.0f, haze_ortho_depth = 1.0f;
  glm::vec3 horizon{0.0f}, zenith{0.0f}, below{0.0f};
  float sky_floor = 0.0f;  // orthographic sky: the ground height it is graded from
  // Light on open ground: the sun's axis height (its cosine on the ground), its radiance, the sky's
  // irradiance / pi on an open upward surface.
  float sun_y = 0;
  glm::vec3 sun_radiance{0.0f}, sky_irradiance{0.0f};
  // Open ground: outside [sun_lower, sun_upper] in (x, z) the sun is unblocked (when sun_region), and
  // farther than ao_distance from the box the sky is open.
  bool sun_region = false;
  // RenderSettings::open_ground_shortcuts: false, every ground point samples the sun and the sky.
  bool open_ground_shortcuts = true;
  float ground_floor = 0;
  float sun_lower_x = 0, sun_lower_z = 0, sun_upper_x = 0, sun_upper_z = 0;
  float ao_distance = 0;
  // The characters' box (lower > upper: empty).
  glm::vec3 box_lower{0.0f}, box_upper{0.0f};
  bool box_empty = true;
  // Shading (render/tracer/shading_lanes.h): the sun's frame (its axis is the frame's z) and cone, the
  // characters' Blinn-Phong lobe, the lit ground's radiance seen by downward sky rays, and the shadow
  // and sky rays per camera sample.
  glm::vec3 sun_frame_x{0.0f}, sun_frame_y{0.0f}, sun_axis{0.0f, 1.0f, 0.0f};
  float sun_cos_max = 1.0f, sun_tan = 0.0f;
  float specular = 0.0f, blinn_norm = 1.0f;
  int shininess = 1;
  glm::vec3 ground_bounce{0.0f};
  int light_samples = 1, ao_samples = 1;
};

// Camera rays of samples [0, size): ox..dz. With `flat_ground` also the plane's t_ground and the box
// test against it; otherwise t_ground = infinity, [t_enter, t_leave] the ray's part within the
// heightfield's slab, and the caller traces the terrain, then runs boxTestLanes.
void cameraRayLanes(const LaneConstants& k, CameraLanes& lanes, bool flat_ground);
// may_hit: whether each camera ray may meet the characters' box before its t_ground.
void boxTestLanes(const LaneConstants& k, CameraLanes& lanes);
// The samples [0, size) whose ray may meet the characters' box, ascending, into `out` (room for
// `padded` entries); returns how many.
std::size_t listMayHit(const CameraLanes& lanes, int32_t* out);
// The samples [0, size) that see a surface to gather (a character, or ground that is not open: the
// lanes hold the light of open ground and of the sky), ascending, into `out` (room for `padded`);
// returns how many. Reads open, hit_ray and t_ground.
std::size_t listSurfaceSamples(const CameraLanes& lanes, int32_t* out);
// What Embree wrote for the camera rays against the heightfield (EmbreeScene::setGroundMesh's quads),
// one entry per sample, padded as the lanes are (a padding entry's geom invalid), and the grid the cells
// are numbered in (TerrainMesh: cells and vertices row by row along X, one normal a vertex).
struct GroundHits {
  const unsigned *geom = nullptr, *prim = nullptr;  // geomID (RTC_INVALID_GEOMETRY_ID: a miss) and the cell
  const float *u = nullptr, *v = nullptr;           // the quad's barycentrics
  // The mesh's grid (TerrainMesh): vertices a row (xs.size(), at least 2; fewer than 2^24 cells) and
  // the vertex normals, row by row.
  std::size_t row_vertices = 2;
  const glm::vec3* normals = nullptr;
};
// t_ground (t_leave where the ray hit, else infinity) and, where it hit, gnx..gnz: the hit triangle's
// vertex normals weighted by its barycentrics (groundTriangleHit), not yet unit.
void groundHitLanes(const GroundHits& hits, CameraLanes& lanes);
// The flat ground's surface and, where it is open, its radiance, for samples with a finite t_shade.
void groundLanes(const LaneConstants& k, CameraLanes& lanes);
// The same over uneven ground: the point along the ray (not snapped to a plane), shaded with the
// normal in gnx..gnz. Open ground there also needs the hills to leave the sun open (the horizon map's
// test, kept in hills_open) and the normal to face up (the shading's shortcut for the sky holds for
// upward ground only).
void terrainGroundLanes(const LaneConstants& k, CameraLanes& lanes);
// The background radiance of every sample (the sky gradient, or the orthographic sky).
void skyLanes(const LaneConstants& k, CameraLanes& lanes);

// Points [first, first + n) of `points` (n a whole number of CameraLanes::kPad) into u and v (indexed
// as the points): Stratified2D::operator[] bit for bit. The sequence hashing is integer arithmetic
// (32-bit products in the permutation, 64-bit products built from 32-bit ones in the hash), so every
// target gives the same points.
void stratifiedLanes(const Stratified2D::Layout& layout, const StratifiedLanes& points, std::size_t first,
                     std::size_t n, float* u, float* v);

// The sequences of `n` pixels for one dimension, set up in lanes: entry p of `parts` becomes
// Stratified2D(PixelSampler(x[p], y[p], frame), layout, dim).pixelPart() bit for bit, with index 0
// (the hashes are 64-bit integer arithmetic, so every target agrees). n is a whole number of
// CameraLanes::kPad (x and y hold n entries, padding included; `parts` is resized to at least n).
// Throws std::invalid_argument otherwise. Setting a pixel's sequences up one by one was a visible part
// of a draft frame: two to four hash rounds a pixel, each a chain of multiplies.
void pixelPartLanes(const Stratified2D::Layout& layout, SampleDimension dim, uint32_t frame, const uint32_t* x,
                    const uint32_t* y, std::size_t n, StratifiedLanes& parts);

// The filtered checker of integrator.h in lanes, for n points (the test compares the two).
void filteredCheckerLanes(const float* s, const float* t, const float* width, float* out, std::size_t n);

// The instruction set the kernels dispatch to ("AVX3" is AVX-512, as Highway names it).
std::string simdTargetName();
// Names of the targets this build has kernels for and this CPU runs, best first.
std::vector<std::string> simdTargets();
// Dispatch to the named target from now on ("" or "best": the CPU's best again). Throws
// std::invalid_argument naming the targets when the name is not one of simdTargets().
void pinSimdTarget(const std::string& name);

}  // namespace stirrup::render
