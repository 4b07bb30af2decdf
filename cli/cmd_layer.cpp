// stirrup layer A B -o OUT: composites two image sequences frame by frame (side by side, over,
// difference, onion skin), with B mapped onto A's frames by an offset and a rate and placed by a crop,
// a scale and a position: the layered view of the review movies on its own (render/review/layer.h).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "render/review/layer.h"
#include "render/tracer/image.h"
#include "rig/error.h"
#include "scene/frame_range.h"
#include "scene/frame_sequence.h"
#include "scene/scene.h"

namespace stirrup::cli {
namespace {

namespace fs = std::filesystem;

struct LayerOptions {
  std::string a, b, out, scene;
  bool mode_given = false, opacity_given = false, label_b_given = false;
  std::string frames;
  std::string mode = "over";
  float opacity = 0.5f;
  float gain = 4.0f;
  std::string coverage = "matte";
  int offset = 0;
  double rate = 1.0;
  std::string edge = "hold";
  std::string crop;
  std::optional<float> scale;
  std::string position;
  bool flip_x = false;
  std::string grid, margins, cell_crop;
  bool snap = false;
  int onion_frames = 2, onion_step = 1;
  std::string label_a = "A", label_b = "B";
  bool no_labels = false;
  bool allow_impossible = false;  // --scene beyond a horse's limits: its reference block is read anyway
};

bool isPattern(const std::string& s) { return scene::FrameSequence::isPattern(s); }

// NAME.####.ext (or NAME.%04d.ext) with the frame number filled in; one image is itself.
fs::path frameFile(const std::string& pattern, int frame) {
  const std::optional<scene::FrameSequence> sequence = scene::FrameSequence::parse(pattern);
  return sequence ? sequence->path(frame) : fs::path(pattern);
}

glm::vec2 parsePosition(const std::string& text) {
  std::istringstream s(text);
  float x = 0, y = 0;
  char comma = 0;
  if (!(s >> x >> comma >> y) || comma != ',' || !(s >> std::ws).eof())
    throw rig::InputError("--position: expected x,y in pixels of A's frame, got \"" + text + "\"");
  return {x, y};
}

scene::PlateGrid parseGrid(const LayerOptions& o) {
  scene::PlateGrid g;
  std::istringstream s(o.grid);
  char x = 0;
  if (!(s >> g.rows >> x >> g.columns) || (x != 'x' && x != 'X') || !(s >> std::ws).eof() || g.rows < 1 ||
      g.columns < 1)
    throw rig::InputError("--grid: expected ROWSxCOLUMNS (for example 2x6), got \"" + o.grid + "\"");
  if (!o.margins.empty()) {
    std::istringstream m(o.margins);
    char c1 = 0, c2 = 0, c3 = 0;
    if (!(m >> g.margin_left >> c1 >> g.margin_top >> c2 >> g.margin_right >> c3 >> g.margin_bottom) || c1 != ',' ||
        c2 != ',' || c3 != ',' || !(m >> std::ws).eof() || g.margin_left < 0 || g.margin_top < 0 ||
        g.margin_right < 0 || g.margin_bottom < 0)
      throw rig::InputError("--margins: expected left,top,right,bottom in pixels >= 0, got \"" + o.margins + "\"");
  }
  if (!o.cell_crop.empty()) g.cell_crop = scene::parsePixelRect(o.cell_crop, "--cell-crop");
  g.snap = o.snap;
  return g;
}

render::LayerCoverage parseCoverage(const std::string& s) {
  if (s == "matte") return render::LayerCoverage::Matte;
  if (s == "alpha") return render::LayerCoverage::Alpha;
  if (s == "full") return render::LayerCoverage::Full;
  throw rig::InputError("--coverage: expected matte, alpha or full, got \"" + s + "\"");
}

scene::FootageEdge parseEdge(const std::string& s) {
  if (s == "hold") return scene::FootageEdge::Hold;
  if (s == "loop") return scene::FootageEdge::Loop;
  if (s == "blank") return scene::FootageEdge::Blank;
  throw rig::InputError("--edge: expected hold, loop or blank, got \"" + s + "\"");
}

// B and the style from a scene's "reference" block; false (after saying so) when its file is absent.
bool referenceFromScene(const LayerOptions& o, render::FootageSequence& b, render::LayerStyle& style) {
  const scene::SceneSpec scene = scene::loadScene(o.scene, {o.allow_impossible});
  if (!scene.reference)
    throw rig::InputError(o.scene + ": reference: expected a \"reference\" block naming the footage (see docs/layered.md)");
  const scene::ReferenceSpec& ref = *scene.reference;
  if (!render::referenceAvailable(ref)) {
    std::printf("%s: skipped: the reference footage %s is not there\n", o.scene.c_str(), ref.file.string().c_str());
    return false;
  }
  b = render::openReference(ref, o.scene + ": reference");
  if (!o.mode_given) style.mode = ref.mode;
  if (!o.opacity_given) style.opacity = ref.opacity;
  if (!o.label_b_given) style.other_label = ref.label;
  return true;
}

void runLayer(const LayerOptions& o) {
  // Everything is checked before the first frame is written.
  render::LayerStyle style;
  style.mode = scene::parseLayerMode(o.mode, "--mode");
  style.opacity = o.opacity;
  style.difference_gain = o.gain;
  style.coverage = parseCoverage(o.coverage);
  style.onion_frames = o.onion_frames;
  style.onion_step = o.onion_step;
  style.labels = !o.no_labels;
  style.ours_label = o.label_a;
  style.other_label = o.label_b;

  // A: ours, a sequence or one image.
  const render::FootageSequence a = render::openFootage(fs::path(o.a));
  const bool a_sequence = isPattern(o.a);
  std::vector<int> frames;
  if (o.frames.empty()) {
    for (int f = a.first; f < a.first + a.frameCount(); ++f) frames.push_back(f);
  } else {
    frames = scene::parseFrameList(o.frames, "--frames");
    for (int f : frames)
      if (f < a.first || f >= a.first + a.frameCount())
        throw rig::InputError(o.a + ": frame " + std::to_string(f) + " is not in the sequence (it has frames " +
                         std::to_string(a.first) + "-" + std::to_string(a.first + a.frameCount() - 1) + ")");
  }
  if (!a_sequence && frames.size() > 1) throw rig::InputError("--frames: A is one image, so give at most one frame");
  if (frames.size() > 1 && !isPattern(o.out))
    throw rig::InputError("-o: expected a sequence pattern like OUT.####.png for " + std::to_string(frames.size()) +
                     " frames, got \"" + o.out + "\"");
  const std::string ext = fs::path(o.out).extension().string();
  if (ext != ".png" && ext != ".exr") throw rig::InputError("-o: expected a .png or .exr file or pattern, got \"" + o.out + "\"");
  if (const fs::path dir = fs::path(o.out).parent_path(); !dir.empty() && !fs::is_directory(dir))
    throw rig::InputError("-o: no such folder " + dir.string());

  // B: a scene's reference footage, the other sequence, an image, or a plate cut into frames.
  render::FootageSequence b;
  const bool placement_given = o.scale.has_value() || !o.position.empty() || !o.crop.empty() || o.offset != 0 ||
                               o.rate != 1.0 || o.flip_x || !o.grid.empty();
  if (!o.scene.empty()) {
    if (!o.b.empty()) throw rig::InputError("--scene: the scene's reference is B; give A and -o only");
    if (placement_given)
      throw rig::InputError("--scene: the scene's reference block places B; edit it rather than giving --crop, --scale, ...");
    if (!referenceFromScene(o, b, style)) return;
  } else if (o.b.empty()) {
    throw rig::InputError("expected B (a sequence, an image or a plate) or --scene SCENE with a reference block");
  } else if (!o.grid.empty()) {
    b.images = render::cutPlate(render::readLinearImage(o.b), parseGrid(o), o.b);
    b.name = o.b;
  } else {
    if (!o.margins.empty() || !o.cell_crop.empty() || o.snap)
      throw rig::InputError("--margins, --cell-crop and --snap cut a plate: give --grid ROWSxCOLUMNS too");
    b = render::openFootage(fs::path(o.b));
    // B numbered like A: offset 0 shows B's first frame at A's first frame.
  }
  if (o.scene.empty()) {
    b.offset = o.offset;
    b.rate = o.rate;
    b.edge = parseEdge(o.edge);
    if (!o.crop.empty()) b.crop = scene::parsePixelRect(o.crop, "--crop");
    b.flip_x = o.flip_x;
  }

  const render::Image first_a = a.source(frames.front());
  const render::Image first_b = b.source(b.first);
  const int crop_w = b.crop.empty() ? first_b.width : b.crop.width;
  const int crop_h = b.crop.empty() ? first_b.height : b.crop.height;
  // Side by side without placement shows B as it is (cropped); the other modes need B on A's canvas,
  // by default scaled to A's height and centred.
  const bool placed = !o.scene.empty() || o.scale.has_value() || !o.position.empty() ||
                      style.mode != scene::LayerMode::SideBySide;
  if (o.scene.empty()) {
    b.scale = o.scale.value_or(float(first_a.height) / float(crop_h));
    b.position = o.position.empty() ? glm::vec2((first_a.width - crop_w * b.scale) / 2.0f, 0.0f) : parsePosition(o.position);
    if (!placed) {
      b.scale = 1.0f;
      b.position = {0.0f, 0.0f};
    }
    b.validate("B (" + o.b + ")");
  }

  for (int f : frames) {
    const render::Image out = render::layeredFrame(a, b, f, style, placed, crop_w, crop_h);
    const fs::path file = frameFile(o.out, f);
    if (ext == ".exr")
      render::writeExr(out, file, {{"stirrup:frame", std::to_string(f)}, {"stirrup:layer", scene::layerModeName(style.mode)}});
    else
      render::writePng(out, file);
  }
}

}  // namespace

void addLayerCommand(CLI::App& app) {
  auto o = std::make_shared<LayerOptions>();
  CLI::App* cmd = app.add_subcommand("layer", "Composite two image sequences frame by frame (layered comparisons)");
  cmd->footer(
      "A is ours (a render: NAME.####.png or .exr, or one image); B is the other sequence, an image, or a\n"
      "plate of frames in a grid (--grid). Our frame f shows B's frame\n"
      "  B.first + offset + floor((f - A.first) * rate)   (--edge: hold, loop or blank outside B)\n"
      "B's --crop rectangle is scaled by --scale and put at --position (pixels of A's frame); without them\n"
      "B is scaled to A's height and centred (side-by-side shows B as it is, at A's height).\n"
      "Modes: side-by-side (labelled), over (A over B at --opacity, keyed by --coverage), difference\n"
      "(|A - B| x --gain), onion-skin (A over tinted ghosts of its neighbouring frames, over B).\n"
      "Example: stirrup layer out/gallop/gallop_side.####.png muybridge-plate.jpg --grid 2x6 --snap \\\n"
      "           --cell-crop 0,0,452,424 --edge loop -o out/gallop/gallop_layered.####.png --mode over");
  cmd->add_option("a", o->a, "Our sequence NAME.####.png (or one image)")->required();
  cmd->add_option("b", o->b, "The other sequence, image or plate (or --scene)");
  cmd->add_option("--scene", o->scene, "B is this scene's reference footage, placed as its \"reference\" block says");
  cmd->add_option("-o,--out", o->out, "Output NAME.####.png or .exr (one file when A is one image)")->required();
  cmd->add_option("--frames", o->frames, "A's frames to composite, e.g. 1-120x2 (default: all of A)");
  cmd->add_option("--mode", o->mode, "side-by-side, over, difference or onion-skin (default over)");
  cmd->add_option("--opacity", o->opacity, "Over: A's opacity; onion-skin: the nearest ghosts' (default 0.5)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--gain", o->gain, "Difference: |A - B| is multiplied by this (default 4)")->check(CLI::PositiveNumber);
  cmd->add_option("--coverage", o->coverage, "What of A lies over B: matte (A's matte pass, else all), alpha or full");
  cmd->add_option("--offset", o->offset, "B frames to skip: B's frame shown at A's first frame (default 0)");
  cmd->add_option("--rate", o->rate, "B frames per A frame: B's fps / A's fps (default 1)")->check(CLI::PositiveNumber);
  cmd->add_option("--edge", o->edge, "Outside B's frames: hold, loop or blank (default hold)");
  cmd->add_option("--crop", o->crop, "x,y,w,h: the part of each B frame to use (default all)");
  cmd->add_option("--scale", o->scale, "B pixels to A pixels (default: B's crop fits A's height)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--position", o->position, "x,y: where B's crop's top-left goes in A's frame (default: centred)");
  cmd->add_flag("--flip-x", o->flip_x, "Mirror B (a horse going the other way)");
  cmd->add_option("--grid", o->grid, "B is a plate: ROWSxCOLUMNS of frames, read row by row");
  cmd->add_option("--margins", o->margins, "Plate margins left,top,right,bottom (default 0,0,0,0)");
  cmd->add_option("--cell-crop", o->cell_crop, "x,y,w,h of the picture in each cell (leave out the frame number)");
  cmd->add_flag("--snap", o->snap, "Move each cell to its photograph's top-left corner (the plate's dark border)");
  cmd->add_option("--onion-frames", o->onion_frames, "Onion skin: ghosts each side (default 2)")->check(CLI::Range(0, 16));
  cmd->add_option("--onion-step", o->onion_step, "Onion skin: frames between ghosts (default 1)")->check(CLI::Range(1, 1000));
  cmd->add_option("--label-a", o->label_a, "Side-by-side: A's label (default A)");
  cmd->add_option("--label-b", o->label_b, "Side-by-side: B's label (default B)");
  cmd->add_flag("--no-labels", o->no_labels, "Side-by-side: no labels");
  cmd->add_flag("--allow-impossible", o->allow_impossible,
                "Read --scene's reference even when the scene is beyond a horse's limits (docs/horse-limits.md)");
  cmd->callback([o, cmd] {
    o->mode_given = cmd->count("--mode") > 0;
    o->opacity_given = cmd->count("--opacity") > 0;
    o->label_b_given = cmd->count("--label-b") > 0;
    runLayer(*o);
  });
}

}  // namespace stirrup::cli
