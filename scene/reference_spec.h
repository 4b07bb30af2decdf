// What a scene asks of its layered view, as data (no pixels): the "reference" block of a scene file
// (SceneSpec::reference) and the layer modes, rectangles and plate grids it names. The compositing
// that uses them is review work (render/review/layer.h); the scene document only reads and checks them.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "rig/io/json_fields.h"

namespace stirrup::scene {

// How two sequences are laid together (render/review/layer.h LayerStyle).
enum class LayerMode { SideBySide, Over, Difference, OnionSkin };

// "side-by-side", "over", "difference", "onion-skin" (also "onion"); InputError naming `context`.
LayerMode parseLayerMode(const std::string& name, const std::string& context);
const char* layerModeName(LayerMode mode);  // the canonical spellings above

struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;  // top-left origin; empty (width or height 0): the whole image
  bool empty() const { return width <= 0 || height <= 0; }
};
// "x,y,w,h" -> PixelRect; InputError naming `context`.
PixelRect parsePixelRect(const std::string& text, const std::string& context);

// What happens when an our-frame maps before the first or after the last footage frame.
enum class FootageEdge { Hold, Loop, Blank };

// A plate of frames in a grid (Muybridge's): rows x columns cells inside the plate's margins, read
// row by row, left to right. Each cell is (plate - margins) / columns wide (likewise high); within a
// cell, `cell_crop` (cell pixels; empty: the whole cell) keeps the picture and leaves out the printed
// frame number and the borders. Every frame has cell_crop's size.
//
// Real plates are not a perfect grid (Muybridge's is two half-plates with a wider gutter between
// them, and its rows are not evenly spaced). With `snap`, each cell's origin moves to the top-left
// corner of its photograph: the last dark column (row) of the plate's border within an eighth of a
// cell of the nominal edge, "dark" meaning below 30% of the way from the darkest to the brightest
// column (row) mean there. Without a dark border nearby the nominal edge stays.
struct PlateGrid {
  int rows = 1, columns = 1;
  int margin_left = 0, margin_top = 0, margin_right = 0, margin_bottom = 0;
  PixelRect cell_crop;
  bool snap = false;
};

// A scene's "reference" block (scene/scene.h: SceneSpec::reference): footage for the layered view.
//   "reference": {"file": "../../shared/reference/muybridge/horse-and-rider-gallop-plate.jpg",
//                 "grid": {"rows": 2, "columns": 6, "margins": [l, t, r, b], "cell_crop": [x, y, w, h]},
//                 "offset": 0, "rate": 1.0, "edge": "loop", "crop": [x, y, w, h], "scale": 0.7,
//                 "position": [x, y], "flip_x": false, "shift_x": [...], "mode": "over", "opacity": 0.5,
//                 "label": "MUYBRIDGE 1887"}
// `file` is relative to the scene file: a plate (with "grid"), an image, or a name.####.ext pattern.
struct ReferenceSpec {
  std::filesystem::path file;       // resolved (absolute or relative to the working directory)
  std::optional<PlateGrid> grid;
  int offset = 0;
  double rate = 1.0;
  FootageEdge edge = FootageEdge::Loop;
  PixelRect crop;
  float scale = 1.0f;
  glm::vec2 position = {0.0f, 0.0f};
  bool flip_x = false;
  std::vector<float> shift_x;       // "shift_x": one per footage frame, or absent (FootageSequence::shift_x)
  LayerMode mode = LayerMode::Over;
  float opacity = 0.5f;
  std::string label = "REFERENCE";
};

// Parses the block `r` points at; `file` is resolved against scene_dir. A wrong type or value is an
// InputError naming the scene file and the field ("scenes/x.json: reference.grid.rows: ..."). A
// missing file is not an error here (render/review/layer.h referenceAvailable).
ReferenceSpec parseReferenceSpec(rig::JsonObjectReader r, const std::filesystem::path& scene_dir);

}  // namespace stirrup::scene
