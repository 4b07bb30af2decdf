// A crowd's own characters (issue 60: a troop of the user's horse). Pairs that name a horse or rider
// file (rig::PairSpec::horse_file, rider_file: a crowd's "characters" entries, or a "riders" entry's
// "horse" and "rider") are resolved before the pairs are checked, each as a single pair's characters
// are (scene/ridden_pair.h):
//   - each file read once (rig::resolveCharacter, through its mapping), shared by the pairs naming it;
//   - a pair without a rider file rides the generated rider at its own proportions and colours, without
//     a horse file the generated horse at its own;
//   - the rider seated on the horse with the pair's own profile (scene::seatPair: a standing rider seated
//     by the rig, a seated one fitted to a horse she was not built for, the leathers set to her leg);
//   - the box the pair takes at rest (rig::pairExtent of the seated characters), for the crowd's
//     footprint check;
//   - a pair naming "animation" plays its horse's own keyed animation (rig/io/keyed_horse_clip.h, the
//     joints exactly as keyed) from its slot, facing the lead's way (or along its path), at its own
//     start phase (rig/motion/placed_clip.h); the others ride a gait along their paths, the hooves
//     turned about this horse's rest places. An animation is keyed on flat ground: a crowd over hills
//     rides the generated gait.
#pragma once

#include <string>
#include <vector>

#include "rig/motion/crowd.h"

namespace stirrup::scene {

struct SceneSpec;

// Resolves every pair of `pairs` that names its own characters (rig::PairSpec::characters), with the
// profiles and ground of `scene` (as far as it is read). Errors are one-line InputErrors naming the scene
// file and `field` ("crowd.characters", "riders").
void resolvePairCharacters(std::vector<rig::PairSpec>& pairs, const SceneSpec& scene, const std::string& field);

}  // namespace stirrup::scene
