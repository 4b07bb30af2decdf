#include "rig/channel_rotation.h"

#include <numbers>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/glm.hpp>
#include <glm/gtx/euler_angles.hpp>

namespace stirrup::rig {
namespace {
constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr double kRad = std::numbers::pi / 180.0;
}  // namespace

glm::dquat rotationFromChannels(double rx, double ry, double rz) {
  const glm::dmat4 m = glm::eulerAngleYZX(-ry * kRad, rz * kRad, rx * kRad);
  return glm::quat_cast(glm::dmat3(m));
}

std::array<double, 3> channelsFromRotation(const glm::dquat& q) {
  double y = 0, z = 0, x = 0;
  glm::extractEulerAngleYZX(glm::dmat4(glm::mat3_cast(q)), y, z, x);
  return {x * kDeg, -y * kDeg, z * kDeg};  // rx, ry, rz
}

}  // namespace stirrup::rig
