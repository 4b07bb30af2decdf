#include "scene/fence.h"

#include <algorithm>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace stirrup::scene {
namespace {

rig::Obstacle fence(double height) {
  rig::Obstacle o;
  o.height_cm = height;
  o.width_cm = 320.0;
  return o;
}

TEST(Fence, PolesTopOutAtTheFenceHeightAcrossItsWidth) {
  const FenceStyle style;
  const PropMesh m = makeFence(fence(90.0), 500.0, style);
  ASSERT_FALSE(m.indices.empty());
  float pole_top = -1e9f, z_lo = 1e9f, z_hi = -1e9f, post_top = -1e9f;
  for (const glm::vec3& p : m.positions) {
    // Pole vertices lie within the pole radius of the line; the square posts' corners lie outside it.
    const bool on_pole = std::abs(p.x - 500.0f) < 0.5f * (style.pole_radius_cm + style.post_half_cm);
    if (on_pole) pole_top = std::max(pole_top, p.y), z_lo = std::min(z_lo, p.z), z_hi = std::max(z_hi, p.z);
    else post_top = std::max(post_top, p.y);
    EXPECT_NEAR(p.x, 500.0f, style.post_half_cm + 1e-3) << "everything stands on the fence's line";
    EXPECT_GE(p.y, -1e-4f) << "nothing below the ground";
  }
  EXPECT_NEAR(pole_top, 90.0f, 1e-3f);
  EXPECT_NEAR(z_lo, -160.0f, 1e-3f);
  EXPECT_NEAR(z_hi, 160.0f, 1e-3f);
  EXPECT_NEAR(post_top, 90.0f + style.post_above_cm, 1e-3f);
}

TEST(Fence, TrianglesFaceOutAndNormalsAreUnit) {
  const PropMesh m = makeFence(fence(120.0), 0.0);
  ASSERT_EQ(m.positions.size(), m.normals.size());
  ASSERT_EQ(m.positions.size(), m.colors.size());
  ASSERT_EQ(m.indices.size() % 3, 0u);
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], c = m.positions[m.indices[i + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    ASSERT_GT(glm::length(face), 0.0f) << "degenerate triangle " << i / 3;
    const glm::vec3 n = m.normals[m.indices[i]] + m.normals[m.indices[i + 1]] + m.normals[m.indices[i + 2]];
    EXPECT_GT(glm::dot(face, n), 0.0f) << "triangle " << i / 3 << " faces inward";
  }
}

TEST(Fence, PolesArePaintedInBands) {
  const FenceStyle style;
  const PropMesh m = makeFence(fence(90.0), 0.0, style);
  const auto count = [&](const glm::vec3& c) { return std::count(m.colors.begin(), m.colors.end(), c); };
  EXPECT_GT(count(style.red), 0);
  EXPECT_GT(count(style.white), count(style.red));  // the posts are white too
}

TEST(Fence, RejectsAFenceWithNoSize) {
  EXPECT_THROW(makeFence(fence(0.0), 0.0), std::invalid_argument);
  rig::Obstacle o = fence(90.0);
  o.width_cm = -1.0;
  EXPECT_THROW(makeFence(o, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace stirrup::scene
