#include "rig/balance.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "rig/rider_rig.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {


// Segment masses, percent of body mass, women (Plagenhoef, Evans and Abdelnour 1983, "Anatomical data
// for analyzing human motion", Res. Q. Exerc. Sport 54(2)): trunk, head and neck, and one arm (upper
// arm 2.90 + forearm 1.57 + hand 0.50).
constexpr double kTrunkMass = 45.0, kHeadMass = 8.2, kArmMass = 4.97;

// A soft limit: slope 1 at 0, approaching `band` (> 0).
double soft(double x, double band) { return band > 0.0 ? band * std::tanh(x / band) : 0.0; }

}  // namespace

double leanDegrees(glm::vec3 v, glm::vec3 forward) {
  return std::atan2(double(glm::dot(v, forward)), double(v.y)) * kDegreesPerRadian;
}

glm::vec3 saddleHeading(const glm::mat4& saddle) {
  glm::vec3 x(saddle[0]);
  x.y = 0.0f;
  const float n = glm::length(x);
  return n > 1e-6f ? x / n : glm::vec3(1.0f, 0.0f, 0.0f);
}

glm::vec3 sideways(glm::vec3 heading) { return glm::cross(heading, glm::vec3(0.0f, 1.0f, 0.0f)); }

double horseRollDegrees(const Character& horse, std::span<const glm::mat4> world) {
  const auto hip = [&](const char* leg) {
    const std::string pivot = std::string(leg) + "Pivot";
    return glm::vec3(world[std::size_t(horse.roles.count(pivot) ? horse.role(pivot) : horse.role(std::string(leg) + "Upper"))][3]);
  };
  const glm::vec3 across = hip("rb") - hip("lb");
  return std::atan2(-double(across.y), std::hypot(double(across.x), double(across.z))) * kDegreesPerRadian;
}

double trunkComHeight(const Character& rider) {
  const Skeleton& s = rider.skeleton;
  // Her hips: where a seated user's rider folds (hipCentre, between her hip joints), else the pelvis
  // joint (the generated rider's is at her hip joints' height). A user's pelvis joint may sit well
  // below or above them (Rigify's DEF-spine 6.5 cm below), which would read as a longer trunk.
  const auto hip_centre = rider.roles.find("hipCentre");
  const double pelvis = s.restPosition(hip_centre != rider.roles.end() ? hip_centre->second : rider.role("pelvis")).y;
  const double shoulders = 0.5 * (s.restPosition(rider.role("lShoulder")).y + s.restPosition(rider.role("rShoulder")).y);
  const double head = s.restPosition(rider.role("head")).y;
  const double elbows = 0.5 * (s.restPosition(rider.role("lElbow")).y + s.restPosition(rider.role("rElbow")).y);
  const double trunk = 0.5 * (pelvis + shoulders);
  const double com = (kTrunkMass * trunk + kHeadMass * head + 2.0 * kArmMass * elbows) / (kTrunkMass + kHeadMass + 2.0 * kArmMass);
  return std::max(com - pelvis, 1.0);
}

BalanceResult balanceTrunk(const BalanceInput& in, const RigProfile::Balance& p) {
  BalanceResult out;
  const glm::vec3 forward = saddleHeading(in.saddle);
  const glm::vec3 up(in.saddle[1]);
  out.saddle_pitch_deg = leanDegrees(up, forward);
  out.pose_lean_deg = leanDegrees(in.trunk, forward);
  // 1. The fold relative to the saddle, scaled back up by what the posing limit took off.
  out.channel_lean_deg = out.saddle_pitch_deg + (out.pose_lean_deg - out.saddle_pitch_deg) * std::max(in.fold_scale, 1.0);
  // 2. The base of support stirrup_share of the way from the seat to the stirrups, ahead of the seat
  //    in the world against where it is with the saddle level (in the saddle's own frame).
  const glm::vec3 base = (in.stirrups - in.seat) * float(p.stirrup_share);
  const glm::vec3 saddle_x = glm::normalize(glm::vec3(in.saddle[0]));
  const double h = std::max(in.com_height_cm, 1.0);
  out.support_lean_deg = (std::atan2(double(glm::dot(base, forward)), h) - std::atan2(double(glm::dot(base, saddle_x)), h)) * kDegreesPerRadian;
  // 2b. Balanced against gravity and the travel's acceleration.
  out.inertia_lean_deg = std::atan2(p.inertia_share * in.accel_cm_s2, kStandardGravityCmS2) * kDegreesPerRadian;
  // 3. The band.
  // 2c. Against the ground's slope.
  //     The support term (2.) already holds her trunk's centre of mass over her feet as the slope pitches
  //     the horse, which keeps her near the world's vertical; this is the lean riders add on top of it.
  out.slope_lean_deg = (in.ground_pitch_deg >= 0.0 ? p.slope_response : p.downhill_response) * in.ground_pitch_deg;
  const double request = out.channel_lean_deg + out.support_lean_deg + out.inertia_lean_deg + out.slope_lean_deg;
  double lean = request >= 0.0 ? soft(request, p.band_forward_deg) : soft(request, p.band_back_deg);
  // 4. The body's limits, relative to the saddle's upright.
  const double fold = std::clamp(lean - out.saddle_pitch_deg, -p.max_extension_deg, p.max_fold_deg);
  out.limited = fold != lean - out.saddle_pitch_deg;
  lean = out.saddle_pitch_deg + fold;
  // 5. The blend.
  out.lean_deg = out.pose_lean_deg + p.amount * (lean - out.pose_lean_deg);
  out.turn_deg = out.lean_deg - out.pose_lean_deg;
  const double folded = p.max_fold_deg > 0.0 ? std::clamp(fold / p.max_fold_deg, 0.0, 1.0) : 0.0;
  out.seat_lift_cm = p.amount * std::max(0.0, p.seat_rise_cm * folded * folded - in.seat_rise_cm);
  return out;
}

double turnTiltDegrees(double side_accel_cm_s2, const RigProfile::Balance& p) {
  return p.amount * p.turn_share * std::atan2(side_accel_cm_s2, kStandardGravityCmS2) * kDegreesPerRadian;
}

RiderChannels answerTiltedVertical(const RiderChannels& r, const HorseChannels& horse, const RigProfile& profile,
                                   double tilt_deg) {
  if (tilt_deg == 0.0) return r;
  // The difference the tilt makes, not the channels evaluated again: r may carry what evaluateRider did
  // not give (a caller's own channels), and only the roll's answer is the stage's to change.
  HorseChannels tilted = horse;
  tilted[HorseChannel::rearPivotRx] -= tilt_deg;
  const RiderChannels from_tilted = evaluateRider(tilted, profile), from_world = evaluateRider(horse, profile);
  RiderChannels out = r;
  for (std::size_t c = 0; c < kRiderChannelCount; ++c) out.value[c] += from_tilted.value[c] - from_world.value[c];
  return out;
}

}  // namespace stirrup::rig
