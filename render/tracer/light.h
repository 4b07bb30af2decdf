// The lights of the review look behind one interface: the sun (a disc of a given angular radius,
// sampled as a cone so shadows are soft) and the sky (a vertical gradient, sampled cosine-weighted for
// ambient occlusion). Each says the radiance arriving from a direction, draws a direction to sample it
// from a surface, says whether a point needs occlusion rays for it at all (the shadow-ray test: false
// where it is certainly open) and hands the SIMD lanes the numbers they read of it (LaneConstants).
// The lanes (render/tracer/shading_lanes.h, render/tracer/sample_lanes.h) evaluate the same model for
// a whole batch, operation for operation; the scalar members here are that model for one point.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/tracer/lights.h"
#include "render/tracer/sample_lanes.h"

namespace stirrup::render {

// The characters' bounding box, as the lights' occlusion tests see it (lower > upper: empty).
struct OccluderBox {
  glm::vec3 lower{0.0f}, upper{0.0f};
  bool empty() const { return !(lower.x <= upper.x && lower.y <= upper.y && lower.z <= upper.z); }
};

class Light {
 public:
  virtual ~Light() = default;
  // Radiance arriving from unit direction wi (toward the light), unoccluded.
  virtual glm::vec3 radiance(const glm::vec3& wi) const = 0;
  // A direction to sample the light from a surface with unit normal n, for u in [0, 1)^2.
  virtual glm::vec3 sampleDirection(const glm::vec3& n, glm::vec2 u) const = 0;
  // Whether a point at `origin` needs occlusion rays for this light (false: certainly open).
  virtual bool mayBeBlocked(const glm::vec3& origin) const = 0;
  // What the lanes read of this light (RenderSettings::open_ground_shortcuts is the integrator's).
  virtual void toLanes(LaneConstants& k) const = 0;
};

// The sun: radiance sun_color * sun_strength within its cone, none outside. Its shadow-ray test is
// against the characters' box: a point whose whole cone misses the box is lit without rays.
class Sun final : public Light {
 public:
  // `direction` toward the sun (any length), `angular_radius_deg` its disc's radius, `ground_floor`
  // the lowest ground height (for the ground's rectangle).
  Sun(const glm::dvec3& direction, double angular_radius_deg, const glm::vec3& radiance, const OccluderBox& box,
      float ground_floor);

  glm::vec3 radiance(const glm::vec3& wi) const override;
  glm::vec3 sampleDirection(const glm::vec3& n, glm::vec2 u) const override;  // n unused: the sun's cone
  // Whether any ray of the sun's cone from `origin` can meet the characters' box.
  bool mayBeBlocked(const glm::vec3& origin) const override;
  void toLanes(LaneConstants& k) const override;

  // The same answer for a point on or just above the ground, mostly from a rectangle worked out once.
  bool groundMayBeBlocked(const glm::vec3& origin) const;
  // True when the point is outside that rectangle (so the sun is certainly unblocked there).
  bool groundRegionExcludes(const glm::vec3& origin) const;

  const Frame& frame() const { return frame_; }             // its z: the unit axis toward the sun
  const glm::vec3& axisRadiance() const { return radiance_; }  // of a white matte surface facing it
  float cosMax() const { return cos_max_; }

 private:
  void setGroundRegion();

  Frame frame_;
  glm::vec3 inv_dir_;  // 1 / the axis, per component: slab tests without divisions
  float cos_max_, tan_;
  glm::vec3 radiance_;
  OccluderBox box_;
  float box_radius_;   // of the sphere around the box; < 0: no characters
  float ground_floor_;
  bool ground_region_;  // ground points outside [lower, upper] (x, z) see the sun unblocked
  glm::vec2 ground_lower_{0.0f}, ground_upper_{0.0f};
};

// The sky: the gradient's radiance by direction, and from below a character the lit ground's bounce.
// Its occlusion test: a point farther than ao_distance from the characters' box sees the whole sky.
class Sky final : public Light {
 public:
  // `ground_bounce`: the radiance of the lit ground, seen by a character's downward sky rays.
  Sky(const SkyGradient& gradient, float ao_distance, const OccluderBox& box, const glm::vec3& ground_bounce);

  glm::vec3 radiance(const glm::vec3& wi) const override;  // SkyGradient::radiance
  glm::vec3 sampleDirection(const glm::vec3& n, glm::vec2 u) const override;  // cosine-weighted around n
  // Whether an upward surface at `origin` may see the characters within ao_distance.
  bool mayBeBlocked(const glm::vec3& origin) const override;
  void toLanes(LaneConstants& k) const override;

  // Irradiance / pi on an open upward surface (the cosine-weighted mean of the gradient).
  glm::vec3 upwardIrradianceOverPi() const { return gradient_.upwardIrradianceOverPi(); }
  const glm::vec3& groundBounce() const { return ground_bounce_; }
  const SkyGradient& gradient() const { return gradient_; }

 private:
  SkyGradient gradient_;
  float ao_distance_;
  OccluderBox box_;
  glm::vec3 ground_bounce_;
};

}  // namespace stirrup::render
