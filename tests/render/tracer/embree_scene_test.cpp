// The Embree scenes (render/tracer/embree_scene.cpp): the ground quad and the character meshes, traced with
// single rays whose hits are worked out by hand, in every BVH update mode.
#include "render/tracer/embree_scene.h"

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace stirrup::render
