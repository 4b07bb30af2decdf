#include "rig/tack_pose.h"

#include <string>

#include "rig/pose_transforms.h"
#include "rig/skeleton.h"

namespace stirrup::rig {

using namespace pose_transforms;

glm::vec3 stirrupTarget(const Character& horse, std::span<const glm::mat4> horseWorld, const RiderChannels& r,
                        double rider_unit_cm, int side) {
  checkSize(horse, horseWorld);
  using C = RiderChannel;
  const Skeleton& s = horse.skeleton;
  const int saddle = horse.role("saddle");
  const int stirrup = horse.role(side == 0 ? "lStirrup" : "rStirrup");
  const float u = static_cast<float>(rider_unit_cm);
  const float tx = float(r[side == 0 ? C::lFootTx : C::rFootTx]) * u;
  const float away = float(r[side == 0 ? C::lFootTz : C::rFootTz]) * u * (side == 0 ? -1.0f : 1.0f);
  const glm::vec3 rest_in_saddle = s.restPosition(stirrup) - s.restPosition(saddle);
  return transformPoint(horseWorld[saddle], rest_in_saddle + glm::vec3(tx, 0.0f, away));
}

void placeStirrups(const Character& horse, std::span<glm::mat4> horseWorld, const RiderChannels& r,
                   double rider_unit_cm) {
  for (int side = 0; side < 2; ++side) {
    const glm::vec3 p = stirrupTarget(horse, horseWorld, r, rider_unit_cm, side);
    glm::mat4& m = horseWorld[horse.role(side == 0 ? "lStirrup" : "rStirrup")];
    m = horseWorld[horse.role("saddle")];
    m[3] = glm::vec4(p, 1.0f);
  }
}

void placeReins(const Character& horse, std::span<glm::mat4> horseWorld, const Character& rider,
                std::span<const glm::mat4> riderWorld) {
  checkSize(horse, horseWorld);
  checkSize(rider, riderWorld);
  for (const char* side : {"l", "r"}) {
    glm::mat4& m = horseWorld[horse.role(std::string(side) + "Rein")];
    m = horseWorld[horse.role("saddle")];
    m[3] = riderWorld[rider.role(std::string(side) + "Hand")][3];
  }
}

}  // namespace stirrup::rig
