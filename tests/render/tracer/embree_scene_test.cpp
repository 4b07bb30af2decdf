// The Embree scenes (render/tracer/embree_scene.cpp): the ground quad and the character meshes, traced with
// single rays whose hits are worked out by hand, in every BVH update mode.
#include "render/tracer/embree_scene.h"

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/tracer/heightfield_mesh.h"
#include "tests/render/tracer/steep_hills.h"

namespace stirrup::render {
namespace {

// The distance along `dir` to the first hit in `scene`, or nullopt.
std::optional<float> trace(RTCScene scene, glm::vec3 org, glm::vec3 dir) {
  RTCRayHit rh{};
  rh.ray.org_x = org.x, rh.ray.org_y = org.y, rh.ray.org_z = org.z;
  rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
  rh.ray.tnear = 0.0f, rh.ray.tfar = 1e30f, rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return rh.ray.tfar;
}

// One right triangle with its legs along x and y, 10 cm each, in the plane z = `z`, moved by `dx` along x.
std::vector<glm::vec3> triangle(float z, float dx = 0.0f) { return {{dx, 0, z}, {dx + 10, 0, z}, {dx, 10, z}}; }
const std::vector<uint32_t> kOneTriangle = {0, 1, 2};

TEST(EmbreeScene, TheGroundIsASquareAtHeightZero) {
  EmbreeScene scene;
  scene.setGround(500.0f);
  const glm::vec3 down(0, -1, 0);
  EXPECT_NEAR(trace(scene.ground(), {100, 1000, -200}, down).value_or(-1), 1000.0f, 1e-3f);
  EXPECT_NEAR(trace(scene.ground(), {-499, 40, 499}, down).value_or(-1), 40.0f, 1e-3f);
  EXPECT_FALSE(trace(scene.ground(), {600, 1000, 0}, down));  // outside the 1000 cm square
  EXPECT_FALSE(trace(scene.ground(), {0, 1000, 0}, {0, 1, 0}));  // looking up
  EXPECT_FALSE(trace(scene.characters(), {100, 1000, -200}, down));  // the ground is not a character
}

// A heightfield's cells, traced as Embree quads: a hit converted to its triangle and barycentrics
// (groundTriangleHit) is the point the ray hit, on both triangles of a cell, over a warped 3 x 3 grid of
// vertices (rows along z, a cell's triangles (a c d), (a d b) as TerrainMesh makes them).
TEST(EmbreeScene, AGroundHitIsItsTrianglesPoint) {
  std::vector<glm::vec3> positions;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) positions.push_back({100.0f * i, 10.0f * float((i * 7 + j * 3) % 5), 100.0f * j});
  std::vector<uint32_t> indices;
  for (uint32_t j = 0; j < 2; ++j)
    for (uint32_t i = 0; i < 2; ++i) {
      const uint32_t a = j * 3 + i, b = a + 1, c = a + 3, d = c + 1;
      indices.insert(indices.end(), {a, c, d, a, d, b});
    }
  EmbreeScene scene;
  scene.setGroundMesh(positions, indices);
  int seen[8] = {};
  for (float x = 13.0f; x < 200.0f; x += 29.0f)
    for (float z = 7.0f; z < 200.0f; z += 31.0f) {
      SCOPED_TRACE("x " + std::to_string(x) + " z " + std::to_string(z));
      RTCRayHit rh{};
      rh.ray.org_x = x, rh.ray.org_y = 500.0f, rh.ray.org_z = z;
      rh.ray.dir_y = -1.0f;
      rh.ray.tfar = 1e30f, rh.ray.mask = 0xffffffffu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      rtcIntersect1(scene.ground(), &context, &rh);
      ASSERT_NE(rh.hit.geomID, RTC_INVALID_GEOMETRY_ID);
      const GroundTriangleHit g = groundTriangleHit(rh.hit.primID, rh.hit.u, rh.hit.v);
      ASSERT_LT(g.triangle, indices.size() / 3);
      ++seen[g.triangle];
      const uint32_t* t = &indices[3 * g.triangle];
      const glm::vec3 p = (1.0f - g.b1 - g.b2) * positions[t[0]] + g.b1 * positions[t[1]] + g.b2 * positions[t[2]];
      EXPECT_NEAR(p.x, x, 1e-3f);
      EXPECT_NEAR(p.z, z, 1e-3f);
      EXPECT_NEAR(p.y, 500.0f - rh.ray.tfar, 1e-3f);
      EXPECT_GE(g.b1, -1e-6f);
      EXPECT_GE(g.b2, -1e-6f);
      EXPECT_LE(g.b1 + g.b2, 1.0f + 1e-6f);
    }
  for (int t = 0; t < 8; ++t) EXPECT_GT(seen[t], 0) << "triangle " << t;
  // Triangles not in a cell's pairs are refused.
  std::vector<uint32_t> unpaired = indices;
  std::swap(unpaired[3], unpaired[4]);
  EXPECT_THROW(scene.setGroundMesh(positions, unpaired), std::invalid_argument);
  EXPECT_THROW(scene.setGroundMesh(positions, std::vector<uint32_t>{0, 3, 4}), std::invalid_argument);
}

TEST(EmbreeScene, MeshesFollowTheirVerticesInEveryUpdateMode) {
  for (BvhUpdate mode : {BvhUpdate::Rebuild, BvhUpdate::RebuildPerMesh, BvhUpdate::RebuildPerMeshLow, BvhUpdate::Refit}) {
    SCOPED_TRACE(static_cast<int>(mode));
    EmbreeScene scene(mode);
    const unsigned id = scene.addTriangleMesh(3, kOneTriangle, triangle(5.0f));
    EXPECT_EQ(scene.triangleCount(), 1u);
    scene.setVertices(id, triangle(5.0f));
    scene.commit();
    const glm::vec3 forward(0, 0, 1);
    // From z = -100 to the plane z = 5: 105 cm; (1, 1) is inside the triangle, (9, 9) beyond its hypotenuse.
    EXPECT_NEAR(trace(scene.characters(), {1, 1, -100}, forward).value_or(-1), 105.0f, 1e-3f);
    EXPECT_FALSE(trace(scene.characters(), {9, 9, -100}, forward));
    EXPECT_EQ(scene.characterBounds().lower_x, 0.0f);
    EXPECT_EQ(scene.characterBounds().upper_y, 10.0f);
    EXPECT_EQ(scene.characterBounds().lower_z, 5.0f);
    // Moved 100 cm along x and 15 cm nearer: the old place is empty, the new one 90 cm away.
    scene.setVertices(id, triangle(-10.0f, 100.0f));
    scene.commit();
    EXPECT_FALSE(trace(scene.characters(), {1, 1, -100}, forward));
    EXPECT_NEAR(trace(scene.characters(), {101, 1, -100}, forward).value_or(-1), 90.0f, 1e-3f);
    EXPECT_EQ(scene.characterBounds().lower_x, 100.0f);
    EXPECT_EQ(scene.characterBounds().upper_x, 110.0f);
  }
}

TEST(EmbreeScene, ADisabledMeshIsPassedThroughAndCountedApart) {
  EmbreeScene scene(BvhUpdate::Refit);
  const unsigned a = scene.addTriangleMesh(3, kOneTriangle, triangle(5.0f));
  const unsigned b = scene.addTriangleMesh(3, kOneTriangle, triangle(20.0f));
  scene.setVertices(a, triangle(5.0f));
  scene.setVertices(b, triangle(20.0f));
  scene.commit();
  const glm::vec3 org(1, 1, -100), forward(0, 0, 1);
  EXPECT_NEAR(trace(scene.characters(), org, forward).value_or(-1), 105.0f, 1e-3f);
  scene.setEnabled(a, false);
  scene.commit();
  EXPECT_NEAR(trace(scene.characters(), org, forward).value_or(-1), 120.0f, 1e-3f);  // the one behind
  EXPECT_EQ(scene.triangleCount(), 2u);
  EXPECT_EQ(scene.enabledTriangleCount(), 1u);
  scene.setEnabled(a, true);
  scene.commit();
  EXPECT_NEAR(trace(scene.characters(), org, forward).value_or(-1), 105.0f, 1e-3f);
  EXPECT_EQ(scene.enabledTriangleCount(), 2u);
}

TEST(EmbreeScene, AnExplicitIdIsKeptAndNoMeshesHaveEmptyBounds) {
  EmbreeScene scene;
  scene.commit();
  EXPECT_GT(scene.characterBounds().lower_x, scene.characterBounds().upper_x);
  EXPECT_EQ(scene.addTriangleMesh(3, kOneTriangle, {}, 7), 7u);
}

TEST(EmbreeScene, BadTrianglesAreRefused) {
  EmbreeScene scene;
  EXPECT_THROW(scene.addTriangleMesh(3, std::vector<uint32_t>{0, 1, 2, 0}), std::invalid_argument);  // a partial triangle
  EXPECT_THROW(scene.addTriangleMesh(3, std::vector<uint32_t>{0, 1, 3}), std::invalid_argument);     // no vertex 3
  EXPECT_THROW(scene.setGroundMesh(triangle(0.0f), std::vector<uint32_t>{0, 1, 5}), std::invalid_argument);
}

// The heightfield has no cracks along its edges: a ray aimed at a point of a shared edge (a cell's
// diagonal, the edge between two cells) meets the ground, traced as the renderer traces camera rays (one
// coherent stream). Without Embree's robust (watertight) test 14.5% of these rays passed between two
// triangles, and on `cross_country` and `trail` frames a few camera rays a frame did and saw the sky
// (docs/performance-history.md, "Cracks in the heightfield"). A ray aimed at a vertex, where six triangles meet, can still slip through
// (about 1.4% of them here, against 23% without the robust test); a camera ray passes that close to
// a vertex (within the rounding of its direction) far too rarely to show.
TEST(EmbreeScene, RaysAtTheHeightfieldsSharedEdgesMeetIt) {
  const TerrainMesh mesh = makeTerrainMesh(test::rollingHillsTerrain(), {0.0, 0.0, 4000.0, 4000.0});
  EmbreeScene scene;
  scene.setGroundMesh(mesh.positions, mesh.indices);
  const std::size_t nx = mesh.xs.size();
  const glm::vec3 camera(-1500.0f, 400.0f, -900.0f);  // low and far, as a perspective view's
  std::vector<RTCRayHit> rays;
  std::vector<bool> at_vertex;
  auto aim = [&](const glm::vec3& target, bool vertex) {
    const glm::vec3 dir = glm::normalize(target - camera);
    RTCRayHit rh{};
    rh.ray.org_x = camera.x, rh.ray.org_y = camera.y, rh.ray.org_z = camera.z;
    rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
    rh.ray.tfar = 1e30f, rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rays.push_back(rh);
    at_vertex.push_back(vertex);
  };
  for (std::size_t j = 0; j + 1 < mesh.zs.size(); ++j)
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      if (!(mesh.xs[i] >= 0.0 && mesh.xs[i + 1] <= 4000.0 && mesh.zs[j] >= 0.0 && mesh.zs[j + 1] <= 4000.0)) continue;
      const glm::vec3 a = mesh.positions[j * nx + i], b = mesh.positions[j * nx + i + 1];
      const glm::vec3 c = mesh.positions[(j + 1) * nx + i], d = mesh.positions[(j + 1) * nx + i + 1];
      for (const glm::vec3& on_edge : {0.5f * (a + d), 0.25f * a + 0.75f * d, 0.5f * (a + b), 0.5f * (a + c)})
        aim(on_edge, false);
      aim(a, true);
    }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect1M(scene.ground(), &context, rays.data(), unsigned(rays.size()), sizeof(RTCRayHit));
  std::size_t edge_rays = 0, edge_missed = 0, vertex_rays = 0, vertex_missed = 0;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const bool missed = rays[r].hit.geomID == RTC_INVALID_GEOMETRY_ID;
    (at_vertex[r] ? vertex_rays : edge_rays) += 1;
    (at_vertex[r] ? vertex_missed : edge_missed) += missed;
  }
  ASSERT_EQ(edge_rays, 4 * vertex_rays);
  ASSERT_GT(vertex_rays, 20000u);  // 160 x 160 cells of 25 cm
  EXPECT_EQ(edge_missed, 0u) << "of " << edge_rays << " rays at shared edges";
  EXPECT_LT(double(vertex_missed), 0.02 * double(vertex_rays)) << vertex_missed << " of " << vertex_rays << " rays at vertices";
}

}  // namespace
}  // namespace stirrup::render
