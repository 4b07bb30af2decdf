// Reading a glTF file and its accessors: the checked reads every glTF reader here shares (characters,
// terrain meshes). A bad file or accessor is a stirrup::InputError naming `where`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

// The file (.glb binary, else JSON); "WHERE: not a readable glTF file (REASON)" if tinygltf refuses it.
tinygltf::Model readGltfFile(const std::filesystem::path& file, const std::string& where);
// An accessor as floats (float, or normalised/unnormalised integers), `components` per element.
std::vector<float> readAccessor(const tinygltf::Model& model, int index, int components, const std::string& where);
// An index accessor (unsigned byte, short or int) as 32-bit indices.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& where);

}  // namespace stirrup::rig
