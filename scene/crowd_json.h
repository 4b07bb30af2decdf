// A scene's crowd (issue 19; rig/motion/crowd.h), either generated or listed pair by pair:
//   "crowd": {"pairs": 30, "seed": 7,
//             "lead": {"points": [[0, 0], [4000, 600], ...], "speed": [[0, 560], [4, 560], [6, 900]]},
//             "formation": {"files": 6, "file_spacing_cm": 260, "rank_spacing_cm": 700, "jitter_cm": 15},
//             "speed_variation": 0.01, "start_offset_max_s": 1, "profiles": {"thesis": 2, "novice": 1},
//             "withers_height_cm": [145, 175], "rider_height_cm": [150, 190], "rider_build": [0.85, 1.25],
//             "gait_variation": 0.1}
//   "riders": [{"points": [[x, z], ...], "speed": [[s, cm/s], ...], "speed_over": "time", "start_offset_s": 0.3,
//               "profile": "english", "seed": 3, "variation": 0.1, "withers_height_cm": 160,
//               "rider_height_cm": 170, "rider_build": 1, "coat": "grey", "jacket": "navy", "hair": "blonde",
//               "skin": "olive"}, ...]
// Colours are names (rig/characters/palette.h); a generated crowd draws them for each pair.
// These read the fields and their types (unknown fields and wrong types are one-line errors naming the
// file and field); the values are checked by generateCrowd and validatePairs.
#pragma once

#include <vector>

#include "rig/io/json_fields.h"
#include "rig/motion/crowd.h"

namespace stirrup::scene {

rig::CrowdSpec parseCrowdSpec(rig::JsonObjectReader& r);
rig::PairSpec parsePairSpec(rig::JsonObjectReader& r);

}  // namespace stirrup::scene
