#pragma once
// Image files read and written, and text drawn, through OpenImageIO, which is loaded only when a
// process first needs it: its libraries (some 250: codecs, DICOM, GDAL, OpenCV) cost about 0.4 s of
// CPU to load and relocate, which every run of stirrup paid, also those that never touch an image
// file (docs/performance-history.md, "Process start"). OpenImageIO lives in a module of its own,
// libstirrup_openimageio.so (render/image_files/openimageio_module.cpp), installed beside the
// program in LIBDIR/stirrup.

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace stirrup::render {

// How a channel is stored in a written file (the pixels handed over are always float).
enum class StoredAs { UInt8, Half, Float };

// One attribute of a written file's header (an EXR's metadata).
struct FileAttribute {
  std::string name;
  std::variant<std::string, int, float, glm::vec3, glm::mat4> value;
};

// What a file is written as: its size, each channel's storage and name (no names: OpenImageIO's
// R, G, B, A), which channel is alpha and which depth (-1: none), and the header's attributes.
struct ImageFileSpec {
  int width = 0, height = 0;
  std::vector<StoredAs> channel_formats;  // one a channel: their count is the channels'
  std::vector<std::string> channel_names;  // none, or one a channel
  int alpha_channel = -1, z_channel = -1;
  std::vector<FileAttribute> attributes;
};

// An image file as read: the first subimage's pixels as interleaved floats, row-major from the top.
struct ImageFileData {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> channel_names;
  bool linear = false;  // stored as floating point (half, float, double), not as coded integers
  std::vector<float> pixels;

  // The index of the channel called `name`, or -1.
  int channelIndex(const std::string& name) const;
};

// Reads `file`. Throws rig::InputError "FILE: cannot read the image (WHY)", on one line.
ImageFileData readImageFile(const std::filesystem::path& file);

// Writes `pixels` (spec.width x spec.height x channels interleaved floats) as `file`, whole or not at
// all (rig/io/atomic_file.h), in `format` (OpenImageIO's format name, such as "openexr"; empty: by
// the file's extension). The folder must exist. Throws rig::InputError "FILE: cannot write the image
// (WHY)", on one line.
void writeImageFile(const std::filesystem::path& file, const std::string& format, const ImageFileSpec& spec,
                    const float* pixels);

// A text's box at `size` pixels in the font file `font`, relative to its origin on the baseline
// (y grows downward); not `defined` where OpenImageIO cannot measure it.
struct TextBox {
  bool defined = false;
  int xbegin = 0, xend = 0, ybegin = 0, yend = 0;
  int width() const { return xend - xbegin; }
  int height() const { return yend - ybegin; }
};
TextBox measureText(const std::string& text, int size, const std::filesystem::path& font);

// Draws `text` into `mask` (width x height floats, coverage written as 1), its baseline at y, its
// left end, middle or right end at x. Some pixel of the text must land in the mask (OpenImageIO
// aborts otherwise: callers check with measureText).
enum class HorizontalAlign { Left, Center, Right };
void drawTextCoverage(std::vector<float>& mask, int width, int height, int x, int y, const std::string& text, int size,
                      const std::filesystem::path& font, HorizontalAlign align);

// Where the module is looked for, in order: ../LIBDIR/stirrup from the running program's folder (as
// installed, and in the build tree from build/bin and build/tests), then the configured install's.
// No source or build path is compiled in (an installed program holds none).
std::vector<std::filesystem::path> imageModuleFolders();

}  // namespace stirrup::render
