// A glTF file's skin as the mapping reads it (rig/mapping/mapping_skeleton.h): the joints' names, bind
// places and hierarchy as the importer (rig/io/gltf_character.h) gives them, the joints that carry skin
// weight, the bind-pose mesh and a VRM file's own humanoid bone table; and a character file mapped
// automatically (rig/mapping/auto_mapping.h). The mapping itself reads no file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "rig/mapping/auto_mapping.h"
#include "rig/mapping/mapping_skeleton.h"

namespace tinygltf {
class Model;
struct Skin;
}

namespace stirrup::rig {

// The names the importer gives skin `skin`'s joints (the first, unless told): each node's name, or
// "jointN" (N the joint's index in the skin) for a joint without a name or with the name of an earlier
// joint, so every joint has a name of its own a mapping file can use.
std::vector<std::string> gltfJointNames(const tinygltf::Model& model, int skin = 0);

// Reads skin `skin` of a model the importer would read (checked as it checks it: a one-line
// InputError naming `file` for a bad index, accessor or hierarchy).
MappingSkeleton mappingSkeletonFromGltf(const tinygltf::Model& model, const std::string& file, int skin = 0);

// The file's skin `skin` (the first, unless told), checked: it exists, has joints, and every joint is a
// node of the file. Throws InputError naming `file` and what is wrong ("expected a skinned `what`").
const tinygltf::Skin& checkedSkin(const tinygltf::Model& model, const std::string& file, const std::string& what, int skin = 0);

// Skin `skin`'s inverse bind matrices, one per joint (identity where the skin has none). InputError
// naming `file` and the accessor when it holds another count.
std::vector<glm::mat4> gltfInverseBinds(const tinygltf::Model& model, const std::string& file, int skin);

// Reads the file (.glb or .gltf) and maps it.
AutoMapping autoMapCharacterFile(const std::filesystem::path& file, CharacterKind kind, const AutoMappingParams& params = {});

}  // namespace stirrup::rig
