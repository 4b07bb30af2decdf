// The rider's spine as posing reads it from her skeleton (docs/curve-spine.md, "The rider"): the
// chain of joints from her pelvis up toward her neck that the curve spine (Raisani 2004, Part III)
// bends, and where its three FK controllers (lowerBack, waist, chest) sit.
//
// Two kinds of chain:
//  * laid on the curve: the generator's rider (rig/characters/rider_character.h) has a chain of
//    kRiderSpineSegments equal bones straight up from the lower back and its controllers as joints of
//    their own; posing lays every chain joint on the curve at equal arc length, as Raisani's rig does.
//  * any other chain (a user's rider: one to many spine joints, bones of their own lengths, a rest
//    curve of their own): each bone turns with the curve's frame at its middle (CurveSpine::framesAt)
//    from its rest direction, so every bone keeps its length and at rest the chain is exactly where
//    the file put it. The controllers are then points on the curve: at the joints the lowerBack /
//    waist / chest roles name when those lie on the chain, else at thirds of its length.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"

namespace stirrup::rig {

struct RiderSpine {
  int pelvis = -1, neck = -1;
  std::vector<int> chain;               // the pelvis's child on the way to the neck .. the chain's top, root first
  // The chain ends at upperChest, or without that role at the joint the neck hangs from, and the neck
  // rides on its tip; a spine of a single joint instead bends its one bone, from it to the neck.
  bool ends_at_neck = false;
  std::vector<glm::dvec3> points;       // rest places along the chain, pelvis frame: chain joints (+ the neck)
  std::vector<double> arc;              // rest arc length of each point from the first (cm)
  std::array<int, 3> controllers{-1, -1, -1};  // lowerBack, waist, chest joints posed as the FK controllers
  std::array<double, 3> fk_lengths{};   // the three FK bones: the chain's rest length split at the controllers
  glm::vec3 root{0.0f};                 // chain[0] in the pelvis's frame at rest
  bool laid_on_curve = false;           // the generator's chain (see the header comment)
};

// Reads the spine from the rider's roles: pelvis, neck and, when present, upperChest, lowerBack, waist
// and chest. Throws std::invalid_argument naming the role and the joint when the neck does not hang
// below the pelvis or upperChest is not on the way between them.
RiderSpine riderSpine(const Character& rider);

}  // namespace stirrup::rig
