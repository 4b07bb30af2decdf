// Ground read from glTF, in stirrup's world (cm, Y up), as a triangle mesh the horse walks on
// (rig/motion/terrain_mesh.h: the highest surface over a point):
//  - a terrain file another tool made (issue 15: `"terrain": {"file": "ground.glb"}`): every triangle
//    primitive of every node, placed by its node's world transform, in glTF's metres turned into
//    centimetres;
//  - a shot's own ground (issue 60): the meshes a baked shot, or another tool's export of one, names
//    as its ground. A node is the ground when its name, or the name of a node above it, is `ground`
//    or begins with `ground` and then `_`, `.` or `-` (any case): `stirrup bake` writes its terrain as
//    node "ground" holding "ground_mesh", Blender keeps those names on a re-export, and an object a user
//    names "Ground" or "ground.001" in Blender is one too. Skinned meshes (the characters) never are.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include <glm/mat4x4.hpp>

#include "rig/motion/terrain_mesh.h"

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

// Throws rig::InputError, one line starting "FIELD: FILE: ", for a missing or unreadable file, a
// broken node hierarchy or accessor, a non-finite vertex, or no triangles. `field` names where the
// file was given (e.g. "scene.json: terrain.file").
std::shared_ptr<const TerrainMesh> loadTerrainGltf(const std::filesystem::path& file, const std::string& field);

// Whether a node's own name makes it (and what hangs below it) the ground (above).
bool isGroundNodeName(const std::string& name);

// The ground meshes of a file already read: their triangles through `file_to_rig` (the file's world,
// after its nodes' transforms, to stirrup's cm); null when no node is named as the ground. Errors name
// `where` (the file): a broken accessor, a non-finite vertex, ground nodes without a triangle.
std::shared_ptr<const TerrainMesh> gltfGroundMesh(const tinygltf::Model& model, const std::string& where, const glm::dmat4& file_to_rig);

}  // namespace stirrup::rig
