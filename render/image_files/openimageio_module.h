#pragma once
// The calls into libstirrup_openimageio.so, the module that holds OpenImageIO (render/image_files/
// image_file.h says why it is a module). Both sides are built together from this header; the table's
// `abi` is checked on loading, so a module left from another build is refused rather than called.
// No exception crosses the boundary: each call returns its error as text (empty: none).

#include <string>

#include "render/image_files/image_file.h"

namespace stirrup::render {

// Raise on any change to the table or to the types it passes.
constexpr int kImageModuleAbi = 1;

struct ImageModuleCalls {
  int abi;
  std::string (*read)(const std::string& file, ImageFileData& out);
  std::string (*write)(const std::string& file, const std::string& format, const ImageFileSpec& spec, const float* pixels);
  std::string (*measure_text)(const std::string& text, int size, const std::string& font, TextBox& out);
  std::string (*draw_text)(float* mask, int width, int height, int x, int y, const std::string& text, int size,
                           const std::string& font, HorizontalAlign align);
};

}  // namespace stirrup::render

// The module's one exported symbol: its table of calls.
#define STIRRUP_IMAGE_MODULE_ENTRY "stirrup_image_module_calls"
#define STIRRUP_IMAGE_MODULE_FILE "libstirrup_openimageio.so"
extern "C" const stirrup::render::ImageModuleCalls* stirrup_image_module_calls();
