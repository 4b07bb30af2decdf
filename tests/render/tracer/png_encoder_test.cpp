#include "render/tracer/png_encoder.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>
#include <zlib.h>

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

// Scanlines of a width x height image whose every byte differs from its neighbours' (a filter byte 0
// before each row), so a reader that drops, shifts or repeats a byte cannot match them.
std::vector<uint8_t> scanlinesOf(int width, int height) {
  std::vector<uint8_t> lines;
  for (int y = 0; y < height; ++y) {
    lines.push_back(0);
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) lines.push_back(uint8_t((x * 7 + y * 13 + c * 101) % 251));
  }
  return lines;
}

std::vector<uint8_t> pixelsOf(const std::vector<uint8_t>& lines, int width, int height) {
  std::vector<uint8_t> px;
  for (int y = 0; y < height; ++y) {
    const auto row = lines.begin() + std::ptrdiff_t(y * pngScanlineBytes(width) + 1);
    px.insert(px.end(), row, row + 3 * width);
  }
  return px;
}

fs::path written(const std::vector<uint8_t>& png, const std::string& name) {
  const fs::path file = fs::temp_directory_path() / ("stirrup_png_encoder_" + name + ".png");
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  return file;
}

uint32_t bigEndian(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

struct Chunk {
  std::string type;
  std::vector<uint8_t> data;
};

// The file's chunks, each CRC checked with zlib's crc32 (not the encoder's libdeflate).
std::vector<Chunk> chunksOf(const std::vector<uint8_t>& png) {
  const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(png.size() >= 8 && std::equal(signature, signature + 8, png.begin()));
  std::vector<Chunk> chunks;
  for (std::size_t at = 8; at < png.size();) {
    EXPECT_LE(at + 12, png.size());
    if (at + 12 > png.size()) break;
    const uint32_t length = bigEndian(&png[at]);
    EXPECT_LE(at + 12 + length, png.size());
    if (at + 12 + length > png.size()) break;
    Chunk c{std::string(png.begin() + std::ptrdiff_t(at + 4), png.begin() + std::ptrdiff_t(at + 8)),
            std::vector<uint8_t>(png.begin() + std::ptrdiff_t(at + 8), png.begin() + std::ptrdiff_t(at + 8 + length))};
    EXPECT_EQ(bigEndian(&png[at + 8 + length]), uint32_t(crc32(0L, &png[at + 4], uInt(4 + length)))) << c.type;
    chunks.push_back(std::move(c));
    at += 12 + length;
  }
  return chunks;
}

// Another PNG reader (OpenImageIO's, libpng and zlib) reads every level back as the same pixels, in
// sRGB, at sizes whose rows are no whole number of words.
TEST(PngEncoder, AnotherReaderReadsEveryLevelAsTheSamePixels) {
  for (const auto& [w, h] : {std::pair{1, 1}, {7, 5}, {641, 3}, {3, 300}}) {
    const std::vector<uint8_t> lines = scanlinesOf(w, h);
    for (const int level : {0, 1, 6, 9, kPngDeflateLevelMax}) {
      const fs::path file = written(encodePngRgb8(lines, w, h, level), "read");
      auto in = OIIO::ImageInput::open(file.string());
      ASSERT_TRUE(in) << OIIO::geterror();
      const OIIO::ImageSpec& spec = in->spec();
      EXPECT_EQ(spec.width, w);
      EXPECT_EQ(spec.height, h);
      ASSERT_EQ(spec.nchannels, 3);
      EXPECT_EQ(spec.format, OIIO::TypeDesc::UINT8);
      EXPECT_EQ(spec.get_string_attribute("oiio:ColorSpace"), "sRGB");
      std::vector<uint8_t> px(std::size_t(w) * std::size_t(h) * 3);
      ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data())) << in->geterror();
      EXPECT_EQ(px, pixelsOf(lines, w, h)) << w << "x" << h << " level " << level;
      in->close();
      fs::remove(file);
    }
  }
}

// The chunks the specification asks for, in its order, each CRC right; the IDAT inflates (zlib) to
// the scanlines as given; the sRGB chunk with the gAMA and cHRM that stand for it.
TEST(PngEncoder, TheFileIsTheSpecificationsChunks) {
  const int w = 33, h = 17;
  const std::vector<uint8_t> lines = scanlinesOf(w, h);
  const std::vector<Chunk> chunks = chunksOf(encodePngRgb8(lines, w, h, 1));
  ASSERT_EQ(chunks.size(), 6u);
  EXPECT_EQ(chunks[0].type, "IHDR");
  EXPECT_EQ(chunks[0].data, (std::vector<uint8_t>{0, 0, 0, 33, 0, 0, 0, 17, 8, 2, 0, 0, 0}));
  EXPECT_EQ(chunks[1].type, "gAMA");
  EXPECT_EQ(bigEndian(chunks[1].data.data()), 45455u);  // 1 / 2.2
  EXPECT_EQ(chunks[2].type, "sRGB");
  EXPECT_EQ(chunks[2].data.size(), 1u);
  EXPECT_EQ(chunks[3].type, "cHRM");
  ASSERT_EQ(chunks[3].data.size(), 32u);
  EXPECT_EQ(bigEndian(&chunks[3].data[0]), 31270u);   // D65 white x
  EXPECT_EQ(bigEndian(&chunks[3].data[28]), 6000u);   // the blue primary's y
  EXPECT_EQ(chunks[4].type, "IDAT");
  std::vector<uint8_t> inflated(lines.size() + 16);
  uLongf size = inflated.size();
  ASSERT_EQ(uncompress(inflated.data(), &size, chunks[4].data.data(), uLong(chunks[4].data.size())), Z_OK);
  inflated.resize(size);
  EXPECT_EQ(inflated, lines);
  EXPECT_EQ(chunks[5].type, "IEND");
  EXPECT_TRUE(chunks[5].data.empty());
}

// Level 0 stores the scanlines (the file holds all of them); a compressing level makes a file of
// flat colour far smaller, and a higher one no larger.
TEST(PngEncoder, LevelZeroStoresAndTheOthersCompress) {
  const int w = 200, h = 100;
  std::vector<uint8_t> flat(std::size_t(h) * pngScanlineBytes(w), 0);
  for (std::size_t i = 0; i < flat.size(); ++i)
    if (i % pngScanlineBytes(w) != 0) flat[i] = 120;
  const std::size_t stored = encodePngRgb8(flat, w, h, 0).size();
  const std::size_t fast = encodePngRgb8(flat, w, h, 1).size();
  const std::size_t best = encodePngRgb8(flat, w, h, 9).size();
  EXPECT_GE(stored, flat.size());
  EXPECT_LT(fast * 20, stored);
  EXPECT_LE(best, fast);
}

TEST(PngEncoder, ASizeOrLevelItCannotWriteIsAnError) {
  const std::vector<uint8_t> lines = scanlinesOf(4, 3);
  EXPECT_THROW(encodePngRgb8(lines, 4, 4, 1), std::invalid_argument);   // too few bytes
  EXPECT_THROW(encodePngRgb8(lines, 3, 3, 1), std::invalid_argument);   // too many
  EXPECT_THROW(encodePngRgb8(lines, 0, 3, 1), std::invalid_argument);
  EXPECT_THROW(encodePngRgb8(lines, 4, -3, 1), std::invalid_argument);
  EXPECT_THROW(encodePngRgb8(lines, 4, 3, -1), std::invalid_argument);
  EXPECT_THROW(encodePngRgb8(lines, 4, 3, kPngDeflateLevelMax + 1), std::invalid_argument);
  EXPECT_NO_THROW(encodePngRgb8(lines, 4, 3, kPngDeflateLevelMax));
}

}  // namespace
}  // namespace stirrup::render
