// A PNG file of 8-bit RGB pixels, made whole in memory: the review frames' writer (writePng,
// render/tracer/image.h). Deflated by libdeflate rather than written through OpenImageIO's libpng and
// zlib: at level 1 libdeflate deflates a 640x360 review frame in about half zlib's time, and a draft
// frame stored (level 0) is little more than two checksums, which libdeflate computes with the CPU's
// carry-less multiply (docs/performance-history.md, "The frames' write"). Any PNG reader opens the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace stirrup::render {

// libdeflate's levels: 0 (stored) to 12 (smallest); 1 to 9 compare with zlib's.
inline constexpr int kPngDeflateLevelMax = 12;

// Bytes of one row of the scanlines encodePngRgb8 takes: its filter-type byte and 3 bytes a pixel.
constexpr std::size_t pngScanlineBytes(int width) { return 1 + 3 * std::size_t(width); }

// The whole file of a `width` x `height` 8-bit RGB image in the sRGB colour space (IHDR; sRGB with the
// gAMA and cHRM that stand for it in older readers; one IDAT; IEND). `scanlines` are the rows as PNG's
// filter stage leaves them, height * pngScanlineBytes(width) bytes: each row's filter type first (0
// for none, the only one a caller needs: the frames compress as well without filters, faster), then
// its pixels. Throws std::invalid_argument for a size that does not match or a level outside 0 to 12.
std::vector<uint8_t> encodePngRgb8(std::span<const uint8_t> scanlines, int width, int height, int level);

}  // namespace stirrup::render
