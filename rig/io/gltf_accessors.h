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
// An accessor as floats (float, or normalised/unnormalised integers), `components` per element.
std::vector<float> readAccessor(const tinygltf::Model& model, int index, int components, const std::string& where);
// An index accessor (unsigned byte, short or int) as 32-bit indices.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& where);

}  // namespace stirrup::rig
