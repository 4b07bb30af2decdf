// Tubes (rig/characters/tube.cpp): rings along the polyline at the ring spacing, the radius, the sag,
// the skin weights blending the two joints, and a closed surface, counted by hand on a straight tube.
#include "rig/characters/tube.h"

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// 12 cm along x from joint 0 to joint 1, rings every 3 cm: 5 rings (x = 0, 3, 6, 9, 12) of 8 vertices,
// plus a cap centre at each end = 42 vertices; 4 x 8 side quads (2 triangles each) and 2 x 8 cap
// triangles = 80 triangles.
TEST(Tube, RingsAtTheSpacingWithTheRadius) {
  SkinnedMesh m;
  const std::vector<TubePoint> line = {{{0, 0, 0}, 0}, {{12, 0, 0}, 1}};
  TubeParams p;
  p.radius = 1.0f;
  p.sides = 8;
  p.ring_spacing = 3.0f;
  p.color = {0.2f, 0.3f, 0.4f};
  appendTube(m, line, p);
  ASSERT_EQ(m.positions.size(), 42u);
  EXPECT_EQ(m.indices.size(), 80u * 3u);
  for (std::size_t v = 0; v < 40; ++v) {
    const int ring = int(v / 8);
    EXPECT_NEAR(m.positions[v].x, 3.0f * ring, 1e-5f) << v;
    EXPECT_NEAR(std::hypot(m.positions[v].y, m.positions[v].z), 1.0f, 1e-5f) << v;  // on the radius
    EXPECT_NEAR(m.normals[v].x, 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(m.normals[v]), 1.0f, 1e-5f);
    // From joint 0 to joint 1 linearly: ring 1 (t = 0.25) is 0.75 / 0.25.
    EXPECT_EQ(m.joints[v].x, 0);
    EXPECT_EQ(m.joints[v].y, 1);
    EXPECT_NEAR(m.weights[v].x, 1.0f - 0.25f * ring, 1e-6f) << v;
    EXPECT_NEAR(m.weights[v].y, 0.25f * ring, 1e-6f) << v;
    EXPECT_EQ(m.colors[v], p.color);
  }
  // The caps' centres face out of the ends.
  EXPECT_EQ(m.positions[40], glm::vec3(0, 0, 0));
  EXPECT_NEAR(m.normals[40].x, -1.0f, 1e-6f);
  EXPECT_EQ(m.positions[41], glm::vec3(12, 0, 0));
  EXPECT_NEAR(m.normals[41].x, 1.0f, 1e-6f);
  // Closed: every edge belongs to exactly two triangles.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = m.indices[t + k], b = m.indices[t + (k + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& [edge, count] : edges) EXPECT_EQ(count, 2) << edge.first << "-" << edge.second;
}

// A sag of 2 cm droops the middle by 4 s (1 - s) x 2: 2 cm at the middle, 1.5 cm a quarter along.
TEST(Tube, SagDroopsTheMiddle) {
  SkinnedMesh m;
  const std::vector<TubePoint> line = {{{0, 0, 0}, 3}, {{12, 0, 0}, 3}};
  TubeParams p;
  p.sides = 4;
  p.sag = 2.0f;
  appendTube(m, line, p);
  const auto ringCentreY = [&](int ring) {
    float y = 0.0f;
    for (int k = 0; k < 4; ++k) y += m.positions[std::size_t(ring * 4 + k)].y;
    return y / 4.0f;
  };
  EXPECT_NEAR(ringCentreY(0), 0.0f, 1e-5f);
  EXPECT_NEAR(ringCentreY(1), -1.5f, 1e-5f);
  EXPECT_NEAR(ringCentreY(2), -2.0f, 1e-5f);
  EXPECT_NEAR(ringCentreY(4), 0.0f, 1e-5f);
  EXPECT_EQ(m.weights[0], glm::vec4(1, 0, 0, 0));  // one joint: all on it
  EXPECT_EQ(m.joints[0].x, 3);
}

TEST(Tube, AppendsAfterWhatIsThereAndSkipsDegenerateTubes) {
  SkinnedMesh m;
  m.positions.resize(10);
  m.normals.resize(10);
  m.colors.resize(10);
  m.joints.resize(10);
  m.weights.resize(10);
  TubeParams p;
  p.sides = 3;
  p.ring_spacing = 100.0f;  // one step: two rings
  appendTube(m, std::vector<TubePoint>{{{0, 0, 0}, 0}, {{0, 5, 0}, 0}}, p);
  EXPECT_EQ(m.positions.size(), 10u + 2 * 3 + 2);
  for (std::uint32_t i : m.indices) EXPECT_GE(i, 10u);
  const std::size_t before = m.positions.size();
  appendTube(m, std::vector<TubePoint>{{{0, 0, 0}, 0}}, p);  // one point
  appendTube(m, std::vector<TubePoint>{{{1, 1, 1}, 0}, {{1, 1, 1}, 0}}, p);  // no length
  p.sides = 2;
  appendTube(m, std::vector<TubePoint>{{{0, 0, 0}, 0}, {{0, 5, 0}, 0}}, p);  // not a tube
  EXPECT_EQ(m.positions.size(), before);
}

// A tube of the tack labels its own vertices with its part; one that is no tack's labels nothing in a mesh
// without tack, and its vertices as the body's in a mesh with tack.
TEST(Tube, ATackTubeLabelsItsVerticesWithItsPart) {
  SkinnedMesh m;
  TubeParams p;
  p.sides = 4;
  appendTube(m, std::vector<TubePoint>{{{0, 0, 0}, 0}, {{0, 5, 0}, 0}}, p);
  EXPECT_TRUE(m.tack_parts.empty());
  const std::size_t body = m.vertexCount();
  p.part = TackPart::StirrupIronR;
  appendTube(m, std::vector<TubePoint>{{{0, 0, 0}, 0}, {{0, 5, 0}, 0}}, p);
  const std::size_t iron = m.vertexCount();
  p.part = TackPart::None;
  appendTube(m, std::vector<TubePoint>{{{0, 0, 0}, 0}, {{0, 5, 0}, 0}}, p);
  ASSERT_EQ(m.tack_parts.size(), m.vertexCount());
  for (std::size_t v = 0; v < m.vertexCount(); ++v)
    EXPECT_EQ(m.tack_parts[v], v >= body && v < iron ? TackPart::StirrupIronR : TackPart::None) << v;
  EXPECT_EQ(m.triangleTackPart(m.triangleCount() - 1), TackPart::None);
}

}  // namespace
}  // namespace stirrup::rig
