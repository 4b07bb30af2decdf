#include "render/tracer/png_encoder.h"

#include <array>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include <libdeflate.h>

namespace stirrup::render {
namespace {

// The PNG specification's constants (W3C Recommendation, second edition 2003; ISO/IEC 15948).
constexpr std::array<uint8_t, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr uint8_t kColourTypeRgb = 2;
// sRGB's rendering intent, and the gAMA (1/2.2 x 100 000) and cHRM (the sRGB primaries and D65 white,
// x and y x 100 000) the specification gives a writer of an sRGB chunk to write beside it; the values
// OpenImageIO's PNG writer wrote for these frames before.
constexpr uint8_t kSrgbIntent = 3;  // absolute colorimetric, as OpenImageIO writes it
constexpr uint32_t kGamma = 45455;
constexpr std::array<uint32_t, 8> kChromaticities = {31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000};

void putBigEndian(uint8_t* at, uint32_t v) {
  at[0] = uint8_t(v >> 24), at[1] = uint8_t(v >> 16), at[2] = uint8_t(v >> 8), at[3] = uint8_t(v);
}

// A chunk whose `size` data bytes are already at out[start + 8 ...]: its length and type before them,
// its CRC (of the type and the data) after.
void sealChunk(std::vector<uint8_t>& out, std::size_t start, const char (&type)[5], std::size_t size) {
  putBigEndian(&out[start], uint32_t(size));
  std::memcpy(&out[start + 4], type, 4);
  const uint32_t crc = libdeflate_crc32(0, &out[start + 4], 4 + size);
  out.resize(start + 8 + size + 4);
  putBigEndian(&out[start + 8 + size], crc);
}

void appendChunk(std::vector<uint8_t>& out, const char (&type)[5], std::span<const uint8_t> data) {
  const std::size_t start = out.size();
  out.resize(start + 8 + data.size());
  if (!data.empty()) std::memcpy(&out[start + 8], data.data(), data.size());
  sealChunk(out, start, type, data.size());
}

struct CompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

}  // namespace

std::vector<uint8_t> encodePngRgb8(std::span<const uint8_t> scanlines, int width, int height, int level) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("encodePngRgb8: the size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is not positive");
  }
  const std::size_t expected = std::size_t(height) * pngScanlineBytes(width);
  if (scanlines.size() != expected) {
    throw std::invalid_argument("encodePngRgb8: " + std::to_string(scanlines.size()) + " bytes of scanlines, expected " +
                                std::to_string(expected));
  }
  if (level < 0 || level > kPngDeflateLevelMax) {
    throw std::invalid_argument("encodePngRgb8: level " + std::to_string(level) + " is not 0 to 12");
  }
  const std::unique_ptr<libdeflate_compressor, CompressorDeleter> compressor(libdeflate_alloc_compressor(level));
  if (!compressor) throw std::bad_alloc();

  std::vector<uint8_t> out(kSignature.begin(), kSignature.end());
  std::array<uint8_t, 13> header{};
  putBigEndian(&header[0], uint32_t(width));
  putBigEndian(&header[4], uint32_t(height));
  header[8] = 8;  // bits a channel
  header[9] = kColourTypeRgb;
  // header[10..12]: deflate, adaptive filtering (each row names its filter), no interlace: all 0.
  appendChunk(out, "IHDR", header);
  std::array<uint8_t, 4> gamma{};
  putBigEndian(gamma.data(), kGamma);
  appendChunk(out, "gAMA", gamma);
  appendChunk(out, "sRGB", std::array<uint8_t, 1>{kSrgbIntent});
  std::array<uint8_t, 32> chromaticities{};
  for (std::size_t i = 0; i < kChromaticities.size(); ++i) putBigEndian(&chromaticities[4 * i], kChromaticities[i]);
  appendChunk(out, "cHRM", chromaticities);

  // One IDAT: the zlib stream deflated straight into the file's bytes.
  const std::size_t idat = out.size();
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor.get(), scanlines.size());
  out.resize(idat + 8 + bound + 4);
  const std::size_t deflated =
      libdeflate_zlib_compress(compressor.get(), scanlines.data(), scanlines.size(), &out[idat + 8], bound);
  if (deflated == 0 || deflated > 0x7fffffffu) {  // within the bound it cannot fail; a chunk holds < 2^31 bytes
    throw std::invalid_argument("encodePngRgb8: a " + std::to_string(width) + "x" + std::to_string(height) +
                                " image is too large for one PNG chunk");
  }
  sealChunk(out, idat, "IDAT", deflated);
  appendChunk(out, "IEND", {});
  return out;
}

}  // namespace stirrup::render
