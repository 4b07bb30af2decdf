// The film a render produces: linear-light RGBA plus optional per-pixel passes (depth, character
// matte, object id), and writers for review PNGs (sRGB, 8-bit) and scene-linear EXRs (half float).
// Both writers write NAME.tmp and rename it over NAME, so an interrupted write never leaves a
// truncated file that looks complete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

namespace stirrup::render {

// The object id stored where a pixel saw only sky.
inline constexpr uint32_t kNoObject = std::numeric_limits<uint32_t>::max();

struct Image {
  Image() = default;
  Image(int width, int height);  // colour only; black, alpha 0

  int width = 0, height = 0;
  // Linear scene-referred colour, row-major from the top-left. RGB already includes the sky where it
  // shows; alpha is the fraction of the pixel covered by ground or characters (0 over open sky).
  std::vector<glm::vec4> rgba;

  // Optional passes, each either empty or width * height long. Add new passes here; the EXR
  // writer stores every non-empty one as extra channels.
  std::vector<float> depth;         // nearest view-axis depth in cm over the pixel's samples; +inf: sky
  std::vector<float> matte;         // fraction of the pixel covered by the horse or the rider
  std::vector<uint32_t> object_id;  // the ObjectId most of the pixel's samples hit, or kNoObject

  glm::vec4& at(int x, int y) { return rgba[size_t(y) * size_t(width) + size_t(x)]; }
  const glm::vec4& at(int x, int y) const { return rgba[size_t(y) * size_t(width) + size_t(x)]; }
  size_t pixelCount() const { return size_t(width) * size_t(height); }
};

// The sRGB transfer function (IEC 61966-2-1) of a linear value, clamped to [0, 1].
float linearToSrgb(float linear);
// 8-bit sRGB code of a linear value, rounded to nearest: 0.5 -> 188, 0.18 -> 118.
uint8_t linearToSrgb8(float linear);

// Review image: opaque 8-bit sRGB RGB (the sky is part of the picture; alpha is left out so viewers
// and movie encoders never show the sky as transparent). Throws std::runtime_error on failure.
void writePng(const Image& image, const std::filesystem::path& file);

// Scene-linear OpenEXR: R, G, B, A as half float, plus Z (float, cm), matte (half) and objectId
// (float holding the integer id, -1 for none) for each pass the image has; ZIP compressed.
// `metadata` pairs become string attributes in the header (e.g. {"stirrup:frame", "12"}).
using ExrMetadata = std::vector<std::pair<std::string, std::string>>;
void writeExr(const Image& image, const std::filesystem::path& file, const ExrMetadata& metadata = {});

}  // namespace stirrup::render
