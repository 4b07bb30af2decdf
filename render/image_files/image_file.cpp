#include "render/image_files/image_file.h"

#include <dlfcn.h>

#include <algorithm>
#include <stdexcept>
#include <system_error>

#include "render/image_files/openimageio_module.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

// Loads the module once, the first time any call needs it, and keeps it for the process's life.
// A missing or mismatched module is an installation fault: every call then throws the same
// one-line error naming the folders looked in.
const ImageModuleCalls& moduleCalls() {
  struct Loaded {
    const ImageModuleCalls* calls = nullptr;
    std::string error;
  };
  static const Loaded loaded = [] {
    Loaded l;
    std::string tried;
    for (const fs::path& folder : imageModuleFolders()) {
      const fs::path file = folder / STIRRUP_IMAGE_MODULE_FILE;
      tried += (tried.empty() ? "" : ", ") + folder.string();
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) continue;
      void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        const char* why = dlerror();
        l.error = file.string() + ": cannot load (" + (why ? why : "no reason given") + ")";
        return l;
      }
      using Entry = const ImageModuleCalls* (*)();
      auto entry = reinterpret_cast<Entry>(dlsym(handle, STIRRUP_IMAGE_MODULE_ENTRY));
      const ImageModuleCalls* calls = entry ? entry() : nullptr;
      if (!calls || calls->abi != kImageModuleAbi) {
        l.error = file.string() + ": not this build's module (expected the calls of ABI " +
                  std::to_string(kImageModuleAbi) + "; install stirrup again)";
        return l;
      }
      l.calls = calls;
      return l;
    }
    l.error = std::string(STIRRUP_IMAGE_MODULE_FILE) + " (stirrup's image files, OpenImageIO) not found in " + tried +
              ": expected it installed beside the program";
    return l;
  }();
  if (!loaded.calls) throw std::runtime_error(loaded.error);
  return *loaded.calls;
}

}  // namespace

int ImageFileData::channelIndex(const std::string& name) const {
  const auto it = std::find(channel_names.begin(), channel_names.end(), name);
  return it == channel_names.end() ? -1 : int(it - channel_names.begin());
}

std::vector<fs::path> imageModuleFolders() {
  std::vector<fs::path> folders;
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) folders.push_back((program.parent_path() / STIRRUP_IMAGE_MODULE_FROM_PROGRAM).lexically_normal());
  // A program copied away from its installed tree still finds the configured install's.
  const fs::path installed(STIRRUP_IMAGE_MODULE_INSTALL_DIR);
  if (std::find(folders.begin(), folders.end(), installed) == folders.end()) folders.push_back(installed);
  return folders;
}

ImageFileData readImageFile(const fs::path& file) {
  ImageFileData data;
  const std::string error = moduleCalls().read(file.string(), data);
  if (!error.empty()) throw rig::InputError(file.string() + ": cannot read the image (" + error + ")");
  return data;
}

void writeImageFile(const fs::path& file, const std::string& format, const ImageFileSpec& spec, const float* pixels) {
  const ImageModuleCalls& calls = moduleCalls();
  // Named by its format, the temporary is FILE.tmp; else FILE.tmp.EXT, for OpenImageIO to go by.
  rig::replaceFileAtomically(
      file,
      [&](const fs::path& tmp) {
        const std::string error = calls.write(tmp.string(), format, spec, pixels);
        if (!error.empty()) throw rig::InputError(file.string() + ": cannot write the image (" + error + ")");
      },
      format.empty() ? rig::TempName::KeepExtension : rig::TempName::Plain);
}

TextBox measureText(const std::string& text, int size, const fs::path& font) {
  TextBox box;
  const std::string error = moduleCalls().measure_text(text, size, font.string(), box);
  if (!error.empty()) throw rig::InputError(font.string() + ": cannot measure text (" + error + ")");
  return box;
}

void drawTextCoverage(std::vector<float>& mask, int width, int height, int x, int y, const std::string& text, int size,
                      const fs::path& font, HorizontalAlign align) {
  if (mask.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument("drawTextCoverage: the mask is not width x height");
  const std::string error = moduleCalls().draw_text(mask.data(), width, height, x, y, text, size, font.string(), align);
  if (!error.empty()) throw std::runtime_error("render_text: " + error);
}

}  // namespace stirrup::render
