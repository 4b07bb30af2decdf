// Footage for layered comparisons: reading images to linear light, image sequences and their mapping
// onto our frames, placement on our canvas, cutting grid plates, and the scene's reference block.
#include "render/review/layer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "render/image_files/image_file.h"
#include "rig/error.h"
#include "scene/frame_sequence.h"

namespace stirrup::render {

namespace fs = std::filesystem;

namespace {

std::string rectText(const scene::PixelRect& r) {
  return std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.width) + "," +
         std::to_string(r.height);
}

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

float srgbToLinear(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

std::string numberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The rectangle `crop` of an image w x h, or all of it when empty; InputError when outside.
scene::PixelRect effectiveCrop(const scene::PixelRect& crop, int w, int h, const std::string& context) {
  if (crop.empty()) {
    if (crop.width < 0 || crop.height < 0)
      throw rig::InputError(context + ": expected a width and height >= 0, got " + rectText(crop));
    return scene::PixelRect{0, 0, w, h};
  }
  if (crop.x < 0 || crop.y < 0 || crop.x + crop.width > w || crop.y + crop.height > h)
    throw rig::InputError(context + ": rectangle " + rectText(crop) + " (x,y,w,h) lies outside the " + sizeText(w, h) +
                     " image");
  return crop;
}

// Bilinear sample at continuous coordinates (pixel centres at +0.5), clamped to `r`.
glm::vec3 sampleBilinear(const Image& img, const scene::PixelRect& r, double u, double v) {
  const double fu = u - 0.5, fv = v - 0.5;
  const int x0 = int(std::floor(fu)), y0 = int(std::floor(fv));
  const float fx = float(fu - x0), fy = float(fv - y0);
  auto texel = [&](int x, int y) {
    x = std::clamp(x, r.x, r.x + r.width - 1);
    y = std::clamp(y, r.y, r.y + r.height - 1);
    return glm::vec3(img.at(x, y));
  };
  return (1 - fy) * ((1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
         fy * ((1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
}

// Our canvas's pixel (x, y) centre in the crop's coordinates, or nothing where the footage does not reach.
Image placeOnCanvas(const Image& src, const scene::PixelRect& crop, float scale, glm::vec2 position, bool flip_x,
                    int width, int height) {
  Image out(width, height);
  const double s = scale;
  const int taps = std::max(1, int(std::ceil(1.0 / s - 1e-9)));
  const int x_begin = std::max(0, int(std::floor(position.x))),
            x_end = std::min(width, int(std::ceil(position.x + crop.width * s)));
  const int y_begin = std::max(0, int(std::floor(position.y))),
            y_end = std::min(height, int(std::ceil(position.y + crop.height * s)));
  for (int y = y_begin; y < y_end; ++y)
    for (int x = x_begin; x < x_end; ++x) {
      const double cx = (x + 0.5 - position.x) / s, cy = (y + 0.5 - position.y) / s;
      if (cx < 0 || cy < 0 || cx >= crop.width || cy >= crop.height) continue;
      glm::vec3 sum(0.0f);
      for (int j = 0; j < taps; ++j)
        for (int i = 0; i < taps; ++i) {
          double u = (x + (i + 0.5) / taps - position.x) / s, v = (y + (j + 0.5) / taps - position.y) / s;
          if (flip_x) u = crop.width - u;
          sum += sampleBilinear(src, crop, crop.x + u, crop.y + v);
        }
      out.at(x, y) = glm::vec4(sum / float(taps * taps), 1.0f);
    }
  return out;
}

// Mean of sRGB-coded luminance over a column (or row) span, the way an eye sees a plate's border.
double plateMean(const std::vector<float>& lum, int w, bool column, int at, int from, int to) {
  double sum = 0;
  for (int k = from; k < to; ++k) sum += column ? lum[size_t(k) * size_t(w) + size_t(at)] : lum[size_t(at) * size_t(w) + size_t(k)];
  return to > from ? sum / (to - from) : 0.0;
}

// The photograph's edge near `nominal` along one axis (see PlateGrid::snap).
int snapEdge(const std::vector<float>& lum, int w, int h, bool columns, int nominal, int slack, int across_from,
             int across_to) {
  const int limit = columns ? w : h;
  const int lo = std::max(0, nominal - slack), hi = std::min(limit - 1, nominal + slack);
  std::vector<double> means;
  for (int i = lo; i <= hi; ++i) means.push_back(plateMean(lum, w, columns, i, across_from, across_to));
  if (means.empty()) return nominal;
  const auto [mn, mx] = std::minmax_element(means.begin(), means.end());
  if (*mx - *mn < 0.15) return nominal;  // no border here
  const double dark = *mn + 0.3 * (*mx - *mn);
  for (int i = hi; i >= lo; --i)
    if (means[size_t(i - lo)] < dark) return i + 1 <= hi ? i + 1 : nominal;
  return nominal;
}

}  // namespace

Image readLinearImage(const fs::path& file) {
  if (!fs::exists(file)) throw rig::InputError(file.string() + ": no such image file");
  const ImageFileData read = readImageFile(file);
  const int nc = read.channels;
  const std::vector<float>& px = read.pixels;
  const bool linear = read.linear;
  auto decode = [&](float v) { return linear ? v : srgbToLinear(v); };
  // Channels by name where the file names them (an EXR's may come in any order), else by position.
  const auto channel = [&](const char* name, int fallback) {
    const int i = read.channelIndex(name);
    return i >= 0 ? i : (fallback < nc ? fallback : -1);
  };
  const bool colour = nc >= 3;
  const int cr = colour ? channel("R", 0) : 0, cg = colour ? channel("G", 1) : 0, cb = colour ? channel("B", 2) : 0;
  const int ca = channel("A", colour ? 3 : 1), cm = read.channelIndex("matte");
  Image img(read.width, read.height);
  if (cm >= 0) img.matte.resize(img.pixelCount());
  for (size_t i = 0; i < img.pixelCount(); ++i) {
    const float* p = &px[i * size_t(nc)];
    img.rgba[i] = glm::vec4(decode(p[cr]), decode(p[cg]), decode(p[cb]), ca >= 0 ? p[ca] : 1.0f);
    if (cm >= 0) img.matte[i] = p[cm];
  }
  return img;
}

std::optional<int> FootageSequence::theirFrame(int our_frame) const {
  const int n = frameCount();
  if (n <= 0) return std::nullopt;
  const long long index = offset + static_cast<long long>(std::floor((our_frame - 1) * rate + 1e-9));
  switch (edge) {
    case scene::FootageEdge::Hold: return first + int(std::clamp<long long>(index, 0, n - 1));
    case scene::FootageEdge::Loop: return first + int(((index % n) + n) % n);
    case scene::FootageEdge::Blank:
      if (index < 0 || index >= n) return std::nullopt;
      return first + int(index);
  }
  return std::nullopt;
}

Image FootageSequence::source(int their_frame) const {
  const int index = their_frame - first;
  if (index < 0 || index >= frameCount())
    throw rig::InputError(name + ": no frame " + std::to_string(their_frame) + " (the footage has frames " +
                     std::to_string(first) + "-" + std::to_string(first + frameCount() - 1) + ")");
  if (!images.empty()) return images[size_t(index)];
  return readLinearImage(files[size_t(index)]);
}

Image FootageSequence::frame(int our_frame, int width, int height) const {
  const std::optional<int> their = theirFrame(our_frame);
  if (!their) return Image(width, height);
  const Image src = source(*their);
  const scene::PixelRect c = effectiveCrop(crop, src.width, src.height, name + ": crop");
  const size_t index = size_t(*their - first);
  const float dx = index < shift_x.size() ? shift_x[index] * scale * (flip_x ? -1.0f : 1.0f) : 0.0f;
  return placeOnCanvas(src, c, scale, position + glm::vec2(dx, 0.0f), flip_x, width, height);
}

void FootageSequence::validate(const std::string& context) const {
  if (frameCount() <= 0) throw rig::InputError(context + ": expected at least one footage frame, got none");
  if (!(std::isfinite(rate) && rate > 0))
    throw rig::InputError(context + ": rate: expected their frames per our frame > 0, got " + numberText(rate));
  if (!(std::isfinite(scale) && scale > 0))
    throw rig::InputError(context + ": scale: expected a number > 0, got " + numberText(scale));
  if (!std::isfinite(position.x) || !std::isfinite(position.y))
    throw rig::InputError(context + ": position: expected finite pixel coordinates");
  for (const fs::path& f : files)
    if (!fs::exists(f)) throw rig::InputError(context + ": " + f.string() + ": no such image file");
  const Image src = source(first);
  effectiveCrop(crop, src.width, src.height, context + ": crop");
}

FootageSequence openFootage(const fs::path& pattern) {
  const std::optional<scene::FrameSequence> sequence = scene::FrameSequence::parse(pattern);
  FootageSequence seq;
  seq.name = pattern.string();
  if (!sequence) {
    if (!fs::exists(pattern)) throw rig::InputError(pattern.string() + ": no such image file");
    seq.files = {pattern};
    return seq;
  }
  const std::map<int, fs::path> found = sequence->scan();
  if (found.empty()) throw rig::InputError(pattern.string() + ": no frames match this sequence pattern");
  seq.first = found.begin()->first;
  for (const auto& [number, file] : found) {
    if (number != seq.first + int(seq.files.size()))
      throw rig::InputError(pattern.string() + ": frame " + std::to_string(seq.first + int(seq.files.size())) +
                       " is missing (found frames " + std::to_string(seq.first) + " to " +
                       std::to_string(found.rbegin()->first) + ")");
    seq.files.push_back(file);
  }
  return seq;
}

FootageSequence openFootage(std::vector<fs::path> files, int first) {
  if (files.empty()) throw rig::InputError("footage: expected at least one image file, got none");
  for (const fs::path& f : files)
    if (!fs::exists(f)) throw rig::InputError(f.string() + ": no such image file");
  FootageSequence seq;
  seq.name = files.front().string();
  seq.files = std::move(files);
  seq.first = first;
  return seq;
}

std::vector<Image> cutPlate(const Image& plate, const scene::PlateGrid& g, const std::string& context) {
  const auto need = [&](bool ok, const std::string& field, const std::string& expected) {
    if (!ok) throw rig::InputError(context + ": grid." + field + ": " + expected);
  };
  need(g.rows >= 1, "rows", "expected an integer >= 1, got " + std::to_string(g.rows));
  need(g.columns >= 1, "columns", "expected an integer >= 1, got " + std::to_string(g.columns));
  need(g.margin_left >= 0 && g.margin_top >= 0 && g.margin_right >= 0 && g.margin_bottom >= 0, "margins",
       "expected pixels >= 0");
  const double cw = double(plate.width - g.margin_left - g.margin_right) / g.columns;
  const double ch = double(plate.height - g.margin_top - g.margin_bottom) / g.rows;
  need(cw >= 1 && ch >= 1, "margins",
       "leave no room for " + std::to_string(g.rows) + "x" + std::to_string(g.columns) + " cells in the " +
           sizeText(plate.width, plate.height) + " plate");
  const scene::PixelRect crop = g.cell_crop.empty() ? scene::PixelRect{0, 0, int(cw), int(ch)} : g.cell_crop;
  need(crop.x >= 0 && crop.y >= 0 && crop.width > 0 && crop.height > 0, "cell_crop",
       "expected x, y >= 0 and a width and height > 0, got " + rectText(crop));

  std::vector<float> lum;
  if (g.snap) {
    lum.resize(plate.pixelCount());
    for (size_t i = 0; i < lum.size(); ++i) {
      const glm::vec4& c = plate.rgba[i];
      lum[i] = linearToSrgb(0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z);
    }
  }
  std::vector<Image> frames;
  for (int row = 0; row < g.rows; ++row)
    for (int col = 0; col < g.columns; ++col) {
      int x0 = int(std::lround(g.margin_left + col * cw)), y0 = int(std::lround(g.margin_top + row * ch));
      if (g.snap) {
        const int slack_x = std::max(1, int(cw / 8)), slack_y = std::max(1, int(ch / 8));
        x0 = snapEdge(lum, plate.width, plate.height, true, x0, slack_x, y0 + int(ch / 4), y0 + int(3 * ch / 4));
        y0 = snapEdge(lum, plate.width, plate.height, false, y0, slack_y, x0 + int(cw / 4), x0 + int(3 * cw / 4));
      }
      const scene::PixelRect r{x0 + crop.x, y0 + crop.y, crop.width, crop.height};
      need(r.x + r.width <= plate.width && r.y + r.height <= plate.height, "cell_crop",
           rectText(crop) + " of cell " + std::to_string(int(frames.size()) + 1) + " (at " + std::to_string(x0) + "," +
               std::to_string(y0) + ") lies outside the " + sizeText(plate.width, plate.height) + " plate");
      Image f(r.width, r.height);
      for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) f.at(x, y) = plate.at(r.x + x, r.y + y);
      frames.push_back(std::move(f));
    }
  return frames;
}

std::vector<Image> cutPlate(const fs::path& plate_file, const scene::PlateGrid& grid) {
  return cutPlate(readLinearImage(plate_file), grid, plate_file.string());
}

bool referenceAvailable(const scene::ReferenceSpec& ref) {
  if (!scene::FrameSequence::isPattern(ref.file)) return fs::is_regular_file(ref.file);
  try {
    openFootage(ref.file);
    return true;
  } catch (const rig::InputError&) {
    return false;
  }
}

FootageSequence openReference(const scene::ReferenceSpec& ref, const std::string& context) {
  FootageSequence seq;
  if (ref.grid) {
    seq.images = cutPlate(readLinearImage(ref.file), *ref.grid, context + ": " + ref.file.string());
    seq.name = ref.file.string();
  } else {
    seq = openFootage(ref.file);
  }
  seq.offset = ref.offset;
  seq.rate = ref.rate;
  seq.edge = ref.edge;
  seq.crop = ref.crop;
  seq.scale = ref.scale;
  seq.position = ref.position;
  seq.flip_x = ref.flip_x;
  seq.validate(context);
  if (!ref.shift_x.empty() && int(ref.shift_x.size()) != seq.frameCount())
    throw rig::InputError(context + ": shift_x: expected one shift per footage frame (" + std::to_string(seq.frameCount()) +
                     "), got " + std::to_string(ref.shift_x.size()));
  seq.shift_x = ref.shift_x;
  return seq;
}

LayerStyle referenceStyle(const scene::ReferenceSpec& ref, const std::string& ours_label) {
  LayerStyle s;
  s.mode = ref.mode;
  s.opacity = ref.opacity;
  s.ours_label = ours_label;
  s.other_label = ref.label;
  return s;
}

Image layeredFrame(const FootageSequence& a, const FootageSequence& b, int frame, const LayerStyle& style, bool placed,
                   int blank_width, int blank_height) {
  const Image ours = a.source(frame);
  const int mapped = frame - a.first + 1;
  Image other;
  if (placed) {
    other = b.frame(mapped, ours.width, ours.height);
  } else if (const std::optional<int> their = b.theirFrame(mapped)) {
    const Image src = b.source(*their);
    const scene::PixelRect c = b.crop.empty() ? scene::PixelRect{0, 0, src.width, src.height} : b.crop;
    FootageSequence one;
    one.images = {src};
    one.crop = c;
    one.name = b.name;
    other = one.frame(1, c.width, c.height);
  } else {
    other = Image(blank_width, blank_height);
  }
  if (style.mode != scene::LayerMode::OnionSkin) return layerFrame(ours, other, style);
  const int last = a.first + a.frameCount() - 1;
  std::vector<Image> ghosts;
  std::vector<int> offsets;
  for (int g : onionGhostFrames(frame, style, a.first, last)) {
    ghosts.push_back(a.source(g));
    offsets.push_back(g - frame);
  }
  return onionSkin(ours, ghosts, offsets, other, style);
}

}  // namespace stirrup::render
