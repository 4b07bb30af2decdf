// Reads a character mapping file (rig/mapping/character_mapping.h says what it holds): a JSON object
//
//   {"character": "horse", "scale_cm": 1, "forward": [1, 0, 0], "up": [0, 1, 0], "offset_cm": [0, 0, 0],
//    "roles": {"root": "Hips", "saddle": "Saddle", ...}}
//
// Unknown fields are errors, each a one-line InputError naming the file and the field.
#pragma once

#include <filesystem>

#include "rig/mapping/character_mapping.h"

namespace stirrup::rig {

// Reads a mapping file for a character of `kind` ("character" in the file, when present, must
// match). A role missing from "roles" is a one-line InputError naming the file and the role.
CharacterMapping loadCharacterMapping(const std::filesystem::path& file, CharacterKind kind);

}  // namespace stirrup::rig
