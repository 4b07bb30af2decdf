// The film a render produces: linear-light RGBA plus optional per-pixel passes (depth, character
// matte, object id), and writers for review PNGs (sRGB, 8-bit) and scene-linear EXRs (half float).
// Both writers write NAME.tmp and rename it over NAME, so an interrupted write never leaves a
// truncated file that looks complete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <variant>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/image_files/image_file.h"
#include "scene/camera.h"
#include "scene/png_compression.h"  // the compression levels writePng takes

namespace stirrup::render {

// The object id stored where a pixel saw only sky.
inline constexpr uint32_t kNoObject = std::numeric_limits<uint32_t>::max();

// std::allocator, except that a value-initialised element of a trivial type is left as it is: a
// vector resized with this allocator is not zeroed first (a frame's film, which the renderer writes
// pixel by pixel, is 3.7 MB at 640 x 360).
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  using std::allocator<T>::allocator;
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

struct Image {
  Image() = default;
  Image(int width, int height);  // colour only; black, alpha 0
  // Colour only, its pixels not set: for a caller that writes every one (the renderer).
  static Image unfilled(int width, int height);

  int width = 0, height = 0;
  // Linear scene-referred colour, row-major from the top-left. RGB already includes the sky where it
  // shows; alpha is the fraction of the pixel covered by ground or characters (0 over open sky).
  std::vector<glm::vec4, UninitializedAllocator<glm::vec4>> rgba;

  // Optional passes, each either empty or width * height long. Add new passes here; the EXR
  // writer stores every non-empty one as extra channels.
  std::vector<float> depth;         // nearest view-axis depth in cm over the pixel's samples; +inf: sky
  std::vector<float> matte;         // fraction of the pixel covered by the horse or the rider
  std::vector<glm::vec3> normal;    // mean world-space shading normal (unit; 0 over open sky)
  std::vector<uint32_t> object_id;  // the ObjectId most of the pixel's samples hit, or kNoObject

  glm::vec4& at(int x, int y) { return rgba[size_t(y) * size_t(width) + size_t(x)]; }
  const glm::vec4& at(int x, int y) const { return rgba[size_t(y) * size_t(width) + size_t(x)]; }
  size_t pixelCount() const { return size_t(width) * size_t(height); }
};

// The sRGB transfer function (IEC 61966-2-1) of a linear value, clamped to [0, 1].
float linearToSrgb(float linear);
// 8-bit sRGB code of a linear value, rounded to nearest: 0.5 -> 188, 0.18 -> 118.
uint8_t linearToSrgb8(float linear);
// linearToSrgb8 of the RGB of every pixel into `rgb` (3 bytes a pixel), the same bytes through a table
// instead of a pow per channel.
void encodeSrgb8(std::span<const glm::vec4> rgba, std::span<uint8_t> rgb);

// Review image: opaque 8-bit sRGB RGB (the sky is part of the picture; alpha is left out so viewers
// and movie encoders never show the sky as transparent), at compression level `compression` (0 to 9,
// zlib's scale; else std::invalid_argument), written by render/tracer/png_encoder.h. The folder must
// exist. Throws std::runtime_error on failure.
void writePng(const Image& image, const std::filesystem::path& file, int compression = scene::kReviewPngCompression);

// One attribute of an EXR header: a string, int, float, 3-vector (v3f) or 4x4 matrix (m44f).
using ExrAttribute = FileAttribute;
using ExrMetadata = std::vector<ExrAttribute>;

// Scene-linear OpenEXR: R, G, B, A as half float, plus for each pass the image has Z (float, cm along
// the view axis), matte (half), objectId (float holding the integer id: ground 0, horse 1, rider 2,
// -1 for sky) and N.x, N.y, N.z (half, world space); ZIP compressed. `metadata` becomes
// header attributes (e.g. {"stirrup:frame", 12}).
void writeExr(const Image& image, const std::filesystem::path& file, const ExrMetadata& metadata = {});

// RGBA as 32-bit float EXR: the exact linear pixels, for work handed from one process to another (a
// farm task's contact-sheet frames, read back by the job that makes the sheet). Written atomically like
// the others. readRgbaExr reads such a file back bit for bit; InputError naming the file when it cannot.
void writeRgbaExr(const Image& image, const std::filesystem::path& file);
Image readRgbaExr(const std::filesystem::path& file);

// The header attributes that let a compositor line up a frame: the camera (projection, position,
// target, vertical fov in degrees or ortho height in cm, and the standard worldToCamera matrix),
// the frame, its time in seconds and the scene's name, under "stirrup:" names.
ExrMetadata exrFrameMetadata(const scene::Camera& camera, const std::string& camera_name, int frame, double time_s,
                             const std::string& scene_name);

}  // namespace stirrup::render
