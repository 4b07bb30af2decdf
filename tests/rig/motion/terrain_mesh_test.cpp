#include "rig/motion/terrain_mesh.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "rig/motion/terrain.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

std::string errorOf(std::vector<glm::dvec3> v, std::vector<std::uint32_t> i) {
  return stirrup::test::errorOf([&] { (void)TerrainMesh(std::move(v), std::move(i), "ground.glb"); }, "");
}

// A 10 m square ramp rising 1 cm per 10 cm along +X, as two triangles: every height on it is known.
TerrainMesh ramp() {
  return TerrainMesh({{0, 0, 0}, {1000, 100, 0}, {1000, 100, 1000}, {0, 0, 1000}}, {0, 1, 2, 0, 2, 3}, "ramp");
}

TEST(TerrainMesh, HeightsAndNormalsOnARamp) {
  const TerrainMesh m = ramp();
  EXPECT_EQ(m.triangleCount(), 2u);
  for (double x : {0.0, 1.0, 333.3, 999.0, 1000.0})
    for (double z : {0.0, 500.0, 999.9, 1000.0}) {
      const auto hit = m.at(x, z);
      ASSERT_TRUE(hit) << x << ", " << z;
      EXPECT_NEAR(hit->height_cm, 0.1 * x, 1e-9) << x << ", " << z;
      EXPECT_NEAR(hit->normal.x, -0.1 / std::sqrt(1.01), 1e-9);
      EXPECT_GT(hit->normal.y, 0.99);
    }
  // On the shared diagonal: no gap between the two triangles.
  for (double t = 0; t <= 1000; t += 7.3) EXPECT_TRUE(m.at(t, t)) << t;
  EXPECT_FALSE(m.at(-0.5, 10));
  EXPECT_FALSE(m.at(10, 1000.5));
}

// Two layers (a bridge over the ramp): the horse stands on the highest surface.
TEST(TerrainMesh, TheHighestSurfaceWins) {
  const TerrainMesh m({{0, 0, 0}, {1000, 0, 0}, {0, 0, 1000}, {200, 300, 200}, {400, 300, 200}, {200, 300, 400}},
                      {0, 1, 2, 3, 4, 5}, "two");
  EXPECT_NEAR(m.at(250, 250)->height_cm, 300.0, 1e-9);
  EXPECT_NEAR(m.at(100, 100)->height_cm, 0.0, 1e-9);
}

// A mesh terrain through rig::Terrain: height and slope from the triangle, and off it the lowest vertex.
TEST(TerrainMesh, AsATerrain) {
  const Terrain t = Terrain::mesh(std::make_shared<const TerrainMesh>(ramp()));
  EXPECT_FALSE(t.flat());
  EXPECT_NEAR(t.height(500, 500), 50.0, 1e-9);
  double gx = 0, gz = 0;
  t.gradient(500, 500, gx, gz);
  EXPECT_NEAR(gx, 0.1, 1e-9);
  EXPECT_NEAR(gz, 0.0, 1e-9);
  EXPECT_TRUE(t.covers(10, 10));
  EXPECT_FALSE(t.covers(-10, 10));
  EXPECT_EQ(t.height(-10, 10), 0.0);
}

// Many triangles (a 200 x 200 grid): lookups through the grid agree with the surface everywhere.
TEST(TerrainMesh, AGridOfManyTriangles) {
  HillsParams p;
  p.amplitude_cm = 100;
  p.wavelength_cm = 2000;
  const Terrain hills = Terrain::hills(p, "s");
  std::vector<glm::dvec3> v;
  std::vector<std::uint32_t> idx;
  const int n = 200;
  const double step = 25.0;
  for (int z = 0; z <= n; ++z)
    for (int x = 0; x <= n; ++x) v.push_back({x * step, hills.height(x * step, z * step), z * step});
  for (int z = 0; z < n; ++z)
    for (int x = 0; x < n; ++x) {
      const auto k = std::uint32_t(z * (n + 1) + x);
      idx.insert(idx.end(), {k, k + 1, k + n + 2, k, k + n + 2, k + n + 1});
    }
  const TerrainMesh m(v, idx, "grid");
  EXPECT_EQ(m.triangleCount(), std::size_t(2 * n * n));
  // At the vertices exactly the hills; between them within the hills' curvature over a 25 cm cell.
  for (int z = 0; z <= n; z += 13)
    for (int x = 0; x <= n; x += 11) EXPECT_NEAR(m.at(x * step, z * step)->height_cm, hills.height(x * step, z * step), 1e-6);
  for (double x = 3.7; x < n * step; x += 97.1)
    for (double z = 5.1; z < n * step; z += 89.3) EXPECT_NEAR(m.at(x, z)->height_cm, hills.height(x, z), 0.5);
}

TEST(TerrainMesh, BadMeshesAreOneLineErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(errorOf({{0, 0, 0}, {1, nan, 0}, {0, 0, 1}}, {0, 1, 2}), "ground.glb: vertex 1: expected finite coordinates, got (1, nan, 0)");
  EXPECT_EQ(errorOf({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {0, 1, 3}), "ground.glb: triangle 0: expected vertex indices below 3, got 3");
  EXPECT_EQ(errorOf({}, {}), "ground.glb: expected triangles to stand on, found none");
  // A wall: no area seen from above.
  EXPECT_EQ(errorOf({{0, 0, 0}, {100, 0, 0}, {0, 100, 0}}, {0, 1, 2}), "ground.glb: expected triangles to stand on, found none");
}

}  // namespace
}  // namespace stirrup::rig
