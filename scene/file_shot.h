// A glTF shot rendered as it is: a `stirrup bake -o SHOT.glb`, or Blender's export of a shot (what
// rig::GltfShot::read recognises: the armatures "horse" and "rider", a crowd's "pairNN_horse" and
// "pairNN_rider", or two skins the automatic mapping casts as a horse and a rider). Nothing is re-posed:
// every pair is posed at every frame as the file keys it (rig/io/gltf_shot.h), and the shot's evaluator
// (scene/shot_evaluator.h) skins and frames it as it does a scene's pairs, so `stirrup render`
// traces both through one path.
//
//   input:  the file; the frame rate where the file's scene extras have none; optionally the scene it
//           was baked from, for its look
//   output: the shot's scene: its fps and frames from the file; with a scene its cameras, image size,
//           quality, sun, haze, ground, name and output; else the named views side, persp, close,
//           turntable and top, 640x360, review quality, the file's own ground mesh (rig/io/gltf_shot.h;
//           else flat), the file's stem as name and out/NAME; and the shot read
//
// The views follow the horse's travel as a scene's follow its clip: each pair's horse plays its own
// keyed animation (rig/io/keyed_horse_clip.h) for the travel frame fitted to its trunk, which the
// cameras follow and turn with (KeyedHorseOptions::keyed_travel_only: a horse keyed in place stays).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "rig/clip.h"
#include "rig/io/gltf_shot.h"
#include "scene/scene.h"

namespace stirrup::scene {

// Whether `file` names a glTF file (.glb or .gltf, any case): what `stirrup render` reads as a shot.
bool isGltfFile(const std::filesystem::path& file);

struct FileShot {
  SceneSpec scene;
  std::shared_ptr<const rig::GltfShot> shot;
  std::filesystem::path file;
};

// Reads `file` as a shot. A glTF file that is not one (a horse clip, a character) is a one-line
// InputError naming the file and what a shot holds; so are the shot's own errors (rig::GltfShot::read).
// `scene_file` (empty: none) is read as loadScene reads it; its own clip, characters and pairs are not
// the shot's and are left out.
FileShot loadFileShot(const std::filesystem::path& file, double fps = 24.0, const std::filesystem::path& scene_file = {});

// The travel of pair `pair`'s horse: its own keyed animation read from the shot's file, the travel as
// keyed (no travel added in place).
std::unique_ptr<rig::Clip> fileShotTravel(const FileShot& shot, std::size_t pair);

}  // namespace stirrup::scene
