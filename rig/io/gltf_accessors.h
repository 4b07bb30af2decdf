// Reading a glTF file's accessors: the checked reads every glTF reader here shares (characters,
// terrain meshes). A bad accessor is a stirrup::InputError naming `where`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

// An accessor as floats (float, or normalised/unnormalised integers), `components` per element.
std::vector<float> readAccessor(const tinygltf::Model& model, int index, int components, const std::string& where);
// An index accessor (unsigned byte, short or int) as 32-bit indices.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& where);

}  // namespace stirrup::rig
