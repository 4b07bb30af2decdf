// A baked shot read back, as `stirrup check` measures it (docs/check.md, "A baked shot"): what `stirrup
// bake -o SHOT.glb` writes, or another tool's re-export of it (Blender's glTF exporter). Every pair's
// horse and rider are read as characters from their own skins, and posed at any frame exactly as the
// file's animation keys their joints: nothing is re-posed.
//
//   input:  the file; the frame rate where the file does not say (its scene's extras.fps); an animation by
//           name, or none (every animation of the file played together: GltfAnimation::together, since
//           Blender may split a shot into one animation an armature)
//   output: the pairs (the names the file gives, the characters), the frames (frame 1 = the first key,
//           then one a 1/fps), and each pair at a frame as a rig::MountedPose in stirrup's world (cm)
//
// Which skins: the armatures stirrup names, "horse" and "rider" (a crowd's "pairNN_horse" and
// "pairNN_rider"). A skin's armature is its `skeleton` node, or else the node its top joint hangs from
// (Blender writes no `skeleton`, and names that node after the armature object). A file naming none of
// them with exactly two skins is a shot when the automatic mapping finds a horse in one and a rider in the
// other. Anything else is not a shot (read(): null), and stays what it was: a horse clip.
//
// Roles: the file's role table (rig/io/gltf_character.h gltfRoleTable), else the automatic mapping (whose
// "stirrup" convention reads a bake's joints, named by their roles; rig/mapping/auto_mapping.h). Space: the
// file's world is glTF's, in metres, with stirrup's axes (a bake's world; Blender exports it back so),
// unless the scene's extras say otherwise with "stirrup_world" (a mapping's scale_cm, forward, up and
// offset_cm: the Blender add-on writes its horse's, whose file faces where the user's horse does).
// Every character is read into stirrup's world through it, its mesh in its own units (gltfSkinUnits), so
// the two characters of a pair, and the pairs, stand where the file has them and face +X at rest.
//
// Ground: the meshes the file names as its ground (rig/io/gltf_terrain.h gltfGroundMesh: a bake's node
// "ground", or an object of another tool named so), in stirrup's world through the same space as the
// characters; none when the file has no such node. Whether a hoof is down is not the file's to say: the
// check measures every frame's soles against the ground (rig/frame_check.h hoofDown), as it does a
// scene's.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rig/character.h"
#include "rig/motion/terrain_mesh.h"
#include "rig/pose.h"

namespace stirrup::rig {

struct GltfShotOptions {
  double fps = 24.0;      // frames a second where the file's scene extras have no "fps"
  std::string animation;  // the animation to read by name; empty: every animation together
};

class GltfShot {
 public:
  struct Pair {
    std::string name;  // "" for a single pair ("horse", "rider"); "pair03" in a crowd
    int index = 0;     // a crowd pair's index (3 for "pair03"); 0 for a single pair
    std::string horse_armature, rider_armature;  // the armatures' node names
    int horse_skin = -1, rider_skin = -1;        // their skins in the file
    Character horse, rider;
  };

  // The file read as a baked shot, or null when it is not one (above). Errors are one-line InputErrors
  // naming the file and what is missing: a horse without its rider, a skin whose roles cannot be found,
  // an animation that keys no joint of a pair.
  static std::unique_ptr<GltfShot> read(const std::filesystem::path& file, const GltfShotOptions& options = {});
  ~GltfShot();
  GltfShot(const GltfShot&) = delete;
  GltfShot& operator=(const GltfShot&) = delete;

  const std::vector<Pair>& pairs() const;
  int frameCount() const;
  double fps() const;
  // The animations read (names joined by " + "; empty for a file without animation), and those left out
  // as other takes of the same joints (GltfAnimation::together).
  std::string animationName() const;
  const std::vector<std::string>& leftOut() const;

  // The file's own ground (above) in stirrup's world, or null: the file names none.
  std::shared_ptr<const TerrainMesh> ground() const;
  // The hooves (lf, rf, lb, rb) pair `pair`'s clip slides on purpose at frame `frame`, as the bake records
  // them (rig/io/gltf_bake.h BakedPair::hoof_sliding; none where the file does not say).
  std::array<bool, 4> hoofSliding(std::size_t pair, int frame) const;

  // Pair `pair` at frame `frame` (1 .. frameCount()): both skeletons' joints as the file keys them, in
  // stirrup's world (no hoof targets: `reach` is left empty). Thread safe: frames may be posed in
  // parallel.
  MountedPose pose(std::size_t pair, int frame) const;

 private:
  GltfShot();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stirrup::rig
