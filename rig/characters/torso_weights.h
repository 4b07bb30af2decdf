// Spreading a generated body's torso weights along its spine chain, so a bent chain bends the torso
// smoothly instead of at a few joints. The seated rider (rig/characters/rider_character.cpp) and the
// standing humanoid (rig/characters/standing_humanoid.cpp) both skin their trunk this way.
#pragma once

#include <span>

#include "rig/mesh.h"

namespace stirrup::rig {

// The spine chain, bottom up, and where its bones' middles lie (heights, cm). Bone k runs from
// joints[k] to the next joint up. Either evenly spaced, bone k's middle at y0 + (k + ½)·bone (the
// seated rider: the tip joint's bone half a bone above the chain), or listed in `middles`, one a joint
// (the standing humanoid: its last bone runs to the neck).
struct TorsoChain {
  std::span<const int> joints;
  float y0 = 0.0f, bone = 0.0f;   // evenly spaced, when `middles` is empty
  std::span<const float> middles;
};

// Linear blend weights along the chain: each vertex keeps its weights on joints off the chain (pelvis,
// shoulders, neck); the share it has on the chain is moved onto the two chain joints whose bones'
// middles bracket its height, linearly, clamped to the chain's ends. At most kMaxInfluences weights a
// vertex, the largest, normalised. Evenly spaced, both bracketing joints are listed, the upper one with
// an empty share at a bone's middle (a weight of 0 that may fill a free slot); by middles, the upper
// only with a share: as each generator always wrote its files, byte for byte.
void spreadTorsoWeights(SkinnedMesh& mesh, const TorsoChain& chain);

}  // namespace stirrup::rig
