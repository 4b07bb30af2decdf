#include "rig/characters/proportions.h"

namespace stirrup::rig {

HorseParams scaledHorse(double withers_height_cm, double rider_height_cm) {
  HorseParams h;
  const auto s = static_cast<float>(withers_height_cm / kDefaultWithersHeightCm);
  const auto r = static_cast<float>(rider_height_cm / kDefaultRiderHeightCm);
  // Every place and size; colours and the polygonisation cell are not sizes.
  for (glm::vec3* v : {&h.hips, &h.back_mid, &h.chest_joint, &h.barrel_center, &h.barrel_radii, &h.chest_center,
                       &h.chest_radii, &h.croup_center, &h.croup_radii, &h.buttock_center, &h.buttock_radii,
                       &h.quarter_center, &h.quarter_radii, &h.neck_base, &h.neck_mid, &h.poll, &h.muzzle,
                       &h.fore_scapula, &h.fore_shoulder, &h.fore_elbow, &h.fore_knee, &h.fore_fetlock, &h.fore_hoof,
                       &h.hind_hip, &h.hind_stifle, &h.hind_hock, &h.hind_fetlock, &h.hind_hoof, &h.tail_root})
    *v *= s;
  for (float* f : {&h.withers_height, &h.withers_x, &h.neck_base_radius, &h.neck_mid_radius, &h.throat_radius,
                   &h.head_radius, &h.muzzle_radius, &h.ear_length, &h.mane_radius, &h.forearm_radius, &h.knee_radius,
                   &h.cannon_radius, &h.fetlock_radius, &h.gaskin_radius, &h.hock_radius, &h.hoof_radius,
                   &h.hoof_height, &h.tail_length, &h.saddle_x, &h.saddle_seat_height})
    *f *= s;
  // The stirrup hangs from the saddle as long as her leg (y), out from the barrel as wide as the horse
  // (z); the rein meets her hand where her arm reaches.
  h.mount.stirrup = {h.mount.stirrup.x * r, h.mount.stirrup.y * r, h.mount.stirrup.z * s};
  h.mount.rein_grip *= r;
  return h;
}

RiderParams scaledRider(double height_cm, double build) {
  RiderParams p;
  const auto s = static_cast<float>(height_cm / kDefaultRiderHeightCm);
  const auto b = static_cast<float>(build);
  for (glm::vec3* v : {&p.pelvis, &p.lower_back, &p.waist, &p.chest, &p.upper_chest, &p.neck, &p.head, &p.shoulder,
                       &p.wrist_from_grip, &p.hip, &p.ankle_from_ball, &p.hips_radii, &p.chest_radii})
    *v *= s;
  for (float* f : {&p.head_height, &p.upper_arm, &p.forearm, &p.thigh, &p.shin, &p.waist_radius, &p.shoulder_radius,
                   &p.wrist_radius, &p.thigh_radius, &p.knee_radius, &p.calf_radius, &p.ankle_radius, &p.braid_radius,
                   &p.braid_length, &p.coat_tail_length})
    *f *= s;
  // Build: girth (depth and breadth), not height.
  for (glm::vec3* v : {&p.hips_radii, &p.chest_radii}) *v *= glm::vec3(b, 1.0f, b);
  for (float* f : {&p.waist_radius, &p.thigh_radius, &p.knee_radius, &p.calf_radius}) *f *= b;
  return p;
}

}  // namespace stirrup::rig
