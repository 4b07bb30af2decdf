#include "render/tracer/heightfield_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include "render/tracer/embree_scene.h"
#include "tests/render/tracer/steep_hills.h"

namespace stirrup::render {
namespace {

// Rolling hills like a path scene's: 80 cm high, 30 m apart, two octaves.
rig::Terrain hills() { return test::rollingHillsTerrain(); }

constexpr double kFineSpacingCm = 25.0;   // the brief: hooves visibly on the ground
constexpr double kOnSurfaceCm = 0.5;      // how close the mesh must be to Terrain::height near the track
const GroundRegion kTrack{-500.0, -800.0, 4000.0, 4500.0};

TEST(TerrainGridLines, FineOverTheRegionThenGrowingOut) {
  const TerrainMeshParams params;
  const std::vector<double> lines = terrainGridLines(kTrack.x0, kTrack.x1, kFineSpacingCm, params);
  ASSERT_TRUE(std::is_sorted(lines.begin(), lines.end()));
  EXPECT_LE(lines.front(), kTrack.x0 - params.extent_cm);
  EXPECT_GE(lines.back(), kTrack.x1 + params.extent_cm);
  double previous_cell = 0.0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const double cell = lines[i] - lines[i - 1];
    EXPECT_GT(cell, 0.0);
    // Inside the region (and the one cell reaching its edge): the fine spacing.
    if (lines[i - 1] >= kTrack.x0 - kFineSpacingCm && lines[i] <= kTrack.x1 + kFineSpacingCm) {
      EXPECT_LE(cell, kFineSpacingCm + 1e-9) << "at x " << lines[i];
    }
    // Outward, no cell more than `growth` times its inner neighbour (the last one may be cut short).
    if (lines[i - 1] >= kTrack.x1 && previous_cell > 0.0 && i + 1 < lines.size()) {
      EXPECT_LE(cell, previous_cell * params.growth + 1e-6) << "at x " << lines[i];
    }
    previous_cell = cell;
  }
  // Far fewer lines than a fine grid over the whole extent.
  EXPECT_LT(lines.size(), std::size_t((kTrack.x1 - kTrack.x0) / kFineSpacingCm) + 300);
}

// Straight down onto the mesh through Embree: near the track the hit is within half a centimetre of the
// analytic height, far out the ground is still there (no holes, no cracks between fine and coarse).
TEST(TerrainMesh, RaysHitItOnTheTerrain) {
  const rig::Terrain terrain = hills();
  const TerrainMesh mesh = makeTerrainMesh(terrain, kTrack);
  EmbreeScene scene;
  scene.setGroundMesh(mesh.positions, mesh.indices);
  auto downAt = [&](double x, double z, float& y) {
    RTCRayHit rh{};
    rh.ray.org_x = float(x), rh.ray.org_y = 1000.0f, rh.ray.org_z = float(z);
    rh.ray.dir_x = 0.0f, rh.ray.dir_y = -1.0f, rh.ray.dir_z = 0.0f;
    rh.ray.tnear = 0.0f, rh.ray.tfar = 1e30f, rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(scene.ground(), &context, &rh);
    y = 1000.0f - rh.ray.tfar;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  };
  int checked = 0;
  double hilly = 0.0;
  // A lattice of points off the grid lines (odd fractions of the spacing) over the track.
  for (double x = kTrack.x0 + 7.3; x < kTrack.x1; x += 317.9) {
    for (double z = kTrack.z0 + 11.1; z < kTrack.z1; z += 291.7) {
      float y = 0.0f;
      ASSERT_TRUE(downAt(x, z, y)) << x << ", " << z;
      EXPECT_NEAR(y, terrain.height(x, z), kOnSurfaceCm) << x << ", " << z;
      hilly = std::max(hilly, std::abs(terrain.height(x, z)));
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(hilly, 30.0);  // the points do sample hills, not ground near 0
  // Far away: coarse, but the ground is there, and within the hills' amplitude.
  for (double d : {3000.0, 20000.0, 60000.0, 95000.0}) {
    for (const auto& [x, z] : {std::pair{kTrack.x1 + d, 1234.5}, std::pair{-d, kTrack.z0 - d}, std::pair{1500.5, kTrack.z1 + d}}) {
      float y = 0.0f;
      ASSERT_TRUE(downAt(x, z, y)) << "a hole at " << x << ", " << z;
      EXPECT_LE(std::abs(y), 80.0f + 1e-3f) << x << ", " << z;
    }
  }
}

// A region far beyond the fine vertex budget gets a wider spacing instead of running out of memory.
TEST(TerrainMesh, StaysWithinItsVertexBudget) {
  TerrainMeshParams params;
  params.max_fine_vertices = 10000.0;
  const TerrainMesh mesh = makeTerrainMesh(hills(), {0.0, 0.0, 20000.0, 20000.0}, params);
  // The budget, plus the growing border's lines on each side (a few hundred per axis at most).
  EXPECT_LT(mesh.positions.size(), std::size_t((100.0 + 200.0) * (100.0 + 200.0)));
  EXPECT_EQ(mesh.indices.size() % 3, 0u);
}

// A grid of 2^24 cells or more is refused before anything is allocated, with a message that says why:
// the renderer finds a hit cell's row in floats (groundHitLanes), exact only below that.
TEST(TerrainMesh, RefusesAGridTooLargeToNumberItsCells) {
  TerrainMeshParams params;
  params.max_fine_vertices = 1.0e12;
  params.fine_spacing_cm = 1.0;
  try {
    (void)makeTerrainMesh(hills(), {0.0, 0.0, 5000.0, 5000.0}, params);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fewer than 2^24"), std::string::npos) << e.what();
  }
  params.fine_spacing_cm = 10.0;  // 500 x 500 fine cells and the border: well under
  EXPECT_NO_THROW((void)makeTerrainMesh(hills(), {0.0, 0.0, 5000.0, 5000.0}, params));
}


// The constant-time cell lookup is the binary search it replaces, on the lines themselves, between them,
// at both ends, and over grid lines that grow cell by cell as the terrain's do.
TEST(TerrainMesh, GridLineIndexIsTheBinarySearch) {
  TerrainMeshParams params;
  const std::vector<std::vector<double>> cases = {
      terrainGridLines(-1234.5, 5678.25, 25.0, params),
      terrainGridLines(0.0, 0.0, 25.0, params),
      {-3.0, -1.0, 0.5, 0.75, 4.0},
      {0.0, 1.0},
  };
  uint32_t state = 9u;
  auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) * 0x1p-24;
  };
  for (const std::vector<double>& lines : cases) {
    const GridLineIndex index(lines);
    auto expected = [&](double v) {
      const std::size_t i = std::size_t(std::upper_bound(lines.begin(), lines.end(), v) - lines.begin());
      return std::min(i == 0 ? 0 : i - 1, lines.size() - 2);
    };
    std::vector<double> probes(lines.begin(), lines.end());
    for (double line : lines) probes.push_back(std::nextafter(line, -1e300)), probes.push_back(std::nextafter(line, 1e300));
    for (int k = 0; k < 20000; ++k) probes.push_back(lines.front() + (lines.back() - lines.front()) * uniform());
    for (double v : probes) {
      if (v < lines.front() || v > lines.back()) continue;
      ASSERT_EQ(index.cell(lines, v), expected(v)) << v << " over " << lines.size() << " lines";
    }
  }
}

// The vertex normals the renderer shades with are the terrain's own at each vertex.
TEST(TerrainMesh, VertexNormalsAreTheTerrains) {
  const rig::Terrain terrain = hills();
  const TerrainMesh mesh = makeTerrainMesh(terrain, kTrack);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (std::size_t k = 0; k < mesh.positions.size(); k += 211) {
    const glm::vec3& v = mesh.positions[k];
    const glm::dvec3 n = terrain.normal(v.x, v.z);
    EXPECT_NEAR(mesh.normals[k].x, n.x, 1e-5);
    EXPECT_NEAR(mesh.normals[k].y, n.y, 1e-5);
    EXPECT_NEAR(mesh.normals[k].z, n.z, 1e-5);
  }
}

// The mesh's own height is what a ray tracing it meets: at the vertices the terrain's, between them
// the triangle's plane, which a ray straight down through Embree finds to float precision.
TEST(TerrainMesh, HeightAtIsTheTracedMesh) {
  const rig::Terrain terrain = hills();
  const TerrainMesh mesh = makeTerrainMesh(terrain, kTrack);
  for (std::size_t k = 0; k < mesh.positions.size(); k += 997) {
    const glm::vec3& v = mesh.positions[k];
    EXPECT_NEAR(mesh.heightAt(v.x, v.z), v.y, 1e-3);  // (x, z) rounded to floats: off the line by an ulp
  }
  EmbreeScene scene;
  scene.setGroundMesh(mesh.positions, mesh.indices);
  uint32_t state = 5u;
  auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) * 0x1p-24;
  };
  for (int i = 0; i < 2000; ++i) {
    // Over the coarse ground too, where the mesh is far from Terrain::height.
    const double x = -20000.0 + 44000.0 * uniform(), z = -20000.0 + 44000.0 * uniform();
    RTCRayHit rh{};
    rh.ray.org_x = float(x), rh.ray.org_y = 1000.0f, rh.ray.org_z = float(z);
    rh.ray.dir_y = -1.0f;
    rh.ray.tfar = 1e6f;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(scene.ground(), &context, &rh);
    ASSERT_NE(rh.hit.geomID, RTC_INVALID_GEOMETRY_ID);
    EXPECT_NEAR(1000.0 - double(rh.ray.tfar), mesh.heightAt(double(float(x)), double(float(z))), 0.01) << x << " " << z;
  }
}

// A sun higher than the steepest hill: every point on the ground sees it, no map needed. The path
// scenes' hills (80 cm, 30 m apart) rise far less than tan 46 = 1.04 (the sun 48 degrees up less its
// 2 degree radius) anywhere.
TEST(SunHorizon, AHighSunOverGentleHillsIsOpenEverywhere) {
  const TerrainMesh mesh = makeTerrainMesh(hills(), kTrack);
  const SunHorizon horizon(mesh, {0.45, 0.75, 0.5}, 2.0 * std::numbers::pi / 180.0, kTrack);
  EXPECT_LT(horizon.steepestSlope(), 1.0);
  EXPECT_TRUE(horizon.everywhereOpen());
  EXPECT_TRUE(horizon.open({100.0f, float(mesh.heightAt(100.0, 100.0)) + 0.01f, 100.0f}, 0.01f, true));
}

// Far from the origin a shadow ray's origin is lifted by centimetres (2e-3 cm plus 3e-5 of its largest
// coordinate), more than the map's texels allow for; where the sun is open everywhere no texel is asked,
// so the ground there is still open, and none of its sun rays meets the mesh (the rolling hills to a
// kilometre past the track; every point 300 m to 1 km from the origin, lifted along the hills' normal
// as the renderer lifts it).
TEST(SunHorizon, AHighSunIsOpenEvenWhereTheRayOffsetIsCentimetres) {
  const test::HighSunHills hills;
  ASSERT_TRUE(hills.horizon.everywhereOpen());
  std::mt19937 rng(29);
  for (int i = 0; i < 400; ++i) {
    const glm::vec2 at = test::farFromTheOrigin(rng);
    const glm::vec3 p = test::groundBelow(hills.scene.ground(), at.x, at.y);
    ASSERT_TRUE(std::isfinite(p.y)) << p.x << " " << p.z;
    const float extent = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
    const float slack = 3e-3f + 4e-5f * extent;
    ASSERT_GT(slack, 1.0f);  // past what a texel allows for
    ASSERT_TRUE(hills.horizon.open(p, slack, true)) << p.x << " " << p.z;
    const glm::vec3 above(p.x, p.y + 100.0f, p.z);  // a rider's point, not known on the mesh
    ASSERT_TRUE(hills.horizon.openAbove(above, slack, hills.mesh.heightAt(p.x, p.z))) << p.x << " " << p.z;
    const glm::vec3 n(hills.terrain.normal(double(p.x), double(p.z)));
    const std::array<bool, 17> blocked = hills.discBlocked(p + (2e-3f + 3e-5f * extent) * n);
    for (int k = 0; k <= 16; ++k) ASSERT_FALSE(blocked[std::size_t(k)]) << p.x << " " << p.z << ", ray " << k;
  }
}

// Steep hills under a low sun: wherever the map says a point is open, no ray of the sun's disc from it
// meets the mesh (traced through Embree, the rim and the centre of the disc); and the map is of use,
// answering much of the lit ground while the hills shadow half of it (sun 8 degrees up, 5 m hills 15 m apart).
TEST(SunHorizon, WhereItSaysOpenNoSunRayMeetsTheMesh) {
  const test::SteepHills hills;
  const TerrainMesh& mesh = hills.mesh;
  const SunHorizon& horizon = hills.horizon;
  ASSERT_FALSE(horizon.everywhereOpen());
  ASSERT_GT(horizon.width(), 0u);
  uint32_t state = 11u;
  auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) * 0x1p-24;
  };
  int said_open = 0, blocked_axis = 0, points = 0;
  for (int i = 0; i < 4000; ++i) {
    const double x = -1500.0 + 3000.0 * uniform(), z = -1500.0 + 3000.0 * uniform();
    const glm::vec3 q(float(x), float(mesh.heightAt(x, z) + 0.2), float(z));  // a ray origin just above
    ++points;
    const bool open = horizon.open(q, 0.05f, false);
    said_open += open;
    ASSERT_EQ(horizon.openAbove(q, 0.05f, mesh.heightAt(x, z)), open) << x << " " << z;  // the height given
    const std::array<bool, 17> blocked = hills.discBlocked(q);
    blocked_axis += blocked[0];
    for (int r = 0; r <= 16; ++r) {
      if (open) {
        ASSERT_FALSE(blocked[std::size_t(r)]) << "said open at " << x << " " << z << ", ray " << r << " meets the mesh";
      }
    }
  }
  std::printf("%d points: %d with the sun's axis blocked by the hills, %d said open\n", points, blocked_axis, said_open);
  EXPECT_GT(blocked_axis, points / 10);                 // the hills do shadow the ground
  EXPECT_GT(said_open, (points - blocked_axis) / 4);    // and much of the lit ground needs no ray (28% measured)
}

}  // namespace
}  // namespace stirrup::render
