// Reading a glTF file and its accessors: the checked reads every glTF reader here shares (characters,
// terrain meshes). A bad file or accessor is a rig::InputError naming `where`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rig/error.h"

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

// The images of a file as it holds them (PNG or JPEG bytes), by image index, and why any could not be
// decoded. An image tinygltf could not find (an external file missing) has no bytes and no error.
struct GltfImageBytes {
  std::vector<std::vector<unsigned char>> encoded;
  std::vector<std::string> errors;  // empty where the image decoded
};

// The file (.glb binary, else JSON); "WHERE: not a readable glTF file (REASON)" if tinygltf refuses it.
// With `images`, the images' encoded bytes are kept there, and an image that does not decode leaves
// its tinygltf::Image empty (with the reason in `images->errors`) instead of failing the whole file:
// only a texture that is used is an error.
tinygltf::Model readGltfFile(const std::filesystem::path& file, const std::string& where,
                             GltfImageBytes* images = nullptr);
// Element `index` of one of the model's arrays (meshes, materials, accessors, ...), or a one-line
// InputError naming where the index came from: "x.glb: nodes[4].mesh: 7: no such mesh (the file has 2)".
template <class T>
const T& gltfElement(const std::vector<T>& list, int index, const std::string& where, const char* what) {
  if (index < 0 || static_cast<std::size_t>(index) >= list.size())
    throw InputError(where + ": " + std::to_string(index) + ": no such " + what + " (the file has " + std::to_string(list.size()) + ")");
  return list[static_cast<std::size_t>(index)];
}

// An accessor as floats (float, or normalised/unnormalised integers), `components` per element.
std::vector<float> readAccessor(const tinygltf::Model& model, int index, int components, const std::string& where);
// An index accessor (unsigned byte, short or int) as 32-bit indices.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& where);

}  // namespace stirrup::rig
