#include "render/tracer/image.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <filesystem>
#include <memory>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "rig/error.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  const fs::path dir = fs::temp_directory_path() / ("stirrup_image_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) img.at(x, y) = {float(x) / float(w - 1), float(y) / float(h - 1), 0.5f, 1.0f};
  }
  return img;
}

// A new image is black with alpha 0 even where the memory it gets held a picture before (its pixels
// are not zeroed by the vector: Image::unfilled leaves them for a renderer that writes every one), and
// an unfilled one has its size. Neither size may be zero or negative.
TEST(Image, ANewImageIsBlackAndAnUnfilledOneHasItsSize) {
  for (int round = 0; round < 3; ++round) {
    {
      Image before = Image::unfilled(64, 32);
      for (glm::vec4& p : before.rgba) p = glm::vec4(0.7f, 0.5f, 0.3f, 1.0f);
    }
    const Image image(64, 32);
    ASSERT_EQ(image.rgba.size(), 64u * 32u);
    for (const glm::vec4& p : image.rgba) ASSERT_EQ(p, glm::vec4(0.0f));
  }
  const Image unfilled = Image::unfilled(7, 5);
  EXPECT_EQ(unfilled.width, 7);
  EXPECT_EQ(unfilled.height, 5);
  EXPECT_EQ(unfilled.rgba.size(), 35u);
  EXPECT_TRUE(unfilled.depth.empty() && unfilled.object_id.empty());
  EXPECT_THROW(Image::unfilled(0, 5), std::invalid_argument);
  EXPECT_THROW(Image(4, -1), std::invalid_argument);
}

TEST(Image, SrgbEncodesKnownValues) {
  EXPECT_EQ(linearToSrgb8(0.0f), 0);
  EXPECT_EQ(linearToSrgb8(1.0f), 255);
  EXPECT_EQ(linearToSrgb8(0.5f), 188);
  EXPECT_EQ(linearToSrgb8(0.18f), 118);  // middle grey
  EXPECT_EQ(linearToSrgb8(0.002f), 7);   // the linear toe: 12.92 * 0.002 * 255 = 6.6
  EXPECT_EQ(linearToSrgb8(-1.0f), 0);
  EXPECT_EQ(linearToSrgb8(7.0f), 255);
  EXPECT_EQ(linearToSrgb8(std::nanf("")), 0);
  EXPECT_NEAR(linearToSrgb(0.214041f), 0.5f, 1e-5f);
}

// The table encoder gives the same byte as linearToSrgb8 for every float tried: a sweep of every 97th
// float in [0, 1] (about 11 million), both sides of every code's step, and the edge cases.
TEST(Image, TableSrgbEncoderMatchesThePowFormulaExactly) {
  std::vector<float> values = {0.0f, -0.0f, -1.0f, 1.0f, 2.0f, 1e-30f, 0.0031308f, 0.5f, 0.18f,
                               std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min()};
  const uint32_t one = std::bit_cast<uint32_t>(1.0f);
  for (uint32_t bits = 0; bits <= one; bits += 97) values.push_back(std::bit_cast<float>(bits));
  // Around each step: the last float of code k - 1 and the first of code k.
  float previous = 0.0f;
  int code = 0;
  for (uint32_t bits = 0; bits <= one; bits += 4096) {
    const float v = std::bit_cast<float>(bits);
    const int c = linearToSrgb8(v);
    if (c != code) {
      for (uint32_t b = std::bit_cast<uint32_t>(previous); b <= bits; ++b) values.push_back(std::bit_cast<float>(b));
      code = c;
    }
    previous = v;
  }
  std::vector<glm::vec4> rgba;
  for (std::size_t i = 0; i < values.size(); i += 3)
    rgba.emplace_back(values[i], i + 1 < values.size() ? values[i + 1] : 0.0f, i + 2 < values.size() ? values[i + 2] : 0.0f, 1.0f);
  std::vector<uint8_t> bytes(rgba.size() * 3);
  encodeSrgb8(rgba, bytes);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < rgba.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (bytes[3 * i + c] != linearToSrgb8(rgba[i][c])) {
        if (++mismatches <= 5) ADD_FAILURE() << "value " << rgba[i][c] << ": table " << int(bytes[3 * i + c]) << ", formula " << int(linearToSrgb8(rgba[i][c]));
      }
  EXPECT_EQ(mismatches, 0u) << "of " << rgba.size() * 3 << " values";
  EXPECT_GT(rgba.size() * 3, 11000000u);
  std::vector<uint8_t> wrong(5);
  EXPECT_THROW(encodeSrgb8(rgba, wrong), std::invalid_argument);
}

TEST(Image, PngRoundTripsThroughOpenImageIO) {
  const fs::path file = tempDir() / "gradient.png";
  const Image img = gradient(33, 17);
  writePng(img, file);
  EXPECT_FALSE(fs::exists(fs::path(file.string() + ".tmp")));
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  ASSERT_EQ(spec.width, 33);
  ASSERT_EQ(spec.height, 17);
  ASSERT_EQ(spec.nchannels, 3);
  std::vector<uint8_t> px(33 * 17 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  in->close();
  for (int y = 0; y < 17; ++y) {
    for (int x = 0; x < 33; ++x) {
      const size_t i = (size_t(y) * 33 + x) * 3;
      ASSERT_EQ(px[i + 0], linearToSrgb8(img.at(x, y).x));
      ASSERT_EQ(px[i + 1], linearToSrgb8(img.at(x, y).y));
      ASSERT_EQ(px[i + 2], 188);
    }
  }
}

TEST(Image, ExrKeepsLinearValuesAndPasses) {
  const fs::path file = tempDir() / "passes.exr";
  Image img = gradient(8, 4);
  img.at(3, 2) = {2.5f, 0.125f, 0.0f, 0.5f};  // above 1: scene-linear, not clamped
  img.depth.assign(img.pixelCount(), 1234.5f);
  img.matte.assign(img.pixelCount(), 0.25f);
  img.object_id.assign(img.pixelCount(), 2u);
  img.object_id[0] = kNoObject;
  writeExr(img, file, {{"stirrup:frame", "12"}});
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.nchannels, 7);
  EXPECT_EQ(spec.channelnames[4], "Z");
  EXPECT_EQ(spec.channelnames[6], "objectId");
  EXPECT_EQ(spec.get_string_attribute("stirrup:frame"), "12");
  EXPECT_EQ(spec.channelformat(0), OIIO::TypeDesc::HALF);
  std::vector<float> px(8 * 4 * 7);
  ASSERT_TRUE(in->read_image(0, 0, 0, 7, OIIO::TypeDesc::FLOAT, px.data()));
  in->close();
  const float* p = &px[(2 * 8 + 3) * 7];
  EXPECT_EQ(p[0], 2.5f);
  EXPECT_EQ(p[1], 0.125f);
  EXPECT_EQ(p[3], 0.5f);
  EXPECT_EQ(p[4], 1234.5f);
  EXPECT_EQ(p[5], 0.25f);
  EXPECT_EQ(p[6], 2.0f);
  EXPECT_EQ(px[6], -1.0f);
}

TEST(Image, ExrCarriesNormalsAndTypedMetadata) {
  const fs::path file = tempDir() / "normals.exr";
  Image img = gradient(4, 2);
  img.depth.assign(img.pixelCount(), 50.0f);
  img.normal.assign(img.pixelCount(), glm::vec3(0.0f, 1.0f, 0.0f));
  img.normal[5] = {0.6f, 0.0f, -0.8f};
  scene::Camera camera;
  camera.projection = scene::Camera::Projection::Orthographic;
  camera.position = {100.0, 200.0, 900.0};
  camera.target = {100.0, 200.0, 0.0};  // looking down -Z: worldToCamera is a pure translation
  camera.ortho_height_cm = 320.0;
  writeExr(img, file, exrFrameMetadata(camera, "side", 7, 0.25, "trot"));
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec spec = in->spec();
  ASSERT_EQ(spec.nchannels, 8);
  const std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
  EXPECT_EQ(names, (std::vector<std::string>{"R", "G", "B", "A", "Z", "N.x", "N.y", "N.z"}));
  EXPECT_EQ(spec.z_channel, 4);
  EXPECT_EQ(spec.get_string_attribute("stirrup:scene"), "trot");
  EXPECT_EQ(spec.get_int_attribute("stirrup:frame"), 7);
  EXPECT_EQ(spec.get_float_attribute("stirrup:time"), 0.25f);
  EXPECT_EQ(spec.get_string_attribute("stirrup:camera"), "side");
  EXPECT_EQ(spec.get_string_attribute("stirrup:camera:projection"), "orthographic");
  EXPECT_EQ(spec.get_float_attribute("stirrup:camera:ortho_height"), 320.0f);
  const OIIO::ParamValue* position = spec.find_attribute("stirrup:camera:position");
  ASSERT_TRUE(position);
  ASSERT_EQ(position->type(), OIIO::TypeDesc::TypeVector);
  EXPECT_EQ(static_cast<const float*>(position->data())[2], 900.0f);
  const OIIO::ParamValue* w2c = spec.find_attribute("worldToCamera");
  ASSERT_TRUE(w2c);
  ASSERT_EQ(w2c->type(), OIIO::TypeDesc::TypeMatrix44);
  const float* m = static_cast<const float*>(w2c->data());
  // Row vectors: p * M. The camera's own position maps to the origin.
  const float p[4] = {100.0f, 200.0f, 900.0f, 1.0f};
  for (int col = 0; col < 3; ++col) {
    float sum = 0.0f;
    for (int row = 0; row < 4; ++row) sum += p[row] * m[row * 4 + col];
    EXPECT_NEAR(sum, 0.0f, 1e-3f) << "column " << col;
  }
  std::vector<float> px(4 * 2 * 8);
  ASSERT_TRUE(in->read_image(0, 0, 0, 8, OIIO::TypeDesc::FLOAT, px.data()));
  in->close();
  EXPECT_NEAR(px[5 * 8 + 5], 0.6f, 1e-3f);  // half float: within its precision
  EXPECT_NEAR(px[5 * 8 + 7], -0.8f, 1e-3f);
  EXPECT_EQ(px[0 * 8 + 6], 1.0f);
  EXPECT_EQ(px[0 * 8 + 4], 50.0f);
}

TEST(Image, FailedWriteLeavesNoFile) {
  const fs::path file = tempDir() / "no_such_dir" / "x.png";
  EXPECT_THROW(writePng(gradient(4, 4), file), std::runtime_error);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_THROW(writePng(Image{}, tempDir() / "empty.png"), std::invalid_argument);
}

// Bytes a PNG of `img` must decode to: the sRGB code of each channel, from the formula (not the writer).
std::vector<uint8_t> expectedSrgbBytes(const Image& img) {
  std::vector<uint8_t> bytes;
  for (const glm::vec4& p : img.rgba)
    for (int c = 0; c < 3; ++c) bytes.push_back(linearToSrgb8(p[c]));
  return bytes;
}

// An image whose rows differ in every channel (odd sizes, so no row is a whole number of words).
Image speckled(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = {float((x * 7 + y * 13) % 31) / 30.0f, float(x) / float(w - 1), float(y) / float(h - 1), 1.0f};
  return img;
}

std::vector<uint8_t> readPngBytes(const fs::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) return {};
  std::vector<uint8_t> px(size_t(in->spec().width) * size_t(in->spec().height) * 3);
  if (in->spec().nchannels != 3 || !in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data())) return {};
  return px;
}

// PNG is lossless: the zlib level changes the file's size and the write's time, never the pixels.
TEST(Image, PngAtEveryZlibLevelHoldsTheSamePixels) {
  const Image img = speckled(97, 61);
  const std::vector<uint8_t> expected = expectedSrgbBytes(img);
  std::vector<uintmax_t> sizes;
  for (const int level : {scene::kPngCompressionMin, scene::kDraftPngCompression, scene::kReviewPngCompression, 6, scene::kPngCompressionMax}) {
    const fs::path file = tempDir() / ("level" + std::to_string(level) + ".png");
    writePng(img, file, level);
    EXPECT_EQ(readPngBytes(file), expected) << "level " << level;
    sizes.push_back(fs::file_size(file));
  }
  // Level 0 stores the rows as they are: the file holds every pixel's 3 bytes and a filter byte a row.
  EXPECT_GE(sizes[0], uintmax_t(97 * 61 * 3 + 61));
  // A compressing level makes it smaller (the blue channel is one value a row).
  EXPECT_LT(sizes[2], sizes[0]);
  EXPECT_LE(sizes[4], sizes[2]);
}

// Another decoder than OpenImageIO's reads a stored PNG (draft's) and a level-1 one (review's) to the
// same pixels: ffmpeg, as the movie encoder reads the frames.
TEST(Image, FfmpegDecodesStoredAndCompressedPngsToTheSamePixels) {
  if (std::system("ffmpeg -version > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg is not installed";
  const Image img = speckled(45, 23);
  const std::vector<uint8_t> expected = expectedSrgbBytes(img);
  for (const int level : {scene::kDraftPngCompression, scene::kReviewPngCompression}) {
    const fs::path file = tempDir() / ("ffmpeg" + std::to_string(level) + ".png");
    writePng(img, file, level);
    const std::string cmd = "ffmpeg -v error -i '" + file.string() + "' -f rawvideo -pix_fmt rgb24 -";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::vector<uint8_t> decoded(expected.size() + 1);  // one more: a longer stream is a failure too
    const size_t n = std::fread(decoded.data(), 1, decoded.size(), pipe);
    EXPECT_EQ(pclose(pipe), 0) << cmd;
    decoded.resize(n);
    EXPECT_EQ(decoded, expected) << "level " << level;
  }
}

TEST(Image, APngCompressionOutsideZlibsLevelsIsRejected) {
  for (const int level : {-1, 10}) {
    const fs::path file = tempDir() / ("bad" + std::to_string(level) + ".png");
    EXPECT_THROW(writePng(gradient(4, 4), file, level), std::invalid_argument);
    EXPECT_FALSE(fs::exists(file));
    EXPECT_FALSE(fs::exists(fs::path(file.string() + ".tmp")));
  }
}

TEST(Image, WriteReplacesAnExistingFileWhole) {
  const fs::path file = tempDir() / "replace.png";
  writePng(gradient(64, 64), file);
  writePng(gradient(8, 8), file);
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 8);
}

TEST(Image, RgbaExrReadsBackBitForBit) {
  // The contact sheet's frames cross from a farm task to the finishing job through these files: any
  // rounding would make a farm's sheet differ from a local one.
  Image im(5, 3);
  for (std::size_t i = 0; i < im.rgba.size(); ++i)
    im.rgba[i] = glm::vec4(0.1f * float(i) + 1e-7f, std::nextafter(0.5f, 1.0f), 1e-30f * float(i), 1.0f / 3.0f);
  const fs::path file = tempDir() / "sheet.exr";
  writeRgbaExr(im, file);
  const Image back = readRgbaExr(file);
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  for (std::size_t i = 0; i < im.rgba.size(); ++i)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(std::bit_cast<std::uint32_t>(back.rgba[i][c]), std::bit_cast<std::uint32_t>(im.rgba[i][c]));
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
}

TEST(Image, ReadRgbaExrNamesAMissingFile) {
  const fs::path file = tempDir() / "missing.exr";
  try {
    readRgbaExr(file);
    FAIL() << "no error";
  } catch (const rig::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace stirrup::render
