// A horse's leg reaching its hoof target with the whole limb. A stance hoof stays where the clip put
// it while the body travels over it by a stride's stance (±60 cm at a brisk walk, gait-reference.md):
// the two bones below the elbow or stifle cannot span that, so the limb above them takes part, as a
// horse's does. The scapula turns about its pivot and the shoulder opens (fore), the femur swings at
// the hip (hind), the knee or hock opens, and at the end of its reach the hoof rolls over its toe
// (breakover) or lands on its heel, keeping that edge on the ground.
//
// The limb is solved as a virtual chain pivot —a— upper —b— fetlock (a: the scapula and humerus or
// the femur; b: the two bones below). Up to its rest length the upper part swings rigidly with the
// hoof; past it a single stretch fraction t ∈ [0, 1] opens every joint together from its rest angle
// to the open angle of HorseLegParams, so the leg straightens evenly instead of locking one joint.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "rig/skeleton.h"

namespace stirrup::rig {

// How far a leg may open at its full reach. Engineering choices, not measurements: the shoulder opens
// from its standing angle (97° on the default horse) well short of straight, the carpus locks nearly
// straight under load, the hock and the line through the elbow or stifle never straighten.
struct HorseLegParams {
  float shoulder_open_deg = 160.0f;  // scapula–humerus angle at full reach (fore)
  float knee_open_deg = 178.0f;      // carpus (fore): straight in stance
  float hock_open_deg = 165.0f;      // hock (hind)
  float line_open_deg = 178.0f;      // pivot–elbow/stifle–fetlock angle of the virtual chain
  float toe_cm = 6.0f;               // hoof edges from the sole centre (the default horse's hoof radius)
  float heel_cm = 5.0f;
  float roll_max_deg = 45.0f;        // breakover / heel landing, at most
  // Share of the leg's swing (the turn of the pivot–fetlock line) the scapula or femur takes; the
  // joints below take the rest (a choice: the whole swing at the hip throws the thigh out behind).
  float upper_swing = 0.5f;
  float soften_cm = 0.3f;            // IK reach softening below the elbow or stifle, so a leg never snaps straight
};

// One leg's joints. `shoulder` is -1 where the upper part is one bone (the hind's femur, pivoting
// at the hip joint `pivot`); a fore leg has the scapula (`pivot`, turning about its pivot point) and
// the shoulder joint carrying the humerus.
struct HorseLegJoints {
  int pivot = -1, shoulder = -1, upper = -1, middle = -1, fetlock = -1, hoof = -1;
  bool fore = true;
};

// A split bone's segments lie in one line (Rigify cuts a long bone exactly, DEF-thigh.L and
// DEF-thigh.L.001): a joint within this angle of straight between its bones is no bend of the limb.
inline constexpr float kInLineDeg = 1.0f;

// The joint carrying the humerus below a fore leg's scapula: the first joint on the way from `pivot`
// down to `upper` where the limb bends, or -1 where none does (a femur from the hip joint to the
// stifle, whole or in segments). The segments of a split bone (joints in line) are passed over.
int horseLegShoulder(const Skeleton& s, int pivot, int upper);

// Where the leg must go, in world: the hoof's sole centre and its orientation (the pastern fold, with
// the travel frame's heading and pitch).
struct HorseLegTarget {
  glm::vec3 hoof;
  glm::mat4 fold;
};

// Writes world matrices of the leg's joints (pivot down to hoof) into `world`, whose other entries
// (the pivot's parent in particular) must already be posed. Joints between the pivot (or shoulder) and
// the upper joint, a split bone's segments, are carried rigidly by the bone above them; joints below
// the upper joint that no member names are left to the caller to carry. Every joint is placed by a rotation and a
// translation that keep each bone its rest length: a target beyond the leg's reach (even with the hoof
// rolled) leaves the leg at its full reach, short of it. Returns how far short (cm): the distance from
// the fetlock where the solve put it to where the (rolled) target wants it; 0 within reach, up to the
// two-bone solve's softening (params.soften_cm) near it.
float solveHorseLeg(const Skeleton& s, const HorseLegJoints& leg, const HorseLegTarget& target,
                   const HorseLegParams& params, std::span<glm::mat4> world);

// The longest reach of the leg's virtual chain (pivot to fetlock, cm) before the hoof must roll.
float horseLegFullReach(const Skeleton& s, const HorseLegJoints& leg, const HorseLegParams& params);

}  // namespace stirrup::rig
