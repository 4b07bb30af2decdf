// Image files read and written through the OpenImageIO module (render/image_files/image_file.h),
// checked against OpenImageIO linked here directly: a second reader and writer.
#include "render/image_files/image_file.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"
#include "tests/test_files.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

class ImageFileTest : public ::testing::Test {
 protected:
  const fs::path dir_ = test::freshTestDir("image_file_test", ::testing::UnitTest::GetInstance()->current_test_info()->name());
};

// An EXR of mixed channels (half colour, float depth), its alpha and depth marked and its header's
// attributes of every kind, as OpenImageIO itself reads it back.
TEST_F(ImageFileTest, AnExrIsWrittenWithItsChannelsFormatsAndAttributes) {
  ImageFileSpec spec;
  spec.width = 3, spec.height = 2;
  spec.channel_names = {"R", "G", "B", "A", "Z"};
  spec.channel_formats = {StoredAs::Half, StoredAs::Half, StoredAs::Half, StoredAs::Half, StoredAs::Float};
  spec.alpha_channel = 3, spec.z_channel = 4;
  glm::mat4 m(1.0f);
  m[3][0] = 7.0f;
  spec.attributes = {{"compression", std::string("zip")}, {"stirrup:frame", 12}, {"stirrup:time", 0.5f},
                     {"stirrup:camera:position", glm::vec3(1, 2, 3)}, {"worldToCamera", m}};
  std::vector<float> px(3 * 2 * 5);
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = 0.25f * float(i) + (i % 5 == 4 ? 1000.0625f : 0.0f);
  const fs::path file = dir_ / "f.exr";
  writeImageFile(file, "openexr", spec, px.data());
  EXPECT_FALSE(fs::exists(dir_ / "f.exr.tmp"));

  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& s = in->spec();
  EXPECT_EQ(s.width, 3);
  EXPECT_EQ(s.height, 2);
  EXPECT_EQ(s.channelnames, spec.channel_names);
  EXPECT_EQ(s.channelformat(0), OIIO::TypeDesc::HALF);
  EXPECT_EQ(s.channelformat(4), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(s.alpha_channel, 3);
  EXPECT_EQ(s.z_channel, 4);
  EXPECT_EQ(s.get_string_attribute("compression"), "zip");
  EXPECT_EQ(s.get_int_attribute("stirrup:frame"), 12);
  EXPECT_FLOAT_EQ(s.get_float_attribute("stirrup:time"), 0.5f);
  const OIIO::ParamValue* p = s.find_attribute("stirrup:camera:position", OIIO::TypeDesc::TypeVector);
  ASSERT_NE(p, nullptr);
  EXPECT_FLOAT_EQ(static_cast<const float*>(p->data())[2], 3.0f);
  const OIIO::ParamValue* w = s.find_attribute("worldToCamera", OIIO::TypeDesc::TypeMatrix44);
  ASSERT_NE(w, nullptr);
  EXPECT_FLOAT_EQ(static_cast<const float*>(w->data())[12], 7.0f);
  std::vector<float> back(px.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, back.data()));
  EXPECT_EQ(back, px);  // quarters are exact in half; the depth's 1/16ths in float
}

// A PNG written by OpenImageIO reads as its bytes over 255, coded (not linear), its channels named.
TEST_F(ImageFileTest, APngReadsAsCodedFloatsWithItsChannelNames) {
  const fs::path file = dir_ / "p.png";
  const unsigned char bytes[2 * 1 * 3] = {0, 51, 255, 102, 1, 17};
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(2, 1, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, bytes));
  ASSERT_TRUE(out->close());
  const ImageFileData d = readImageFile(file);
  EXPECT_EQ(d.width, 2);
  EXPECT_EQ(d.height, 1);
  EXPECT_EQ(d.channels, 3);
  EXPECT_FALSE(d.linear);
  EXPECT_EQ(d.channelIndex("B"), 2);
  EXPECT_EQ(d.channelIndex("A"), -1);
  ASSERT_EQ(d.pixels.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_FLOAT_EQ(d.pixels[std::size_t(i)], float(bytes[i]) / 255.0f) << i;
}

// With no format named the extension chooses, and with no names OpenImageIO's own are kept: a
// written PNG holds the values rounded to 8 bits.
TEST_F(ImageFileTest, ThePngWrittenByItsExtensionHoldsTheRoundedValues) {
  ImageFileSpec spec;
  spec.width = 2, spec.height = 1;
  spec.channel_formats.assign(3, StoredAs::UInt8);
  const std::vector<float> px = {0.0f, 0.5f, 1.0f, 0.2f, 0.21f, 2.0f};
  const fs::path file = dir_ / "w.png";
  writeImageFile(file, "", spec, px.data());
  EXPECT_FALSE(fs::exists(dir_ / "w.png.tmp.png"));
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->format_name(), std::string("png"));
  unsigned char back[6] = {};
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, back));
  const unsigned char expected[6] = {0, 128, 255, 51, 54, 255};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(back[i], expected[i]) << i;
}

// Bad files are one-line InputErrors naming the file; a failed write leaves neither the file nor its
// temporary behind.
TEST_F(ImageFileTest, ReadAndWriteErrorsNameTheFileOnOneLine) {
  const fs::path missing = dir_ / "gone.exr";
  const std::string read = test::errorOf([&] { readImageFile(missing); });
  EXPECT_EQ(read.rfind(missing.string() + ": cannot read the image (", 0), 0u) << read;
  EXPECT_EQ(read.find('\n'), std::string::npos) << read;
  const fs::path text = dir_ / "not_an_image.png";
  { std::ofstream(text) << "hello"; }
  const std::string garbage = test::errorOf([&] { readImageFile(text); });
  EXPECT_EQ(garbage.rfind(text.string() + ": cannot read the image (", 0), 0u) << garbage;

  ImageFileSpec spec;
  spec.width = 1, spec.height = 1;
  spec.channel_formats.assign(3, StoredAs::UInt8);
  const float px[3] = {0, 0, 0};
  const fs::path nowhere = dir_ / "no" / "folder" / "x.png";
  const std::string write = test::errorOf([&] { writeImageFile(nowhere, "", spec, px); });
  EXPECT_EQ(write.rfind(nowhere.string() + ": cannot write the image (", 0), 0u) << write;
  spec.channel_names = {"R"};  // one name for three channels
  const fs::path bad = dir_ / "bad.png";
  const std::string names = test::errorOf([&] { writeImageFile(bad, "", spec, px); });
  EXPECT_NE(names.find("a name, if any) for each channel"), std::string::npos) << names;
  EXPECT_FALSE(fs::exists(bad));
  EXPECT_FALSE(fs::exists(dir_ / "bad.png.tmp.png"));
  spec.channel_names.clear();
  const std::string format = test::errorOf([&] { writeImageFile(dir_ / "x.png", "no-such-format", spec, px); });
  EXPECT_NE(format.find("no OpenImageIO writer for no-such-format"), std::string::npos) << format;
}

// Text is measured and drawn with a system font: the drawn coverage lies within the measured box.
TEST_F(ImageFileTest, TextIsDrawnWithinItsMeasuredBox) {
  const fs::path font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  if (!fs::is_regular_file(font)) GTEST_SKIP() << font << " is not installed (fonts-dejavu-core)";
  const TextBox box = measureText("Hig", 20, font);
  ASSERT_TRUE(box.defined);
  EXPECT_GT(box.width(), 20);
  EXPECT_GT(box.height(), 14);
  EXPECT_LT(box.ybegin, 0);  // above the baseline
  EXPECT_GT(box.yend, 0);    // the g's descender below it
  const int w = 80, h = 40, x = 10, y = 25;
  std::vector<float> mask(std::size_t(w * h), 0.0f);
  drawTextCoverage(mask, w, h, x, y, "Hig", 20, font, HorizontalAlign::Left);
  int covered = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const float c = mask[std::size_t(py * w + px)];
      if (c <= 0.0f) continue;
      ++covered;
      EXPECT_LE(c, 1.0f);
      EXPECT_GE(px, x + box.xbegin - 1) << px << "," << py;
      EXPECT_LT(px, x + box.xend + 1) << px << "," << py;
      EXPECT_GE(py, y + box.ybegin - 1) << px << "," << py;
      EXPECT_LT(py, y + box.yend + 1) << px << "," << py;
    }
  EXPECT_GT(covered, 40);
  std::vector<float> wrong(10);
  EXPECT_THROW(drawTextCoverage(wrong, w, h, x, y, "Hig", 20, font, HorizontalAlign::Left), std::invalid_argument);
}

// The module is looked for from the running program's folder first: the test program's is the build
// tree's tests/, whose ../LIBDIR/stirrup holds it.
TEST(ImageModuleFolders, TheFirstIsBesideTheRunningProgram) {
  const std::vector<fs::path> folders = imageModuleFolders();
  ASSERT_GE(folders.size(), 1u);
  const fs::path program = fs::read_symlink("/proc/self/exe");
  const fs::path within = folders[0].lexically_relative(program.parent_path().parent_path());
  ASSERT_FALSE(within.empty()) << folders[0];
  EXPECT_NE(*within.begin(), "..") << folders[0];
  EXPECT_EQ(folders[0].filename(), "stirrup");
  EXPECT_TRUE(fs::is_regular_file(folders[0] / "libstirrup_openimageio.so")) << folders[0];
}

}  // namespace
}  // namespace stirrup::render
