#include "scene/reference_spec.h"

#include <array>
#include <cmath>
#include <sstream>

#include "rig/error.h"

namespace stirrup::scene {

namespace fs = std::filesystem;

namespace {

std::string rectText(const PixelRect& r) {
  return std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.width) + "," + std::to_string(r.height);
}

}  // namespace

LayerMode parseLayerMode(const std::string& name, const std::string& context) {
  if (name == "side-by-side") return LayerMode::SideBySide;
  if (name == "over") return LayerMode::Over;
  if (name == "difference") return LayerMode::Difference;
  if (name == "onion-skin" || name == "onion") return LayerMode::OnionSkin;
  throw rig::InputError(context + ": expected side-by-side, over, difference or onion-skin, got \"" + name + "\"");
}

const char* layerModeName(LayerMode mode) {
  switch (mode) {
    case LayerMode::SideBySide: return "side-by-side";
    case LayerMode::Over: return "over";
    case LayerMode::Difference: return "difference";
    case LayerMode::OnionSkin: return "onion-skin";
  }
  return "?";
}

PixelRect parsePixelRect(const std::string& text, const std::string& context) {
  PixelRect r;
  char c1 = 0, c2 = 0, c3 = 0;
  std::istringstream s(text);
  if (!(s >> r.x >> c1 >> r.y >> c2 >> r.width >> c3 >> r.height) || c1 != ',' || c2 != ',' || c3 != ',' ||
      !(s >> std::ws).eof() || r.width <= 0 || r.height <= 0 || r.x < 0 || r.y < 0)
    throw rig::InputError(context + ": expected x,y,width,height in pixels (x, y >= 0; width, height > 0), got \"" +
                     text + "\"");
  return r;
}

// Pixel sizes, places and shifts of footage: within 65536 (the largest image OpenImageIO's formats hold a
// side of, and far past any plate); a plate's grid of at most 1000 cells a side.
constexpr double kMaxPixels = 65536.0;
constexpr int kMaxGridCells = 1000;

ReferenceSpec parseReferenceSpec(rig::JsonObjectReader r, const fs::path& scene_dir) {
  ReferenceSpec ref;
  const std::string file = r.string("file", "");
  if (file.empty()) r.fail("file", "expected an image, a plate or a NAME.####.ext sequence, relative to the scene file");
  ref.file = scene_dir / file;
  const auto rect = [&](rig::JsonObjectReader& o, const std::string& key, PixelRect fallback) {
    if (!o.has(key)) return fallback;
    const std::array<double, 4> v = o.numbers<4>(key, {}, 0.0, kMaxPixels);
    for (double d : v)
      if (d != std::floor(d)) o.fail(key, "expected whole pixels [x, y, width, height]");
    const PixelRect p{int(v[0]), int(v[1]), int(v[2]), int(v[3])};
    if (p.x < 0 || p.y < 0 || p.width <= 0 || p.height <= 0)
      o.fail(key, "expected [x, y, width, height] with x, y >= 0 and width, height > 0, got " + rectText(p));
    return p;
  };
  if (r.has("grid")) {
    rig::JsonObjectReader g = r.object("grid");
    PlateGrid grid;
    grid.rows = g.integer("rows", grid.rows, 1, kMaxGridCells, "a count of rows");
    grid.columns = g.integer("columns", grid.columns, 1, kMaxGridCells, "a count of columns");
    const std::array<double, 4> m = g.numbers<4>("margins", {0, 0, 0, 0}, 0.0, kMaxPixels);
    for (double d : m)
      if (d < 0 || d != std::floor(d)) g.fail("margins", "expected whole pixels >= 0 [left, top, right, bottom]");
    grid.margin_left = int(m[0]);
    grid.margin_top = int(m[1]);
    grid.margin_right = int(m[2]);
    grid.margin_bottom = int(m[3]);
    grid.cell_crop = rect(g, "cell_crop", grid.cell_crop);
    grid.snap = g.boolean("snap", grid.snap);
    g.finish();
    ref.grid = grid;
  }
  ref.offset = r.integer("offset", ref.offset, -1000000, 1000000, "a frame offset");
  ref.rate = r.number("rate", ref.rate, 0.001, 1000.0, "their frames per our frame");
  const std::string edge = r.string("edge", "loop");
  if (edge == "hold") ref.edge = FootageEdge::Hold;
  else if (edge == "loop") ref.edge = FootageEdge::Loop;
  else if (edge == "blank") ref.edge = FootageEdge::Blank;
  else r.fail("edge", "expected \"hold\", \"loop\" or \"blank\", got \"" + edge + "\"");
  ref.crop = rect(r, "crop", ref.crop);
  ref.scale = float(r.number("scale", ref.scale, 0.001, 1000.0));
  const std::array<double, 2> pos = r.numbers<2>("position", {ref.position.x, ref.position.y}, -kMaxPixels, kMaxPixels);
  ref.position = glm::vec2(float(pos[0]), float(pos[1]));
  ref.flip_x = r.boolean("flip_x", ref.flip_x);
  if (const nlohmann::json* v = r.value("shift_x")) {
    if (!v->is_array()) r.fail("shift_x", "expected an array of pixel shifts, one per footage frame");
    for (size_t i = 0; i < v->size(); ++i) {
      const std::string at = "shift_x[" + std::to_string(i) + "]";
      if (!(*v)[i].is_number()) r.fail(at, "expected a number, got " + rig::describeJson((*v)[i]));
      const double d = (*v)[i].get<double>();
      if (!(d >= -kMaxPixels && d <= kMaxPixels)) r.fail(at, rig::JsonObjectReader::rangeText(-kMaxPixels, kMaxPixels, d, "pixels"));
      ref.shift_x.push_back(float(d));
    }
  }
  if (r.has("mode")) {
    const std::string mode = r.string("mode", "");
    try {
      ref.mode = parseLayerMode(mode, "mode");
    } catch (const rig::InputError&) {
      r.fail("mode", "expected side-by-side, over, difference or onion-skin, got \"" + mode + "\"");
    }
  }
  ref.opacity = float(r.number("opacity", ref.opacity, 0.0, 1.0));
  ref.label = r.string("label", ref.label);
  r.finish();
  return ref;
}

}  // namespace stirrup::scene
