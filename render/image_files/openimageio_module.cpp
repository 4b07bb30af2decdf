// libstirrup_openimageio.so: every call stirrup makes into OpenImageIO (render/image_files/
// openimageio_module.h). Built as a module of its own, loaded on first use (image_file.cpp).

#include "render/image_files/openimageio_module.h"

#include <exception>
#include <memory>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

namespace stirrup::render {
namespace {

// OpenImageIO's messages can run over several lines; stirrup's errors are one.
std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.empty() ? "no reason given" : text;
}

OIIO::TypeDesc typeOf(StoredAs s) {
  switch (s) {
    case StoredAs::UInt8: return OIIO::TypeDesc::UINT8;
    case StoredAs::Half: return OIIO::TypeDesc::HALF;
    default: return OIIO::TypeDesc::FLOAT;
  }
}

// Runs `f`, turning anything thrown (OpenImageIO or the allocator) into the call's error text.
template <class F>
std::string guarded(F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    return oneLine(e.what());
  } catch (...) {
    return "unknown error";
  }
}

std::string read(const std::string& file, ImageFileData& out) {
  return guarded([&]() -> std::string {
    auto in = OIIO::ImageInput::open(file);
    if (!in) return oneLine(OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 1)
      return "no pixels (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ", " +
             std::to_string(spec.nchannels) + " channels)";
    ImageFileData d;
    d.width = spec.width, d.height = spec.height, d.channels = spec.nchannels;
    d.channel_names = spec.channelnames;
    const auto base = OIIO::TypeDesc::BASETYPE(spec.format.basetype);
    d.linear = base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE;
    d.pixels.resize(std::size_t(d.width) * std::size_t(d.height) * std::size_t(d.channels));
    if (!in->read_image(0, 0, 0, d.channels, OIIO::TypeDesc::FLOAT, d.pixels.data())) return oneLine(in->geterror());
    in->close();
    out = std::move(d);
    return {};
  });
}

std::string write(const std::string& file, const std::string& format, const ImageFileSpec& s, const float* pixels) {
  return guarded([&]() -> std::string {
    const int channels = int(s.channel_formats.size());
    if (channels < 1 || s.width <= 0 || s.height <= 0 ||
        (!s.channel_names.empty() && s.channel_names.size() != s.channel_formats.size()))
      return "expected a size, and a format (and a name, if any) for each channel";
    auto out = format.empty() ? OIIO::ImageOutput::create(file) : OIIO::ImageOutput::create(format);
    if (!out) return "no OpenImageIO writer for " + (format.empty() ? "this file name" : format);
    OIIO::ImageSpec spec(s.width, s.height, channels, typeOf(s.channel_formats[0]));
    if (!s.channel_names.empty()) spec.channelnames = s.channel_names;
    bool mixed = false;
    for (StoredAs f : s.channel_formats) mixed = mixed || f != s.channel_formats[0];
    if (mixed)
      for (StoredAs f : s.channel_formats) spec.channelformats.push_back(typeOf(f));
    spec.alpha_channel = s.alpha_channel;
    spec.z_channel = s.z_channel;
    for (const FileAttribute& a : s.attributes) {
      if (const auto* text = std::get_if<std::string>(&a.value))
        spec.attribute(a.name, *text);
      else if (const int* i = std::get_if<int>(&a.value))
        spec.attribute(a.name, *i);
      else if (const float* f = std::get_if<float>(&a.value))
        spec.attribute(a.name, *f);
      else if (const auto* v = std::get_if<glm::vec3>(&a.value))
        spec.attribute(a.name, OIIO::TypeDesc::TypeVector, v);
      else if (const auto* m = std::get_if<glm::mat4>(&a.value))
        spec.attribute(a.name, OIIO::TypeDesc::TypeMatrix44, m);
    }
    if (!out->open(file, spec)) return oneLine(out->geterror());
    if (!out->write_image(OIIO::TypeDesc::FLOAT, pixels)) {
      const std::string err = oneLine(out->geterror());
      out->close();
      return err;
    }
    if (!out->close()) return oneLine(out->geterror());
    return {};
  });
}

std::string measureText(const std::string& text, int size, const std::string& font, TextBox& out) {
  return guarded([&]() -> std::string {
    const OIIO::ROI r = OIIO::ImageBufAlgo::text_size(text, size, font);
    out = r.defined() ? TextBox{true, r.xbegin, r.xend, r.ybegin, r.yend} : TextBox{};
    return {};
  });
}

std::string drawText(float* mask, int width, int height, int x, int y, const std::string& text, int size,
                     const std::string& font, HorizontalAlign align) {
  return guarded([&]() -> std::string {
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::FLOAT), mask);
    const float white[1] = {1.0f};
    const auto ax = align == HorizontalAlign::Left     ? OIIO::ImageBufAlgo::TextAlignX::Left
                    : align == HorizontalAlign::Center ? OIIO::ImageBufAlgo::TextAlignX::Center
                                                       : OIIO::ImageBufAlgo::TextAlignX::Right;
    if (!OIIO::ImageBufAlgo::render_text(buf, x, y, text, size, font, white, ax, OIIO::ImageBufAlgo::TextAlignY::Baseline,
                                         0, {}, 1))
      return oneLine(buf.geterror());
    return {};
  });
}

constexpr ImageModuleCalls kCalls{kImageModuleAbi, read, write, measureText, drawText};

}  // namespace
}  // namespace stirrup::render

extern "C" __attribute__((visibility("default"))) const stirrup::render::ImageModuleCalls* stirrup_image_module_calls() {
  return &stirrup::render::kCalls;
}
