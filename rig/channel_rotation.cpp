#include "rig/channel_rotation.h"

#include "rig/units.h"
#include <numbers>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/glm.hpp>
#include <glm/gtx/euler_angles.hpp>

namespace stirrup::rig {
glm::dquat rotationFromChannels(double rx, double ry, double rz) {
  const glm::dmat4 m = glm::eulerAngleYZX(-ry * kRadiansPerDegree, rz * kRadiansPerDegree, rx * kRadiansPerDegree);
  return glm::quat_cast(glm::dmat3(m));
}

std::array<double, 3> channelsFromRotation(const glm::dquat& q) {
  double y = 0, z = 0, x = 0;
  glm::extractEulerAngleYZX(glm::dmat4(glm::mat3_cast(q)), y, z, x);
  return {x * kDegreesPerRadian, -y * kDegreesPerRadian, z * kDegreesPerRadian};  // rx, ry, rz
}

}  // namespace stirrup::rig
