// Base colour textures in glTF (docs/characters.md, "Textures"): reading the texture a material names
// into a rig::Texture, and writing one back. Offline jobs of the character reader and writer.
//
// Read: the material's pbrMetallicRoughness.baseColorTexture (its texCoord set, and KHR_texture_transform's
// offset, rotation, scale and texCoord when present), the texture's image decoded once to linear RGB
// (the glTF spec's sRGB transfer undone), its sampler's wrapS / wrapT and filter. Written: the image's
// own bytes as a buffer view, a sampler and a texture.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include "rig/io/gltf_accessors.h"
#include "rig/texture.h"

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

// Which texture a material's base colour reads, and through which texture coordinates.
struct GltfTextureRef {
  int texture = -1;   // index into the file's textures; -1: the material has no base colour texture
  int tex_coord = 0;  // the TEXCOORD_n set
  glm::mat3 uv_transform{1.0f};  // KHR_texture_transform, applied to the set's coordinates (identity without)

  glm::vec2 transform(glm::vec2 uv) const { return glm::vec2(uv_transform * glm::vec3(uv, 1.0f)); }
  // Whether `other` reads the same texture coordinates (set and transform), whatever its texture.
  bool sameCoordinates(const GltfTextureRef& other) const {
    return tex_coord == other.tex_coord && uv_transform == other.uv_transform;
  }
};

// The base colour texture of materials[material]. InputError naming `where` (the file and material)
// for a texture index out of range or an unreadable KHR_texture_transform.
GltfTextureRef baseColorTextureOf(const tinygltf::Model& model, int material, const std::string& where);

// textures[texture] of the model, its image decoded (`images`: readGltfFile's). InputError naming
// `where` when its image is missing, not decodable or not PNG / JPEG, or its sampler is out of range
// or has a wrap glTF does not define.
std::shared_ptr<const Texture> readGltfTexture(const tinygltf::Model& model, const GltfImageBytes& images, int texture,
                                               const std::string& where);

// Appends `texture` to `model`: its encoded image as a buffer view of `bin` (buffer 0), a sampler with
// its wraps and filter, and a texture. Returns the texture's index. Throws std::invalid_argument for a
// texture with no encoded image (textures come from files, which always have one).
int appendGltfTexture(tinygltf::Model& model, std::vector<unsigned char>& bin, const Texture& texture,
                      const std::string& name);

}  // namespace stirrup::rig
