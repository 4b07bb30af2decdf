// The surfaces a batch's camera samples see and the light they gather, in SIMD lanes (Google
// Highway, as render/tracer/sample_lanes.h): the characters' hit surface (smooth normal, colour), then for
// every surface the origin of its secondary rays, the BRDF (diffuse plus a normalised Blinn-Phong
// lobe), the sun's shadow rays over its disc and the sky rays (cosine-weighted), with the light that
// needs no ray where the sun or the sky is certainly open.
//
// The integrator gathers each surface into SurfaceLanes (a hit triangle's vertices, or the ground's
// surface from the ground kernels), runs hitSurfaceLanes then shadingLanes, and queues the valid rays
// in sample order. Sines, cosines and the lobe's power are polynomials and products in a fixed order
// (render/tracer/lights.h: sinCosQuarterPi, unitCircle, powWhole), so every target gives the same bits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/tracer/sample_lanes.h"

namespace stirrup::render {

// A batch's surfaces as arrays (index i: the batch's i-th surface, in sample order). Per-ray arrays
// hold slot k of surface i at k * stride + i.
struct SurfaceLanes {
  // Room for n surfaces with these many sun and sky rays each; keeps the capacity (and the stride of a
  // larger batch before, with as many rays a surface).
  void reserve(std::size_t n, int light_samples, int ao_samples);
  // The surfaces filled are [0, n): the kernels run over n rounded up to whole vectors.
  void setSize(std::size_t n);
  std::size_t size = 0, padded = 0, stride = 0;
  int reserved_light_samples = -1, reserved_ao_samples = -1;  // the rays a surface the arrays are sized for

  // Inputs of hitSurfaceLanes, where `character` is set (all bits): the camera ray and the hit's
  // distance, Embree's geometric normal (any length, any side), the barycentrics (u, v), the
  // triangle's vertex normals and colours, and its texture's colour at the hit.
  std::vector<int32_t> character;
  std::vector<float> ox, oy, oz, dx, dy, dz, t;
  std::vector<float> gx, gy, gz, u, v;
  std::vector<float> n0x, n0y, n0z, n1x, n1y, n1z, n2x, n2y, n2z;
  std::vector<float> c0r, c0g, c0b, c1r, c1g, c1b, c2r, c2g, c2b;
  // The triangle's texture at the hit (1 where it has none): the interpolated colour is scaled by it.
  std::vector<float> tr, tg, tb;
  // The surface: point, geometric normal facing the camera, shading normal on its side, albedo,
  // specular weight, view depth; filled by the caller for the ground (with the ray's direction),
  // by hitSurfaceLanes for the characters. `ground_y` is the ground's height under the point (0 on
  // the plane): a character's downward sky rays stop just above it.
  std::vector<float> px, py, pz, ngx, ngy, ngz, nx, ny, nz, ar, ag, ab, specular, depth, ground_y;
  std::vector<int32_t> on_ground;
  // Uneven ground: all bits where the hills may block the sun (render/tracer/heightfield_mesh.h, SunHorizon): the
  // sun is then sampled with shadow rays, which the integrator also traces against the heightfield.
  std::vector<int32_t> hills;
  // The stratified points of each surface's sun rays and sky rays (per-ray arrays).
  std::vector<float> sun_u, sun_v, sky_u, sky_v;

  // Outputs of shadingLanes. Per surface: the secondary rays' origin; the diffuse albedo (it scales
  // the sky rays' sum); whether the sun needs rays, and if not its reflected light; whether the sky
  // needs rays, and if not its reflected light.
  std::vector<float> rox, roy, roz, diffuse_r, diffuse_g, diffuse_b;
  std::vector<int32_t> sun_traced, sky_traced;
  std::vector<float> sun_r, sun_g, sun_b, sky_r, sky_g, sky_b;
  // Per sun ray: its direction, BRDF times cosine, and whether it carries light (else no ray).
  std::vector<float> sun_wx, sun_wy, sun_wz, sun_fr, sun_fg, sun_fb;
  std::vector<int32_t> sun_valid;
  // Per sky ray: its direction and far end, the radiance it brings when open (the sky's, or the lit
  // ground's for a character's downward ray), and whether it is above the surface (else no ray).
  std::vector<float> sky_wx, sky_wy, sky_wz, sky_t_far, sky_lr, sky_lg, sky_lb;
  std::vector<int32_t> sky_valid;

  // Per surface, filled by the caller: the aerial perspective over its light (1: none).
  std::vector<float> haze;
  // Per sun ray and per sky ray, set by occluderLanes: all bits where the ray brings its light unless
  // something blocks it (it is valid and its surface traces that light); the caller then clears the
  // rays Embree found blocked.
  std::vector<int32_t> sun_open, sky_open;
  // Output of surfaceRadianceLanes: each surface's light, hazed.
  std::vector<float> radiance_r, radiance_g, radiance_b;
};

// The characters' surfaces (where `character` is set) from their hits; the others are left as filled.
void hitSurfaceLanes(const LaneConstants& k, SurfaceLanes& surfaces);
// The secondary rays and the light that needs none, for every surface.
void shadingLanes(const LaneConstants& k, SurfaceLanes& surfaces);

// What occluderLanes found among the shadow and sky rays of surfaces [0, size).
struct OccluderCounts {
  std::size_t sun = 0, sky = 0;  // rays that may meet the characters, listed
  std::size_t made = 0;          // rays made: valid, of a surface that traces that light, with a far end past 0
};
// Sets sun_open and sky_open, and lists the rays that may meet the characters' box before their far end
// (the others are open without a call into Embree) by their index in the per-ray arrays, ascending:
// `sun_list` and `sky_list` need room for every ray of their kind plus one vector (CameraLanes::kPad).
OccluderCounts occluderLanes(const LaneConstants& k, SurfaceLanes& surfaces, int32_t* sun_list, int32_t* sky_list);
// Each surface's light from its open rays (or the light that needed none), hazed: what the integrator
// summed surface by surface, in the same order of operations.
void surfaceRadianceLanes(const LaneConstants& k, SurfaceLanes& surfaces);

}  // namespace stirrup::render
