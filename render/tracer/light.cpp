#include "render/tracer/light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

namespace stirrup::render {

Sun::Sun(const glm::dvec3& direction, double angular_radius_deg, const glm::vec3& radiance, const OccluderBox& box,
         float ground_floor)
    : radiance_(radiance), box_(box), ground_floor_(ground_floor) {
  frame_ = Frame::around(glm::normalize(glm::vec3(direction)));
  inv_dir_ = 1.0f / frame_.z;  // inf for a zero component, which mayBeBlocked never uses
  const float angle = float(std::max(0.0, angular_radius_deg) * std::numbers::pi / 180.0);
  cos_max_ = std::cos(angle);
  tan_ = std::tan(angle);
  box_radius_ = box.empty() ? -1.0f : 0.5f * glm::length(box.upper - box.lower);
  setGroundRegion();
}

glm::vec3 Sun::radiance(const glm::vec3& wi) const {
  return glm::dot(wi, frame_.z) >= cos_max_ ? radiance_ : glm::vec3(0.0f);
}

glm::vec3 Sun::sampleDirection(const glm::vec3&, glm::vec2 u) const { return sampleCone(frame_, cos_max_, u); }

// Whether any ray of the sun's cone from `origin` can meet the characters' bounding box. The cone is
// covered by the axis ray against the box grown by the cone's radius at the box's far corner. When it
// misses, the sun is certainly unblocked there and needs no shadow rays (most of the ground).
bool Sun::mayBeBlocked(const glm::vec3& origin) const {
  if (box_radius_ < 0.0f) return false;
  const glm::vec3 far_corner = glm::max(glm::abs(origin - box_.lower), glm::abs(origin - box_.upper));
  const float margin = glm::length(far_corner) * tan_ * 1.01f + 0.1f;
  const glm::vec3 lower = box_.lower - margin, upper = box_.upper + margin;
  const glm::vec3& d = frame_.z;
  float t0 = 0.0f, t1 = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0f) {
      if (origin[a] < lower[a] || origin[a] > upper[a]) return false;
      continue;
    }
    float near = (lower[a] - origin[a]) * inv_dir_[a], far = (upper[a] - origin[a]) * inv_dir_[a];
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return false;
  }
  return true;
}

// mayBeBlocked(o) is true only when the sun's axis from o meets the characters' box grown by a margin
// M(o) = |far corner| tan(sun radius) 1.01 + 0.1 (above). For a point o on the ground, hitting it at q
// (in the grown box) means o = q - t d with t = (q.y - o.y) / d.y <= (H + M) / d.y, H the box's top,
// and the far corner is at most t + |box extent| + sqrt(3) M from o. So M <= k ((H + M) / d.y +
// |extent| + sqrt(3) M) + 0.1 with k = 1.01 tan: a bound on M, and with it a rectangle of the ground
// outside which mayBeBlocked is certainly false. The rectangle answers most of the ground in four
// comparisons, with the same answer the full test gives there.
void Sun::setGroundRegion() {
  ground_region_ = false;
  const glm::vec3& d = frame_.z;
  if (box_radius_ < 0.0f || !(d.y > 0.0f)) return;
  const float k = 1.01f * tan_;
  const float denominator = 1.0f - k / d.y - 1.7320508f * k;
  if (!(denominator > 0.1f)) return;  // a low or very wide sun: no useful bound, always run the test
  // Heights from the lowest ground (0 on the plane: then exactly the plane's bound).
  const float top = std::max(box_.upper.y - ground_floor_, 0.0f);
  const float extent = glm::length(box_.upper - box_.lower);
  const float margin = (k * (top / d.y + extent) + 0.1f) / denominator * 1.01f + 1.0f;  // + rounding slack
  const float t_max = (top + margin) / d.y;
  ground_lower_ = {box_.lower.x - margin - std::max(0.0f, t_max * d.x),
                   box_.lower.z - margin - std::max(0.0f, t_max * d.z)};
  ground_upper_ = {box_.upper.x + margin - std::min(0.0f, t_max * d.x),
                   box_.upper.z + margin - std::min(0.0f, t_max * d.z)};
  ground_region_ = true;
}

bool Sun::groundRegionExcludes(const glm::vec3& origin) const {
  return ground_region_ && origin.y >= ground_floor_ &&
         (origin.x < ground_lower_.x || origin.x > ground_upper_.x || origin.z < ground_lower_.y ||
          origin.z > ground_upper_.y);
}

bool Sun::groundMayBeBlocked(const glm::vec3& origin) const {
  return !groundRegionExcludes(origin) && mayBeBlocked(origin);
}

void Sun::toLanes(LaneConstants& k) const {
  k.sun_y = frame_.z.y;
  k.sun_radiance = radiance_;
  k.sun_region = ground_region_;
  k.sun_lower_x = ground_lower_.x, k.sun_lower_z = ground_lower_.y;
  k.sun_upper_x = ground_upper_.x, k.sun_upper_z = ground_upper_.y;
  k.sun_frame_x = frame_.x, k.sun_frame_y = frame_.y, k.sun_axis = frame_.z;
  k.sun_cos_max = cos_max_, k.sun_tan = tan_;
}

Sky::Sky(const SkyGradient& gradient, float ao_distance, const OccluderBox& box, const glm::vec3& ground_bounce)
    : gradient_(gradient), ao_distance_(ao_distance), box_(box), ground_bounce_(ground_bounce) {}

glm::vec3 Sky::radiance(const glm::vec3& wi) const { return gradient_.radiance(wi); }

glm::vec3 Sky::sampleDirection(const glm::vec3& n, glm::vec2 u) const {
  return sampleCosineHemisphere(Frame::around(n), u);
}

// As the shading lanes decide it for upward ground: without characters nothing blocks the sky; with
// them, only a point within ao_distance of their box may be.
bool Sky::mayBeBlocked(const glm::vec3& origin) const {
  if (box_.empty()) return false;
  const glm::vec3 e = glm::max(glm::max(box_.lower - origin, origin - box_.upper), glm::vec3(0.0f));
  return !(glm::length(e) > ao_distance_);
}

void Sky::toLanes(LaneConstants& k) const {
  k.horizon = gradient_.horizon, k.zenith = gradient_.zenith, k.below = gradient_.below;
  k.sky_irradiance = gradient_.upwardIrradianceOverPi();
  k.ao_distance = ao_distance_;
  k.ground_bounce = ground_bounce_;
}

}  // namespace stirrup::render
