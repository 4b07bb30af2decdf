// A terrain from a glTF file another tool made (issue 15: `"terrain": {"file": "ground.glb"}`): every
// triangle primitive of every node, placed by its node's world transform, in glTF's metres (Y up)
// turned into stirrup's centimetres. The horse walks on the highest surface (rig/motion/terrain_mesh.h).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "rig/motion/terrain_mesh.h"

namespace stirrup::rig {

// Throws stirrup::InputError, one line starting "FIELD: FILE: ", for a missing or unreadable file, a
// broken node hierarchy or accessor, a non-finite vertex, or no triangles. `field` names where the
// file was given (e.g. "scene.json: terrain.file").
std::shared_ptr<const TerrainMesh> loadTerrainGltf(const std::filesystem::path& file, const std::string& field);

}  // namespace stirrup::rig
