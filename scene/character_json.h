// A scene's character entry, read the one way a scene's "characters" block and a crowd's name a horse or
// a rider (docs/characters.md): "default" (the built-in generator), a glTF file (relative to the scene
// file) carrying its role table, or {"file": ..., "mapping": ...} for a user's character with its mapping
// file. Files that do not exist are one-line errors naming the field.
#pragma once

#include <filesystem>
#include <string>

#include "rig/io/json_fields.h"

namespace stirrup::scene {

struct CharacterEntry {
  std::string file = "default";  // "default", or the file's path (the scene's folder resolved)
  std::string mapping;           // the mapping file's path, or empty
};

// The entry `key` of `r` (absent: `fallback`); files resolve against `dir`.
CharacterEntry parseCharacterEntry(rig::JsonObjectReader& r, const std::string& key, const std::filesystem::path& dir,
                                   const CharacterEntry& fallback = {});

}  // namespace stirrup::scene
