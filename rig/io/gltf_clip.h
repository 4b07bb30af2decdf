// Horse clips as glTF 2.0 files. Writing: the control skeleton of the channel contract as named nodes
// (a root `horse` carrying the travel, and lfHoof, rfHoof, lbHoof, rbHoof, rearPivot, backMid, neck,
// head, tail under it) with one animation sampled per frame, LINEAR samplers. Reading: any glTF
// animation through a ClipMapping from its node names to the contract's controls, either as control
// nodes (a clip written here, perhaps renamed in another tool) or as a skeleton, whose leg-tip joints'
// world positions relative to the rest pose become the hoof controls (a clip authored on another
// quadruped, such as the Khronos Fox). A clip's obstacles (the jump's fence) travel with it in the root
// node's extras.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "rig/clip.h"

namespace stirrup::rig {

struct GltfWriteOptions {
  double fps = 30.0;
  double start_s = 0.0;
  double end_s = -1.0;  // < 0: the clip's duration
};

// Writes .glb (binary) or .gltf (JSON with the buffer embedded) by the file's extension.
void writeClipGltf(const Clip& clip, const std::filesystem::path& file, const GltfWriteOptions& options = {});

// The contract's control names a mapping can bind, in this order.
inline constexpr std::array<const char*, 10> kClipControlNames = {
    "horse", "lfHoof", "rfHoof", "lbHoof", "rbHoof", "rearPivot", "backMid", "neck", "head", "tail"};

struct ClipMapping {
  enum class Mode { Controls, Skeleton };
  Mode mode = Mode::Controls;
  std::map<std::string, std::string> nodes;  // control name -> node name in the file
  std::string animation;                     // empty: the file's first animation
  // Past its end the animation loops (a cycle from another tool; default for skeletons) or holds its
  // last frame (a finished stirrup clip; default for controls).
  bool loop = false;
  // Skeleton mode: file units to horse centimetres, the file's travel and up directions, where the
  // ground is for each hoof ("rest": the tip's rest height; "lowest": the lowest it reaches in the
  // clip) and the travel speed to add for a clip animated in place (a number, or "auto" to make the
// supporting hoof stand still in the world).
  double scale_cm = 1.0;
  std::array<double, 3> forward = {1, 0, 0};
  std::array<double, 3> up = {0, 1, 0};
  bool ground_at_lowest = true;
  double speed_cm_s = 0.0;
  bool speed_auto = false;  // "auto": the speed at which the lowest hoof moves back (in-place cycles)
  std::filesystem::path file;  // where the mapping was read from, for messages
};

// Controls mode with every control bound to the node of the same name (clips written by stirrup).
ClipMapping contractMapping();
// Reads a mapping file; unknown fields and controls are one-line InputErrors naming file and field.
ClipMapping loadClipMapping(const std::filesystem::path& file);

class GltfClip final : public Clip {
 public:
  GltfClip(const std::filesystem::path& file, const ClipMapping& mapping);
  ~GltfClip() override;
  GltfClip(const GltfClip&) = delete;
  GltfClip& operator=(const GltfClip&) = delete;

  std::string name() const override;
  double duration() const override;
  HorseFrame sample(double seconds) const override;
  // The fences a stirrup clip was written with (the root control's extras.obstacles); none otherwise.
  std::vector<Obstacle> obstacles() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stirrup::rig
