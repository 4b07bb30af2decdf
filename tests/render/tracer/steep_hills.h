// Hills under a sun, for the tests of the hills' horizon map (heightfield_mesh_test.cpp) and of the
// same test in the ground's SIMD lanes (sample_lanes_test.cpp): rolling hills under a high sun, and steep
// hills under a low one (5 m hills 15 m apart over a 30 m square, the sun 8 degrees up with a disc 2
// degrees across); each with its map and its heightfield in Embree to trace the sun's disc against.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "render/tracer/embree_scene.h"
#include "render/tracer/heightfield_mesh.h"
#include "rig/motion/terrain.h"

namespace stirrup::render::test {

// Rolling hills like a path scene's (issue 15): 80 cm high, 30 m apart, two octaves.
inline rig::Terrain rollingHillsTerrain() {
  rig::HillsParams p;
  p.seed = 3;
  p.amplitude_cm = 80.0;
  p.wavelength_cm = 3000.0;
  p.octaves = 2;
  return rig::Terrain::hills(p, "test");
}

inline rig::Terrain steepHillsTerrain() {
  rig::HillsParams p;
  p.seed = 7;
  p.amplitude_cm = 500.0;
  p.wavelength_cm = 1500.0;
  return rig::Terrain::hills(p, "test");
}

// Whether each ray of a sun's disc (`sun` toward it, `radius` its angular radius) from `origin` meets the
// heightfield in `ground`: its axis (ray 0), then 16 directions on its rim.
inline std::array<bool, 17> sunDiscBlocked(RTCScene ground, const glm::dvec3& sun, double radius, const glm::vec3& origin) {
  const glm::dvec3 axis = glm::normalize(sun);
  const glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(0.0, 1.0, 0.0)));
  const glm::dvec3 up = glm::cross(side, axis);
  std::array<bool, 17> blocked{};
  for (int r = 0; r <= 16; ++r) {
    glm::dvec3 d = axis;
    if (r > 0) {
      const double a = 2.0 * std::numbers::pi * double(r - 1) / 16.0;
      d = glm::normalize(axis * std::cos(radius) + (side * std::cos(a) + up * std::sin(a)) * std::sin(radius));
    }
    RTCRay ray{};
    ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
    ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
    ray.tfar = 1e7f;
    ray.mask = 0xffffffffu;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(ground, &context, &ray);
    blocked[std::size_t(r)] = ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
  }
  return blocked;
}

// The mesh's point straight under (x, z), found as a camera ray finds it: traced down through Embree from
// 20 m up (-infinity off the mesh).
inline glm::vec3 groundBelow(RTCScene ground, float x, float z) {
  RTCRayHit rh{};
  rh.ray.org_x = x, rh.ray.org_y = 2000.0f, rh.ray.org_z = z;
  rh.ray.dir_y = -1.0f, rh.ray.tfar = 1.0e7f, rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(ground, &context, &rh);
  const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  return {x, hit ? 2000.0f - rh.ray.tfar : -std::numeric_limits<float>::infinity(), z};
}

// A point (x, z) 300 m to 1 km from the origin in its larger coordinate, where a shadow ray's origin
// is lifted by 0.9 to 3 cm.
inline glm::vec2 farFromTheOrigin(std::mt19937& rng) {
  std::uniform_real_distribution<float> across(-100000.0f, 100000.0f);
  for (;;) {
    const glm::vec2 at(across(rng), across(rng));
    if (std::max(std::abs(at.x), std::abs(at.y)) >= 30000.0f) return at;
  }
}

// Hills under a sun with a disc 2 degrees across: the mesh over `region` (reaching a kilometre past it),
// the sun's horizon map, and the mesh in Embree to trace the disc against.
struct HillsUnderSun {
  static constexpr double kRadius = 2.0 * std::numbers::pi / 180.0;  // the sun disc's angular radius

  HillsUnderSun(rig::Terrain hills, const GroundRegion& over, const glm::dvec3& toward_sun)
      : terrain(std::move(hills)), region(over), mesh(makeTerrainMesh(terrain, region)), sun(toward_sun),
        horizon(mesh, sun, kRadius, region) {
    scene.setGroundMesh(mesh.positions, mesh.indices);
  }
  HillsUnderSun(const HillsUnderSun&) = delete;  // the map points at the mesh
  HillsUnderSun& operator=(const HillsUnderSun&) = delete;

  // Whether each ray of the sun's disc from `origin` meets the mesh: its axis (ray 0), then 16
  // directions on its rim.
  std::array<bool, 17> discBlocked(const glm::vec3& origin) const {
    return sunDiscBlocked(scene.ground(), sun, kRadius, origin);
  }

  rig::Terrain terrain;
  GroundRegion region;
  TerrainMesh mesh;
  glm::dvec3 sun;
  SunHorizon horizon;
  EmbreeScene scene;
};

// The path scenes' rolling hills under their sun, 48 degrees up (scenes/cavalry.json, ride_out.json):
// the sun rises faster than any hill, so the map is open everywhere; the mesh reaches a kilometre
// past the track, where a shadow ray's origin is lifted by centimetres.
struct HighSunHills : HillsUnderSun {
  HighSunHills() : HillsUnderSun(rollingHillsTerrain(), {-500.0, -800.0, 4000.0, 4500.0}, {0.45, 0.75, 0.5}) {}
};

// 5 m hills 15 m apart under a sun 8 degrees up.
struct SteepHills : HillsUnderSun {
  static constexpr double kElevation = 8.0 * std::numbers::pi / 180.0;  // the sun's height above the horizon

  SteepHills()
      : HillsUnderSun(steepHillsTerrain(), {-1500.0, -1500.0, 1500.0, 1500.0},
                      {std::cos(kElevation) * 0.8, std::sin(kElevation), std::cos(kElevation) * 0.6}) {}
};

}  // namespace stirrup::render::test
