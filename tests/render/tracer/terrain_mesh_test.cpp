#include "render/tracer/terrain_mesh.h"

#include <algorithm>
#include <cmath>

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include "render/tracer/embree_scene.h"

namespace stirrup::render {
namespace {

// Rolling hills like a path scene's: 80 cm high, 30 m apart, two octaves.
rig::Terrain hills() {
  rig::HillsParams p;
  p.seed = 3;
  p.amplitude_cm = 80.0;
  p.wavelength_cm = 3000.0;
  p.octaves = 2;
  return rig::Terrain::hills(p, "test");
}

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

}  // namespace
}  // namespace stirrup::render
