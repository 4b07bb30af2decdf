#include "rig/characters/tube.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace stirrup::rig {
namespace {

struct Ring {
  glm::vec3 center;
  glm::vec3 tangent;
  glm::u16vec4 joints;
  glm::vec4 weights;
};

glm::vec3 perpendicular(glm::vec3 t) {
  const glm::vec3 axis = std::abs(t.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  return glm::normalize(glm::cross(t, axis));
}

}  // namespace

void appendTube(SkinnedMesh& mesh, std::span<const TubePoint> points, const TubeParams& params) {
  if (points.size() < 2 || params.sides < 3) return;
  // Total length, for the sag profile.
  float total = 0.0f;
  for (std::size_t i = 1; i < points.size(); ++i) total += glm::length(points[i].position - points[i - 1].position);
  if (total <= 1e-6f) return;

  std::vector<Ring> rings;
  float walked = 0.0f;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const TubePoint& a = points[i - 1];
    const TubePoint& b = points[i];
    const float len = glm::length(b.position - a.position);
    const int steps = std::max(1, static_cast<int>(std::ceil(len / params.ring_spacing)));
    for (int s = (i == 1 ? 0 : 1); s <= steps; ++s) {
      const float t = static_cast<float>(s) / steps;
      const float along = (walked + t * len) / total;
      Ring r;
      r.center = glm::mix(a.position, b.position, t) - glm::vec3(0.0f, params.sag * 4.0f * along * (1.0f - along), 0.0f);
      r.joints = glm::u16vec4(a.joint, b.joint, 0, 0);
      r.weights = a.joint == b.joint ? glm::vec4(1, 0, 0, 0) : glm::vec4(1.0f - t, t, 0, 0);
      rings.push_back(r);
    }
    walked += len;
  }
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const glm::vec3 prev = rings[i > 0 ? i - 1 : i].center, next = rings[i + 1 < rings.size() ? i + 1 : i].center;
    rings[i].tangent = glm::normalize(next - prev);
  }

  // Parallel transport keeps the rings from twisting along the tube.
  const std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size());
  const auto sides = static_cast<std::uint32_t>(params.sides);
  glm::vec3 normal = perpendicular(rings[0].tangent);
  auto push = [&](glm::vec3 p, glm::vec3 n, const Ring& r) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
    mesh.colors.push_back(params.color);
    mesh.joints.push_back(r.joints);
    mesh.weights.push_back(r.weights);
  };
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const glm::vec3 t = rings[i].tangent;
    normal = normal - t * glm::dot(normal, t);
    normal = glm::length(normal) > 1e-6f ? glm::normalize(normal) : perpendicular(t);
    const glm::vec3 binormal = glm::cross(t, normal);
    for (std::uint32_t k = 0; k < sides; ++k) {
      const float a = 2.0f * std::numbers::pi_v<float> * static_cast<float>(k) / static_cast<float>(sides);
      const glm::vec3 radial = std::cos(a) * normal + std::sin(a) * binormal;
      push(rings[i].center + params.radius * radial, radial, rings[i]);
    }
  }
  const auto n_rings = static_cast<std::uint32_t>(rings.size());
  for (std::uint32_t i = 0; i + 1 < n_rings; ++i)
    for (std::uint32_t k = 0; k < sides; ++k) {
      const std::uint32_t a = base + i * sides + k, b = base + i * sides + (k + 1) % sides;
      const std::uint32_t c = b + sides, d = a + sides;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
    }
  // Caps: a fan at each end, facing along the tube.
  const std::uint32_t start = static_cast<std::uint32_t>(mesh.positions.size());
  push(rings.front().center, -rings.front().tangent, rings.front());
  const std::uint32_t end = start + 1;
  push(rings.back().center, rings.back().tangent, rings.back());
  const std::uint32_t last = base + (n_rings - 1) * sides;
  for (std::uint32_t k = 0; k < sides; ++k) {
    mesh.indices.insert(mesh.indices.end(), {start, base + (k + 1) % sides, base + k});
    mesh.indices.insert(mesh.indices.end(), {end, last + k, last + (k + 1) % sides});
  }
  mesh.labelTack(base, params.part);
}

}  // namespace stirrup::rig
