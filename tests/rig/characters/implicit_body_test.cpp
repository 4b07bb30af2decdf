#include "rig/characters/implicit_body.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <gtest/gtest.h>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"

namespace stirrup::rig {
namespace {

// Every edge used by exactly two triangles, in opposite directions: closed and consistently wound.
// Surface Nets puts one vertex per cell, so where two sheets of surface pass through one cell (a
// crease sharper than the grid) a few edges can be shared by four triangles: allowed up to
// `nonmanifold_fraction`, but never an open edge.
void expectClosedAndOriented(const SkinnedMesh& m, double nonmanifold_fraction = 0.0) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) ++edges[{m.indices[t + e], m.indices[t + (e + 1) % 3]}];
  std::size_t shared = 0, open = 0;
  for (const auto& [edge, count] : edges) {
    shared += count != 1;
    const auto twin = edges.find({edge.second, edge.first});
    open += twin == edges.end() || twin->second != count;
  }
  EXPECT_EQ(open, 0u) << "open edges";
  EXPECT_LE(double(shared), nonmanifold_fraction * double(edges.size())) << shared << " of " << edges.size();
}

float signedVolume(const SkinnedMesh& m) {
  double v = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    v += glm::dot(m.positions[m.indices[t]], glm::cross(m.positions[m.indices[t + 1]], m.positions[m.indices[t + 2]]));
  return static_cast<float>(v / 6.0);
}

void expectFiniteAndUnitNormals(const SkinnedMesh& m) {
  ASSERT_GT(m.vertexCount(), 0u);
  ASSERT_EQ(m.normals.size(), m.vertexCount());
  ASSERT_EQ(m.colors.size(), m.vertexCount());
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const glm::vec3 p = m.positions[v];
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    ASSERT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-4f);
  }
  for (std::uint32_t i : m.indices) ASSERT_LT(i, m.vertexCount());
}

TEST(ImplicitBody, SphereIsClosedOutwardAndOnTheZeroSet) {
  ImplicitBody body;
  body.add(taperedCapsule({0, 0, 0}, {0, 0, 0}, 10.0f, 10.0f, 0, {1, 0, 0}));
  PolygonizeParams params;
  params.cell = 1.0f;
  const SkinnedMesh m = polygonize(body, params);
  expectFiniteAndUnitNormals(m);
  expectClosedAndOriented(m);
  const float exact = 4.0f / 3.0f * std::numbers::pi_v<float> * 1000.0f;
  EXPECT_NEAR(signedVolume(m), exact, 0.03f * exact);  // positive: wound outward
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    EXPECT_NEAR(glm::length(m.positions[v]), 10.0f, 0.05f);
    EXPECT_GT(glm::dot(m.normals[v], glm::normalize(m.positions[v])), 0.999f);
    EXPECT_EQ(m.colors[v], glm::vec3(1, 0, 0));
  }
}

// A shape of a horse's tack labels the vertices it paints (those nearest it) with its part; a body of no
// tack labels none.
TEST(ImplicitBody, ATackShapeLabelsTheSurfaceItPaints) {
  ImplicitBody body;
  body.add(taperedCapsule({-20, 0, 0}, {20, 0, 0}, 8.0f, 8.0f, 0, {1, 0, 0}));
  PolygonizeParams params;
  params.cell = 1.0f;
  EXPECT_TRUE(polygonize(body, params).tack_parts.empty());
  ImplicitPrimitive pad = ellipsoid({0, 8, 0}, {10, 3, 10}, 1, {0, 0, 1}, 0.5f);
  pad.tack_part = TackPart::SaddlePad;
  body.add(pad);
  const SkinnedMesh m = polygonize(body, params);
  ASSERT_EQ(m.tack_parts.size(), m.vertexCount());
  std::size_t labelled = 0;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    EXPECT_EQ(m.tack_parts[v] == TackPart::SaddlePad, m.colors[v] == glm::vec3(0, 0, 1)) << v;
    labelled += m.tack_parts[v] == TackPart::SaddlePad;
  }
  EXPECT_GT(labelled, 100u);
}

TEST(ImplicitBody, BlendedLimbIsClosedWithVerticesOnTheSurface) {
  ImplicitBody body;
  body.add(ellipsoid({0, 0, 0}, {20, 10, 12}, 0, {1, 0, 0}, 4.0f));
  body.add(taperedCapsule({15, 0, 0}, {40, -20, 0}, 6.0f, 3.0f, 1, {0, 1, 0}, 4.0f));
  ImplicitPrimitive hoof = taperedCapsule({40, -20, 0}, {42, -30, 0}, 3.0f, 4.0f, 2, {0, 0, 1}, 1.0f);
  hoof.clip_min.y = -29.0f;
  body.add(hoof);
  PolygonizeParams params;
  params.cell = 1.2f;
  const SkinnedMesh m = polygonize(body, params);
  expectFiniteAndUnitNormals(m);
  expectClosedAndOriented(m, 0.002);
  EXPECT_GT(signedVolume(m), 0.0f);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    ASSERT_LT(std::abs(body.distance(m.positions[v])), 0.25f * params.cell) << v;
    EXPECT_GE(m.positions[v].y, -29.0f - 0.3f * params.cell);  // flat clipped sole
    // Weights: far from the capsule, a vertex on the ellipsoid belongs to joint 0 alone.
    if (m.positions[v].x < -5.0f) {
      EXPECT_EQ(m.joints[v][0], 0);
      EXPECT_NEAR(m.weights[v][0], 1.0f, 1e-4f);
      EXPECT_EQ(m.colors[v], glm::vec3(1, 0, 0));
    }
  }
}

TEST(ImplicitBody, SmoothMinIsMinAwayFromTheCreaseAndBelowItNear) {
  EXPECT_FLOAT_EQ(smoothMin(1.0f, 5.0f, 2.0f), 1.0f);
  EXPECT_FLOAT_EQ(smoothMin(5.0f, 1.0f, 2.0f), 1.0f);
  EXPECT_LT(smoothMin(1.0f, 1.5f, 2.0f), 1.0f);
  EXPECT_NEAR(smoothMin(1.0f, 1.0f, 2.0f), 1.0f - 0.5f, 1e-6f);
  EXPECT_FLOAT_EQ(smoothMin(3.0f, 2.0f, 0.0f), 2.0f);
}

TEST(ImplicitBody, DefaultCharactersAreSensibleMeshes) {
  for (const Character& c : {buildDefaultHorse(), buildDefaultRider()}) {
    expectFiniteAndUnitNormals(c.mesh);
    EXPECT_GT(signedVolume(c.mesh), 0.0f) << c.name;
    for (const glm::vec3& col : c.mesh.colors) {
      ASSERT_GE(glm::min(col.x, glm::min(col.y, col.z)), 0.0f);
      ASSERT_LE(glm::max(col.x, glm::max(col.y, col.z)), 1.0f);
    }
  }
  const Character horse = buildDefaultHorse();
  const Character rider = buildDefaultRider();
  EXPECT_GT(horse.mesh.triangleCount(), 30000u);
  EXPECT_LT(horse.mesh.triangleCount(), 80000u);
  EXPECT_GT(rider.mesh.triangleCount(), 20000u);
  EXPECT_LT(rider.mesh.triangleCount(), 60000u);
}

}  // namespace
}  // namespace stirrup::rig
