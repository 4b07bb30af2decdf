// The default rider: about 170 cm, built seated, in saddle space (the horse's "saddle" joint, the
// seat centre, is the origin; +X toward the horse's head, +Y up, +Z the horse's right). Red coat,
// breeches, tall dark boots, a braid. Every proportion is a named parameter; the mount geometry
// (stirrup and rein places) is the horse's MountParams, passed in, never repeated here.
//
// Roles: "pelvis" (root), "lowerBack", "waist" (spineC), "chest" (spineD), "upperChest" (spineF),
// "neck", "head" (headA), "braid1".."braid3", "coatTail", and per side s = l, r: "<s>Shoulder",
// "<s>Elbow", "<s>Wrist", "<s>Hand" (where the hand closes on the rein, unskinned), "<s>Hip", "<s>Knee", "<s>Ankle", "<s>Ball" (ball of the foot, on the
// stirrup tread at rest).
//
// Spine (docs/curve-spine.md, "The rider"): "lowerBack", "waist" and "chest" are the curve spine's
// three FK controllers (unskinned joints straight up from the lower back; their bones end at the
// next controller and at "upperChest"). The torso is skinned to a chain of kRiderSpineSegments
// equal bones, joints and roles "spine0" (at the lower back, child of the pelvis) .. "spine<N>" (the chain's
// tip = "upperChest"), laid on the curve by poseRiderSpine. Neck, shoulders and coat tail hang
// from chain joints.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "rig/character.h"
#include "rig/curve_spine.h"
#include "rig/characters/horse_character.h"
#include "rig/rider_spine.h"  // riderSpine reads the chain buildRider lays out

namespace stirrup::rig {

struct RiderParams {
  // Spine joints, saddle space (cm).
  glm::vec3 pelvis{-3.0f, 10.0f, 0.0f};
  glm::vec3 lower_back{-4.0f, 17.0f, 0.0f};
  glm::vec3 waist{-4.5f, 27.0f, 0.0f};
  glm::vec3 chest{-4.5f, 38.0f, 0.0f};
  glm::vec3 upper_chest{-4.5f, 48.0f, 0.0f};
  glm::vec3 neck{-3.5f, 57.0f, 0.0f};
  glm::vec3 head{-2.5f, 66.0f, 0.0f};     // top of the neck, the head's pivot
  float head_height = 24.0f;              // chin to crown
  // Arms (left; mirrored for the right).
  glm::vec3 shoulder{-4.5f, 50.0f, -17.0f};
  float upper_arm = 29.0f, forearm = 25.0f;
  glm::vec3 wrist_from_grip{-6.0f, 1.0f, -1.0f};
  glm::vec3 elbow_pole_dir{-0.5f, -1.0f, -0.45f};  // elbows hang back, down and a little out
  // Legs (left; mirrored for the right).
  glm::vec3 hip{-2.0f, 10.0f, -12.5f};
  float thigh = 45.0f, shin = 45.0f;
  glm::vec3 ankle_from_ball{-12.0f, 7.0f, 0.0f};   // heel down, toe in the iron
  glm::vec3 knee_pole_dir{1.0f, 0.0f, -1.0f};      // knees forward and out around the barrel
  // Soft tissue and clothes (radii, cm).
  glm::vec3 hips_radii{11.0f, 10.0f, 16.5f};
  glm::vec3 chest_radii{11.5f, 11.5f, 16.0f};
  float waist_radius = 13.5f;
  float shoulder_radius = 5.2f, wrist_radius = 3.2f;
  float thigh_radius = 8.0f, knee_radius = 5.8f, calf_radius = 5.6f, ankle_radius = 4.0f;
  float braid_radius = 2.6f, braid_length = 34.0f;
  float coat_tail_length = 22.0f;
  // Colours (linear).
  glm::vec3 skin{0.72f, 0.42f, 0.30f};
  glm::vec3 coat{0.42f, 0.02f, 0.025f};
  glm::vec3 breeches{0.72f, 0.66f, 0.52f};
  glm::vec3 boots{0.012f, 0.010f, 0.009f};
  glm::vec3 hair{0.07f, 0.03f, 0.012f};
  glm::vec3 eyes{0.01f, 0.01f, 0.012f};
  // Mesh.
  float cell = 1.05f;
};

// `mount`: where the stirrup treads and rein grips are (the horse's HorseParams::mount).
Character buildRider(const RiderParams& params, const MountParams& mount = MountParams{});
Character buildDefaultRider();
// The rider's trunk alone, as buildRider lays it out (pelvis, the curve spine's controllers and chain,
// neck and head, with their roles; no mesh): for jobs that measure how her spine responds.
Character buildRiderTrunk(const RiderParams& params);

inline constexpr int kRiderSpineSegments = CurveSpine::kRiderSegments;

}  // namespace stirrup::rig
