#include "scene/camera.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace stirrup::scene {

Ray Camera::generateRay(double u, double v, double aspect) const {
  // The pixel count only matters for footprints; rays depend on the aspect alone.
  return CameraFrame(*this, aspect, 1).ray(u, v);
}

CameraFrame::CameraFrame(const Camera& camera, int width, int height)
    : CameraFrame(camera, height > 0 ? double(width) / height : 0.0, height) {}

CameraFrame::CameraFrame(const Camera& camera, double aspect, int height) : projection_(camera.projection) {
  if (!(aspect > 0.0) || height <= 0) throw std::invalid_argument("camera: film size must be positive");
  const glm::dvec3 view = camera.target - camera.position;
  const double distance = glm::length(view);
  if (!(distance > 0.0) || !std::isfinite(distance)) {
    throw std::invalid_argument("camera: position and target must be distinct, finite points");
  }
  forward_ = view / distance;
  target_distance_f_ = float(distance);
  position_ = camera.position;
  // A view straight along `up` has no defined roll; fall back to another axis rather than fail.
  glm::dvec3 up_hint = glm::length(camera.up) > 0.0 ? glm::normalize(camera.up) : glm::dvec3(0, 1, 0);
  if (std::abs(glm::dot(up_hint, forward_)) > 0.9999) {
    up_hint = std::abs(forward_.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  }
  right_ = glm::normalize(glm::cross(forward_, up_hint));
  up_ = glm::cross(right_, forward_);

  if (projection_ == Camera::Projection::Perspective) {
    if (!(camera.fov_deg > 0.0 && camera.fov_deg < 180.0)) {
      throw std::invalid_argument("camera: fov_deg must be in (0, 180)");
    }
    half_height_ = std::tan(camera.fov_deg * std::numbers::pi / 360.0);
    footprint_at_0_ = 0.0;
    footprint_per_cm_ = 2.0 * half_height_ / height;
  } else {
    if (!(camera.ortho_height_cm > 0.0)) throw std::invalid_argument("camera: ortho_height_cm must be > 0");
    half_height_ = 0.5 * camera.ortho_height_cm;
    footprint_at_0_ = camera.ortho_height_cm / height;
    footprint_per_cm_ = 0.0;
  }
  half_width_ = half_height_ * aspect;
  perspective_ = projection_ == Camera::Projection::Perspective;
  position_f_ = glm::vec3(position_);
  forward_f_ = glm::vec3(forward_);
  right_f_ = glm::vec3(right_);
  up_f_ = glm::vec3(up_);
  half_width_f_ = float(half_width_);
  half_height_f_ = float(half_height_);
  const double width_px = aspect * height;
  pixel_dx_ = float(2.0 * half_width_ / width_px);
  pixel_dy_ = float(2.0 * half_height_ / height);
  footprint_at_0_f_ = float(footprint_at_0_);
  footprint_per_cm_f_ = float(footprint_per_cm_);
}

Ray CameraFrame::ray(double u, double v) const {
  const double x = (2.0 * u - 1.0) * half_width_;
  const double y = (1.0 - 2.0 * v) * half_height_;
  if (projection_ == Camera::Projection::Perspective) {
    return {position_, glm::normalize(forward_ + x * right_ + y * up_)};
  }
  return {position_ + x * right_ + y * up_, forward_};
}

double CameraFrame::viewDepth(const glm::dvec3& p) const { return glm::dot(p - position_, forward_); }

}  // namespace stirrup::scene
