// Analytic two-bone IK (hip-knee-ankle, shoulder-elbow-wrist, elbow-carpus-fetlock). The bend plane
// holds the root, the target and a pole point; the middle joint bends toward the pole, so a knee
// points where its pole says and never flips when the limb passes through straight.
#pragma once

#include <glm/glm.hpp>

namespace stirrup::rig {

struct TwoBoneIkInput {
  glm::vec3 root{0.0f};      // fixed: where the upper bone starts
  float upper_length = 1.0f; // root -> middle
  float lower_length = 1.0f; // middle -> end
  glm::vec3 target{0.0f};    // where the end should be
  glm::vec3 pole{0.0f};      // a point the middle joint bends toward
  // Reach softening (cm): targets farther than (upper + lower - soften) are approached along an
  // exponential so the limb never snaps straight; 0 = hard clamp at full reach, exact elsewhere.
  float soften = 0.0f;
  // Closest the end may come to the root, as a fraction of the shortest possible distance, so the
  // limb never folds flat onto itself.
  float min_reach_fraction = 1.05f;
};

struct TwoBoneIkResult {
  glm::vec3 middle{0.0f};
  glm::vec3 end{0.0f};
  glm::vec3 bend_normal{0.0f, 0.0f, 1.0f};  // unit normal of the bend plane
  bool reached = false;                     // end within 1e-3 cm of target
};

TwoBoneIkResult solveTwoBoneIk(const TwoBoneIkInput& in);

// The rotation taking a bone that pointed along rest_dir with its bend plane normal rest_normal
// to one along dir with normal normal. Used to orient IK bones without twisting them.
glm::mat3 boneRotation(glm::vec3 rest_dir, glm::vec3 rest_normal, glm::vec3 dir, glm::vec3 normal);

// A pole point at rest: the middle joint pushed `distance` away from the root-end chord, so the limb
// keeps bending the way it bends at rest.
glm::vec3 restPole(glm::vec3 root, glm::vec3 middle, glm::vec3 end, float distance);

// A two-bone limb posed from its rest: world matrices of the chain's root and middle joints (joints
// with identity bind orientation, so a world matrix is translate(position) * rotation from rest).
struct LimbPose {
  glm::mat4 upper, middle;
  glm::vec3 end;  // where the end joint landed
};
// Rest positions (bind world) and rest pole given; the posed root, target and pole in world. Bones
// turn from their rest orientation without twist.
LimbPose solveLimb(glm::vec3 rest_root, glm::vec3 rest_middle, glm::vec3 rest_end, glm::vec3 rest_pole,
                   glm::vec3 root, glm::vec3 target, glm::vec3 pole, float soften);

}  // namespace stirrup::rig
