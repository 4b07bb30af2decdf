// Layered comparisons (Kuhnel 2003, 4.3-4.4; the thesis's *_layered.mov): a render composited frame
// by frame with another image sequence, either reference footage (Muybridge's plates, any image
// sequence, placed with a frame offset, rate, crop, scale and position so the horses line up) or
// another render of the same clip (the rigged rider against the rider rigidly fixed to the saddle,
// two rig profiles, this version against the last).
//
// Everything here is a pure function of its inputs: no globals, no caches, no clocks, so any frame of
// a layered movie can be made alone, in any order, on any machine.
//
// Colour: Image is linear light (render/tracer/image.h). Footage files are decoded to linear (8-bit and
// 16-bit files are treated as sRGB, float files as linear). Greyscale files fill R, G and B.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "render/tracer/image.h"
#include "scene/reference_spec.h"

namespace stirrup::render {

// ---------------------------------------------------------------------------------------------------
// Per-frame composites


// Which part of `ours` lies over `other` in Over and OnionSkin.
enum class LayerCoverage {
  Matte,  // the horse and rider only (Image::matte); falls back to Full when ours has no matte pass
  Alpha,  // ground and characters (Image::rgba alpha); the sky lets `other` through
  Full,   // the whole frame: a plain cross-dissolve at `opacity`
};

struct LayerStyle {
  scene::LayerMode mode = scene::LayerMode::SideBySide;

  // Over: out = k * ours + (1 - k) * other with k = opacity * coverage(ours) per pixel.
  // OnionSkin: opacity of the nearest ghost frames (see onion_falloff).
  float opacity = 0.5f;
  LayerCoverage coverage = LayerCoverage::Matte;

  // Difference: out.rgb = min(1, difference_gain * |ours.rgb - other.rgb|), alpha 1, so small
  // differences are visible; identical pixels are black.
  float difference_gain = 4.0f;

  // OnionSkin: `onion_frames` neighbours each side of the current frame of ours are laid, matte-keyed
  // and tinted (earlier frames onion_before, later ones onion_after, like a 2D animator's light table),
  // over `other`; ghost d frames away has opacity opacity * onion_falloff^(d-1); the current frame
  // of ours goes on top at full coverage.
  int onion_frames = 2;
  int onion_step = 1;  // frames between ghosts
  float onion_falloff = 0.5f;
  glm::vec4 onion_before = {1.0f, 0.35f, 0.25f, 1.0f};  // multiplies the ghost's colour
  glm::vec4 onion_after = {0.25f, 0.6f, 1.0f, 1.0f};

  // SideBySide: ours on the left, other on the right, both at ours' height (other is resampled to
  // that height keeping its aspect), separated by `gap` pixels of gap_colour. Labels burn in at each
  // side's top left when `labels` is set (upper-case letters, digits and - _ . : / ( ) % + =; other
  // characters print as spaces), `label_scale` pixels per font pixel (the font is 5x7).
  int gap = 4;
  glm::vec4 gap_colour = {0.0f, 0.0f, 0.0f, 1.0f};
  bool labels = true;
  std::string ours_label = "RIGGED";
  std::string other_label = "RIGID";
  int label_scale = 2;
};

// The composite of one frame. Over and Difference need both images the same size (InputError
// otherwise: use FootageSequence::frame to place footage on a canvas of the render's size). The
// result is a review picture: rgba only (no passes), alpha 1.
// With mode OnionSkin this is onionSkin() with no ghosts: ours over other at full coverage.
Image layerFrame(const Image& ours, const Image& other, const LayerStyle& style);

// Onion skin: `ghosts[i]` is frame current + ghost_offsets[i] of ours (offsets non-zero; negative:
// earlier). Ghosts are laid farthest first, then ours on top. Every image must be ours' size.
Image onionSkin(const Image& ours, std::span<const Image> ghosts, std::span<const int> ghost_offsets,
                const Image& other, const LayerStyle& style);

// The frames of ours an onion skin of `frame` needs, earliest first, without `frame` itself,
// restricted to [first, last]: frame +- k * onion_step for k = 1..onion_frames.
std::vector<int> onionGhostFrames(int frame, const LayerStyle& style, int first, int last);

// Burns `text` into `image` with its top-left at (x, y) in `colour` on a dark box (for labels).
void drawLabel(Image& image, int x, int y, const std::string& text, int scale = 2,
               glm::vec4 colour = {1.0f, 1.0f, 1.0f, 1.0f});

// ---------------------------------------------------------------------------------------------------
// Footage


// Reads any image OpenImageIO can (PNG, JPEG, TIFF, EXR...) into linear RGBA, plus the matte pass
// when the file has a "matte" channel (stirrup's EXRs); InputError naming the file when it is missing
// or unreadable.
Image readLinearImage(const std::filesystem::path& file);


// Another image sequence mapped onto our frames and placed on our canvas.
//   their frame number = first + offset + floor((our_frame - 1) * rate)   (then FootageEdge)
// where `first` is the sequence's first frame number; so with offset 0 and rate 1 our frame 1 shows
// their first frame, and rate = their fps / our fps plays footage shot at another rate in real time.
// Placement: the `crop` rectangle of their frame (empty: all of it) is scaled by `scale` and its top
// left put at `position` (pixels of our canvas); flip_x mirrors it (a horse going the other way).
struct FootageSequence {
  // Source: files[i] is frame number first + i. Or, when images is not empty, images[i] is (e.g. the
  // frames cut from a plate).
  std::vector<std::filesystem::path> files;
  std::vector<Image> images;
  int first = 1;
  std::string name;  // for errors and labels (the pattern or the plate file)

  int offset = 0;
  double rate = 1.0;
  scene::FootageEdge edge = scene::FootageEdge::Hold;
  scene::PixelRect crop;
  float scale = 1.0f;
  glm::vec2 position = {0.0f, 0.0f};
  bool flip_x = false;
  // Per-frame horizontal shifts in their pixels (empty: none), added to the placement of frame
  // first + i before scaling, so a horse that wanders in its frames (Muybridge's cameras stood in a
  // row; ours follows the horse) holds still.
  std::vector<float> shift_x;

  int frameCount() const { return images.empty() ? int(files.size()) : int(images.size()); }
  // Their frame number shown at our frame; nullopt when outside the footage with edge Blank.
  std::optional<int> theirFrame(int our_frame) const;
  // Their frame, unplaced, in linear light. InputError when it is missing or unreadable.
  Image source(int their_frame) const;
  // The footage for our frame, placed on a width x height canvas (black, alpha 0 where it does not
  // reach). InputError when the crop lies outside the frame.
  Image frame(int our_frame, int width, int height) const;
  // Checks the settings and the first frame (exists, crop inside it); InputError naming the field.
  void validate(const std::string& context) const;
};

// A sequence from "DIR/name.####.ext" (or name.%04d.ext; any number of #), listing the directory for
// the existing frames (must be contiguous), or from a single file (a one-frame sequence).
// InputError when nothing matches or a frame is missing in the middle.
FootageSequence openFootage(const std::filesystem::path& pattern);
// A sequence from an explicit list of files, frame numbers first, first + 1, ...
FootageSequence openFootage(std::vector<std::filesystem::path> files, int first = 1);

// InputError naming `context` and the field when the grid does not fit the plate.
std::vector<Image> cutPlate(const Image& plate, const scene::PlateGrid& grid, const std::string& context);
std::vector<Image> cutPlate(const std::filesystem::path& plate_file, const scene::PlateGrid& grid);

// ---------------------------------------------------------------------------------------------------
// ReferenceSpec, a scene's "reference" block, is in scene/reference_spec.h.

// True when the reference's file (or the first frame of its pattern) exists; a layered movie against
// a missing reference is skipped with a message, not an error.
bool referenceAvailable(const scene::ReferenceSpec& ref);
// The footage the spec describes (the plate cut when it has a grid); InputError naming `context`.
FootageSequence openReference(const scene::ReferenceSpec& ref, const std::string& context);
// A LayerStyle from the spec's mode, opacity and label (ours labelled `ours_label`).
LayerStyle referenceStyle(const scene::ReferenceSpec& ref, const std::string& ours_label = "STIRRUP");

// Frame `frame` of A composited with B, as `stirrup layer` writes it: B's frame is the one for A's
// frame counted from A's first frame (b.theirFrame(frame - a.first + 1)). `placed`: B is placed on A's
// canvas (FootageSequence::frame); otherwise B is shown as it is, cropped, beside A, and a frame B does
// not have is blank at blank_width x blank_height. Onion skin takes its ghosts from A.
Image layeredFrame(const FootageSequence& a, const FootageSequence& b, int frame, const LayerStyle& style, bool placed,
                   int blank_width, int blank_height);

}  // namespace stirrup::render
