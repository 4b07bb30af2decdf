// Rolling hills, and steep hills under a low sun, for the tests of the hills' horizon map (heightfield_mesh_test.cpp) and of
// the same test in the ground's SIMD lanes (sample_lanes_test.cpp): 5 m hills 15 m apart over a 30 m
// square, the sun 8 degrees up with a disc 2 degrees across, the map, and the heightfield in Embree to
// trace the sun's disc against.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

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

struct SteepHills {
  static constexpr double kRadius = 2.0 * std::numbers::pi / 180.0;     // the sun disc's angular radius
  static constexpr double kElevation = 8.0 * std::numbers::pi / 180.0;  // the sun's height above the horizon

  SteepHills() { scene.setGroundMesh(mesh.positions, mesh.indices); }
  SteepHills(const SteepHills&) = delete;  // the map points at the mesh
  SteepHills& operator=(const SteepHills&) = delete;

  // Whether each ray of the sun's disc from `origin` meets the mesh: its axis (ray 0), then 16
  // directions on its rim.
  std::array<bool, 17> discBlocked(const glm::vec3& origin) const {
    const glm::dvec3 axis = glm::normalize(sun);
    const glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(0.0, 1.0, 0.0)));
    const glm::dvec3 up = glm::cross(side, axis);
    std::array<bool, 17> blocked{};
    for (int r = 0; r <= 16; ++r) {
      glm::dvec3 d = axis;
      if (r > 0) {
        const double a = 2.0 * std::numbers::pi * double(r - 1) / 16.0;
        d = glm::normalize(axis * std::cos(kRadius) + (side * std::cos(a) + up * std::sin(a)) * std::sin(kRadius));
      }
      RTCRay ray{};
      ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
      ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
      ray.tfar = 1e7f;
      ray.mask = 0xffffffffu;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      rtcOccluded1(scene.ground(), &context, &ray);
      blocked[std::size_t(r)] = ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
    }
    return blocked;
  }

  rig::Terrain terrain = steepHillsTerrain();
  GroundRegion region{-1500.0, -1500.0, 1500.0, 1500.0};
  TerrainMesh mesh = makeTerrainMesh(terrain, region);
  glm::dvec3 sun{std::cos(kElevation) * 0.8, std::sin(kElevation), std::cos(kElevation) * 0.6};
  SunHorizon horizon{mesh, sun, kRadius, region};
  EmbreeScene scene;
};

}  // namespace stirrup::render::test
