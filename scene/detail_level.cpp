#include "scene/detail_level.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace stirrup::scene {

double pixelsPerCm(const Camera& camera, int height, const glm::dvec3& point, double reach_cm) {
  if (camera.projection == Camera::Projection::Orthographic) return height / camera.ortho_height_cm;
  // A pair within its reach of the camera is as near as can be: full detail.
  const double distance = std::max(glm::length(point - camera.position) - reach_cm, 1.0);
  const double half_height_cm = distance * std::tan(0.5 * camera.fov_deg * std::numbers::pi / 180.0);
  return 0.5 * height / half_height_cm;
}

bool sphereInView(const Camera& camera, int width, int height, const glm::dvec3& centre, double radius) {
  const CameraFrame f(camera, width, height);
  const glm::dvec3 q = centre - camera.position;
  const double x = glm::dot(q, f.right()), y = glm::dot(q, f.upward()), z = glm::dot(q, f.forward());
  if (!f.perspective())
    return std::abs(x) <= f.halfWidth() + radius && std::abs(y) <= f.halfHeight() + radius && z >= -radius;
  if (z < -radius) return false;
  // Each side plane through the eye: its inward unit normal's dot with q, against -radius.
  const double tw = f.halfWidth(), th = f.halfHeight();
  const double nh = 1.0 / std::sqrt(1.0 + th * th), nw = 1.0 / std::sqrt(1.0 + tw * tw);
  return (z * tw - std::abs(x)) * nw >= -radius && (z * th - std::abs(y)) * nh >= -radius;
}

int pairDetailLevel(const Camera& camera, int width, int height, const glm::dvec3& horse_root, double horse_cell_cm) {
  if (!sphereInView(camera, width, height, horse_root, kPairReachCm + kPairShadowReachCm)) return kDetailLevels - 1;
  return detailLevel(horse_cell_cm, pixelsPerCm(camera, height, horse_root, kPairReachCm));
}

int detailLevel(double horse_cell_cm, double pixels_per_cm) {
  int level = 0;
  for (int k = 1; k < kDetailLevels; ++k)
    if (horse_cell_cm * kDetailCellFactor[k] * pixels_per_cm <= kDetailSwitchCellPixels) level = k;
  return level;
}

}  // namespace stirrup::scene
