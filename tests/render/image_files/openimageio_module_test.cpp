// The module itself (render/image_files/openimageio_module.cpp), opened as the program opens it: its
// one exported entry gives this build's table of calls, and no call lets an exception out; each
// returns its error as one line of text.
#include "render/image_files/openimageio_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

const ImageModuleCalls* openModule() {
  const fs::path file = imageModuleFolders().at(0) / STIRRUP_IMAGE_MODULE_FILE;
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) return nullptr;
  using Entry = const ImageModuleCalls* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, STIRRUP_IMAGE_MODULE_ENTRY));
  return entry ? entry() : nullptr;
}

TEST(OpenImageIOModule, ExportsThisBuildsCallsAndNothingOfOpenImageIO) {
  const ImageModuleCalls* calls = openModule();
  ASSERT_NE(calls, nullptr) << dlerror();
  EXPECT_EQ(calls->abi, kImageModuleAbi);
  EXPECT_TRUE(calls->read && calls->write && calls->measure_text && calls->draw_text);
  // Built with hidden visibility: its helpers are not exported to collide with a program's.
  void* handle = dlopen((imageModuleFolders().at(0) / STIRRUP_IMAGE_MODULE_FILE).c_str(), RTLD_NOW | RTLD_NOLOAD);
  ASSERT_NE(handle, nullptr);
  EXPECT_EQ(dlsym(handle, "_ZN7stirrup6render12_GLOBAL__N_14readERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERNS0_13ImageFileDataE"), nullptr);
}

TEST(OpenImageIOModule, ErrorsComeBackAsOneLineOfText) {
  const ImageModuleCalls* calls = openModule();
  ASSERT_NE(calls, nullptr) << dlerror();
  ImageFileData data;
  const std::string read = calls->read("/nonexistent/stirrup/x.exr", data);
  EXPECT_FALSE(read.empty());
  EXPECT_EQ(read.find('\n'), std::string::npos) << read;
  EXPECT_EQ(data.width, 0);  // left as it was

  ImageFileSpec spec;  // no size, no channels
  const float px[1] = {0};
  const std::string write = calls->write("/nonexistent/stirrup/x.png", "", spec, px);
  EXPECT_EQ(write, "expected a size, and a format (and a name, if any) for each channel");

  TextBox box{true, 1, 2, 3, 4};
  const std::string measure = calls->measure_text("text", 12, "/nonexistent/font.ttf", box);
  // A missing font is OpenImageIO's to report or to leave undefined; either way no exception.
  EXPECT_TRUE(!measure.empty() || !box.defined) << measure;
}

}  // namespace
}  // namespace stirrup::render
