#include "scene/camera.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace stirrup::scene {
namespace {

Camera sideCamera(Camera::Projection projection) {
  Camera c;
  c.projection = projection;
  c.position = {100.0, 120.0, 900.0};
  c.target = {100.0, 120.0, 0.0};
  c.fov_deg = 30.0;
  c.ortho_height_cm = 300.0;
  return c;
}

TEST(Camera, PerspectiveCentreRayHitsTheTarget) {
  Camera c = sideCamera(Camera::Projection::Perspective);
  c.target = {50.0, 80.0, 20.0};  // off-axis on purpose
  const Ray r = c.generateRay(0.5, 0.5, 16.0 / 9.0);
  EXPECT_NEAR(glm::length(r.direction), 1.0, 1e-12);
  const glm::dvec3 to_target = glm::normalize(c.target - c.position);
  EXPECT_NEAR(glm::dot(r.direction, to_target), 1.0, 1e-12);
  EXPECT_EQ(r.origin, c.position);
}

TEST(Camera, PerspectiveVerticalFieldOfViewIsFovDeg) {
  for (double fov : {20.0, 30.0, 60.0}) {
    Camera c = sideCamera(Camera::Projection::Perspective);
    c.fov_deg = fov;
    const Ray top = c.generateRay(0.5, 0.0, 16.0 / 9.0), bottom = c.generateRay(0.5, 1.0, 16.0 / 9.0);
    const double angle = std::acos(glm::dot(top.direction, bottom.direction)) * 180.0 / std::numbers::pi;
    EXPECT_NEAR(angle, fov, 1e-9);
    EXPECT_GT(top.direction.y, 0.0);  // v = 0 is the top of the film
  }
}

TEST(Camera, PerspectiveHorizontalExtentFollowsAspect) {
  Camera c = sideCamera(Camera::Projection::Perspective);
  const double aspect = 2.0;
  const Ray left = c.generateRay(0.0, 0.5, aspect), right = c.generateRay(1.0, 0.5, aspect);
  const double half_w = std::tan(std::acos(glm::dot(left.direction, right.direction)) / 2.0);
  EXPECT_NEAR(half_w, aspect * std::tan(15.0 * std::numbers::pi / 180.0), 1e-9);
  // Looking down -Z from +Z, +X (the horse's travel) is to the right of the picture.
  EXPECT_LT(left.direction.x, 0.0);
  EXPECT_GT(right.direction.x, 0.0);
}

TEST(Camera, OrthographicRaysAreParallelAndSpanTheHeight) {
  const Camera c = sideCamera(Camera::Projection::Orthographic);
  const Ray a = c.generateRay(0.1, 0.2, 16.0 / 9.0), b = c.generateRay(0.9, 0.7, 16.0 / 9.0);
  EXPECT_EQ(a.direction, b.direction);
  EXPECT_NEAR(glm::dot(a.direction, glm::dvec3(0, 0, -1)), 1.0, 1e-12);
  const Ray top = c.generateRay(0.5, 0.0, 16.0 / 9.0), bottom = c.generateRay(0.5, 1.0, 16.0 / 9.0);
  EXPECT_NEAR(top.origin.y - bottom.origin.y, 300.0, 1e-9);
  EXPECT_NEAR(c.generateRay(0.5, 0.5, 1.0).origin.y, 120.0, 1e-9);
  const Ray left = c.generateRay(0.0, 0.5, 2.0), right = c.generateRay(1.0, 0.5, 2.0);
  EXPECT_NEAR(right.origin.x - left.origin.x, 600.0, 1e-9);
}

TEST(Camera, FootprintAndDepth) {
  const CameraFrame persp(sideCamera(Camera::Projection::Perspective), 640, 360);
  EXPECT_NEAR(persp.pixelFootprint(900.0), 900.0 * 2.0 * std::tan(15.0 * std::numbers::pi / 180.0) / 360.0, 1e-9);
  EXPECT_NEAR(persp.viewDepth({0.0, 0.0, 0.0}), 900.0, 1e-9);
  const CameraFrame ortho(sideCamera(Camera::Projection::Orthographic), 640, 360);
  EXPECT_NEAR(ortho.pixelFootprint(10.0), 300.0 / 360.0, 1e-12);
  EXPECT_NEAR(ortho.pixelFootprint(5000.0), 300.0 / 360.0, 1e-12);
}

TEST(Camera, LookingStraightDownStillHasABasis) {
  Camera c;
  c.position = {0, 500, 0};
  c.target = {0, 0, 0};
  const Ray r = c.generateRay(0.5, 0.5, 1.0);
  EXPECT_NEAR(r.direction.y, -1.0, 1e-12);
  EXPECT_TRUE(std::isfinite(c.generateRay(0.0, 0.0, 1.0).direction.x));
}

TEST(Camera, RejectsCamerasThatCannotFormAnImage) {
  Camera c;
  c.target = c.position;
  EXPECT_THROW(c.generateRay(0.5, 0.5, 1.0), std::invalid_argument);
  Camera wide;
  wide.fov_deg = 180.0;
  EXPECT_THROW(CameraFrame(wide, 64, 36), std::invalid_argument);
  EXPECT_THROW(CameraFrame(Camera{}, 0, 36), std::invalid_argument);
}

}  // namespace
}  // namespace stirrup::scene
