// The render camera: a pinhole (perspective) or an orthographic projection looking from `position`
// at `target`. Film coordinates run u in [0, 1] left to right and v in [0, 1] top to bottom.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>

namespace stirrup::scene {

struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit length
};

struct Camera {
  enum class Projection { Perspective, Orthographic } projection = Projection::Perspective;
  glm::dvec3 position{0.0, 120.0, 900.0};
  glm::dvec3 target{0.0, 120.0, 0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_deg = 30.0;           // vertical field of view (perspective)
  double ortho_height_cm = 300.0;  // height of the view (orthographic)

  // The ray through film point (u, v) for a film of width / height = aspect.
  Ray generateRay(double u, double v, double aspect) const;
};

// A camera prepared for one film: the orthonormal view basis and the film extent, computed once per
// frame so that generating a ray is a few multiply-adds. Throws std::invalid_argument when the camera
// cannot form an image (position on the target, a field of view outside (0, 180), a size <= 0).
class CameraFrame {
 public:
  CameraFrame(const Camera& camera, int width, int height);
  CameraFrame(const Camera& camera, double aspect, int height);

  Ray ray(double u, double v) const;
  // The same ray in floats, from pixel coordinates (x right, y down, in pixels): the renderer's
  // per-sample path. Positions are kept relative to the camera in floats, so the error stays a few
  // ulps of the view size rather than of the world coordinates.
  void rayFromPixel(float px, float py, glm::vec3& origin, glm::vec3& direction) const {
    const float x = px * pixel_dx_ - half_width_f_, y = half_height_f_ - py * pixel_dy_;
    if (perspective_) {
      const glm::vec3 d = forward_f_ + x * right_f_ + y * up_f_;
      origin = position_f_;
      direction = d * (1.0f / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
    } else {
      origin = position_f_ + x * right_f_ + y * up_f_;
      direction = forward_f_;
    }
  }
  // pixelFootprint and viewDepth in floats.
  float pixelFootprintF(float t) const { return footprint_at_0_f_ + footprint_per_cm_f_ * t; }
  float viewDepthF(const glm::vec3& p) const {
    const glm::vec3 d = p - position_f_;
    return d.x * forward_f_.x + d.y * forward_f_.y + d.z * forward_f_.z;
  }

  // The width in centimetres of one pixel's footprint on a surface facing the camera at distance t
  // along the ray: constant for orthographic views, growing with t for perspective ones. Used to
  // filter the ground texture so that squares far away blur to their mean instead of crawling.
  double pixelFootprint(double t) const { return footprint_at_0_ + footprint_per_cm_ * t; }

  // Distance of a point in front of the camera along the viewing axis (the depth pass).
  double viewDepth(const glm::dvec3& p) const;

  bool perspective() const { return perspective_; }
  // Distance from the camera to its target along the view (where an orthographic ground starts to fade).
  float targetDistanceF() const { return target_distance_f_; }
  const glm::vec3& positionF() const { return position_f_; }
  const glm::vec3& forwardF() const { return forward_f_; }
  const glm::vec3& upF() const { return up_f_; }
  const glm::vec3& rightF() const { return right_f_; }
  // What rayFromPixel and pixelFootprintF compute from, for the SIMD kernels (sample_lanes.h).
  void laneView(bool& perspective, float& pixel_dx, float& pixel_dy, float& half_width, float& half_height,
                float& footprint_at_0, float& footprint_per_cm) const {
    perspective = perspective_, pixel_dx = pixel_dx_, pixel_dy = pixel_dy_, half_width = half_width_f_;
    half_height = half_height_f_, footprint_at_0 = footprint_at_0_f_, footprint_per_cm = footprint_per_cm_f_;
  }

  const glm::dvec3& forward() const { return forward_; }
  const glm::dvec3& right() const { return right_; }
  const glm::dvec3& upward() const { return up_; }
  // The film's half extent across and up: tangents of the half angles (perspective) or centimetres.
  double halfWidth() const { return half_width_; }
  double halfHeight() const { return half_height_; }

 private:
  Camera::Projection projection_;
  glm::dvec3 position_, forward_, right_, up_;
  double half_width_, half_height_;  // film half-extent: tangents (perspective) or centimetres (ortho)
  double footprint_at_0_, footprint_per_cm_;
  // Float copies for the per-sample path.
  bool perspective_;
  glm::vec3 position_f_, forward_f_, right_f_, up_f_;
  float half_width_f_, half_height_f_, pixel_dx_, pixel_dy_;
  float footprint_at_0_f_, footprint_per_cm_f_;
  float target_distance_f_;
};

}  // namespace stirrup::scene
