// glTF extras written exactly as stirrup holds them. tinygltf 2.7 writes an empty array or object of a
// tinygltf::Value as null (its ValueToJson starts from a null json and only ever appends), so a seat
// record with no notes read back as `"notes": null`; every JSON a stirrup command writes has its empty
// lists as [] (issue 60). withExactExtras rewrites a GLB's JSON chunk with each node's, scene's,
// mesh's, material's and camera's extras converted here, where an empty list stays [].
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

namespace tinygltf {
class Model;
class Value;
}  // namespace tinygltf

namespace stirrup::rig {

// A tinygltf value as JSON: arrays and objects as they are, empty ones too; a binary value as null.
nlohmann::json extrasJson(const tinygltf::Value& value);

// `glb` (tinygltf's GLB of `model`) with its JSON chunk's extras replaced by extrasJson of the model's,
// wherever the model holds an empty array or object in them; otherwise `glb` as it is.
std::vector<unsigned char> withExactExtras(const tinygltf::Model& model, std::vector<unsigned char> glb);

}  // namespace stirrup::rig
