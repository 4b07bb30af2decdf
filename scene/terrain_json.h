// A scene's "terrain" (issue 15): what the horse walks on and the renderer draws.
//   "terrain": {"hills": {"seed": 3, "amplitude_cm": 120, "wavelength_cm": 3000, "octaves": 2}}
//   "terrain": {"file": "ground.glb"}      a glTF mesh, heights read from its triangles
// Absent: flat ground at height 0.
#pragma once

#include <filesystem>
#include <memory>

#include "rig/io/json_fields.h"
#include "rig/motion/terrain.h"

namespace stirrup::scene {

// Reads the terrain object `r` (already the "terrain" field's reader); errors name the file and field.
// Relative files resolve against base_dir.
std::shared_ptr<const rig::Terrain> parseTerrain(rig::JsonObjectReader& r, const std::filesystem::path& base_dir);

}  // namespace stirrup::scene
