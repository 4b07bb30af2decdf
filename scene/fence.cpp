#include "scene/fence.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace stirrup::scene {
namespace {

void addVertex(PropMesh& m, const glm::vec3& p, const glm::vec3& n, const glm::vec3& c) {
  m.positions.push_back(p);
  m.normals.push_back(n);
  m.colors.push_back(c);
}

// An axis-aligned box with flat-shaded faces (four vertices each, so edges stay crisp).
void addBox(PropMesh& m, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& color) {
  struct Face {
    glm::vec3 n, u, v;  // outward normal and two edge directions with u × v = n
  };
  const glm::vec3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
  const Face faces[6] = {
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
  };
  for (const Face& f : faces) {
    const auto base = static_cast<uint32_t>(m.positions.size());
    const glm::vec3 centre = c + f.n * h;
    const glm::vec3 u = f.u * h, v = f.v * h;
    addVertex(m, centre - u - v, f.n, color);
    addVertex(m, centre + u - v, f.n, color);
    addVertex(m, centre + u + v, f.n, color);
    addVertex(m, centre - u + v, f.n, color);
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
  }
}

// A pole along Z from z0 to z1 at (x, y), smooth-shaded, in bands of alternating colour. Each band is
// its own ring pair so the colours change sharply at the band edges.
void addPole(PropMesh& m, double x, double y, double z0, double z1, const FenceStyle& s) {
  const int bands = std::max(1, static_cast<int>(std::lround((z1 - z0) / s.band_cm)));
  const double step = (z1 - z0) / bands;
  const auto r = static_cast<float>(s.pole_radius_cm);
  for (int b = 0; b < bands; ++b) {
    const glm::vec3 color = b % 2 == 0 ? s.white : s.red;
    const auto base = static_cast<uint32_t>(m.positions.size());
    for (int end = 0; end < 2; ++end) {
      const auto z = static_cast<float>(z0 + step * (b + end));
      for (int k = 0; k < s.pole_sides; ++k) {
        const double a = 2.0 * std::numbers::pi * k / s.pole_sides;
        const glm::vec3 n(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
        addVertex(m, glm::vec3(static_cast<float>(x), static_cast<float>(y), z) + r * n, n, color);
      }
    }
    const auto sides = static_cast<uint32_t>(s.pole_sides);
    for (uint32_t k = 0; k < sides; ++k) {
      const uint32_t k1 = (k + 1) % sides;
      const uint32_t a = base + k, b2 = base + k1, c = base + sides + k, d = base + sides + k1;
      // Outward winding: the ring at z0 then z1, angle increasing counter-clockwise about +Z.
      for (uint32_t i : {a, b2, d, a, d, c}) m.indices.push_back(i);
    }
  }
}

}  // namespace

PropMesh makeFence(const rig::Obstacle& obstacle, double x_cm, const FenceStyle& style) {
  if (!(obstacle.height_cm > 0.0) || !(obstacle.width_cm > 0.0) || !(obstacle.depth_cm > 0.0))
    throw std::invalid_argument("fence: height, width and depth must be positive");
  PropMesh m;
  const double half_w = 0.5 * obstacle.width_cm;
  const double r = style.pole_radius_cm;
  // Wing posts just outside the poles' ends, standing on the ground.
  const auto post_top = static_cast<float>(obstacle.height_cm + style.post_above_cm);
  for (double side : {-1.0, 1.0}) {
    const double z = side * (half_w + style.post_half_cm);
    const auto ph = static_cast<float>(style.post_half_cm);
    addBox(m, glm::vec3(static_cast<float>(x_cm) - ph, 0.0f, static_cast<float>(z) - ph),
           glm::vec3(static_cast<float>(x_cm) + ph, post_top, static_cast<float>(z) + ph), style.white);
  }
  // Three poles: the top one's top at the fence height.
  for (double fraction : {1.0, 2.0 / 3.0, 1.0 / 3.0}) {
    const double y = fraction * obstacle.height_cm - r;
    if (y - r < 0.0) continue;  // a very low fence has fewer poles
    addPole(m, x_cm, y, -half_w, half_w, style);
  }
  return m;
}

}  // namespace stirrup::scene
