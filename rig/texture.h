// A base colour texture (glTF 2.0, "Textures", "Samplers" and the metallic-roughness material's
// baseColorTexture): an image decoded to linear RGB once, at load, with
// its sampler's wrap modes and filter, and the lookup the renderer makes at a hit's texture coordinates.
//
// Conventions are glTF's: (u, v) = (0, 0) is the image's top-left corner, (1, 1) its bottom-right;
// texel (x, y) covers [x, x + 1) / width by [y, y + 1) / height, its centre at (x + 0.5) / width.
// There are no mip-maps: a lookup reads one texel (nearest) or four (bilinear), and a minified texture
// is averaged by the pixel's camera samples instead (docs/characters.md, "Textures").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace stirrup::rig {

// A sampler's wrapS / wrapT (the numbers are OpenGL's, as a glTF file holds them).
enum class TextureWrap { Repeat = 10497, ClampToEdge = 33071, MirroredRepeat = 33648 };
// How a lookup between texel centres reads the image.
enum class TextureFilter { Linear, Nearest };

struct Texture {
  std::string name;
  int width = 0, height = 0;
  std::vector<glm::vec3> texels;  // linear RGB, row-major from the image's top-left (width * height)
  TextureWrap wrap_s = TextureWrap::Repeat, wrap_t = TextureWrap::Repeat;
  TextureFilter filter = TextureFilter::Linear;
  // The image as the file held it (PNG or JPEG bytes) and its MIME type: a character written out
  // carries the very image it was read with, not a re-encoding of the decoded texels.
  std::vector<unsigned char> encoded;
  std::string mime_type;

  // The colour at (u, v), wrapped and filtered as the sampler says. Pure scalar arithmetic (double for
  // the texel coordinates), so every run, thread and SIMD target gets the same bits.
  glm::vec3 sample(glm::vec2 uv) const;
  // Texel (x, y) after wrapping x and y into the image.
  glm::vec3 texel(std::int64_t x, std::int64_t y) const;
};

// The sRGB transfer function undone (IEC 61966-2-1): the linear value of an encoded one in [0, 1].
double srgbToLinear(double encoded);
// srgbToLinear of every 8-bit code, as float: the table 8-bit images decode through.
const std::vector<float>& srgb8ToLinearTable();
// Texel index i (any integer) wrapped into [0, n) by `wrap`.
std::int64_t wrapTexel(std::int64_t i, std::int64_t n, TextureWrap wrap);

}  // namespace stirrup::rig
