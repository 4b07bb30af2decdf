#include "scene/file_shot.h"

#include <algorithm>
#include <cctype>

#include "rig/error.h"
#include "rig/io/keyed_horse_clip.h"

namespace stirrup::scene {

bool isGltfFile(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".glb" || ext == ".gltf";
}

FileShot loadFileShot(const std::filesystem::path& file, double fps, const std::filesystem::path& scene_file) {
  rig::GltfShotOptions options;
  options.fps = fps;
  std::unique_ptr<rig::GltfShot> shot = rig::GltfShot::read(file, options);
  if (!shot)
    throw rig::InputError(file.string() +
                     ": not a shot (expected a stirrup bake or Blender's export of one: armatures \"horse\" and \"rider\", or a "
                     "horse's and a rider's skins; a horse clip renders from a scene that names it as its clip)");
  FileShot out;
  out.file = file;
  SceneSpec& scene = out.scene;
  if (!scene_file.empty()) {
    scene = loadScene(scene_file, {true});  // its paths' limits are not the shot's
    // What moves is the file's: the scene's clip, characters, pairs and limits are not the shot's.
    const SceneSpec plain;
    scene.clip = plain.clip, scene.gait = plain.gait;
    scene.horse = plain.horse, scene.rider = plain.rider, scene.horse_mapping = plain.horse_mapping, scene.rider_mapping = plain.rider_mapping;
    scene.crowd.reset(), scene.pairs.clear(), scene.pair_clips.clear(), scene.pair_clips_terrain.reset(), scene.limits.clear();
    scene.reference.reset();
  }
  scene.fps = shot->fps();
  scene.frames = "1-" + std::to_string(shot->frameCount());
  out.shot = std::move(shot);
  if (!scene_file.empty()) return out;
  // The file's own ground, where it names one (a bake over hills holds it): the horses walk on it.
  if (const std::shared_ptr<const rig::TerrainMesh> ground = out.shot->ground())
    scene.terrain = std::make_shared<const rig::Terrain>(rig::Terrain::mesh(ground));
  scene.file = file;
  scene.name = file.stem().string();
  scene.output = std::filesystem::path("out") / scene.name;
  // The review quality the movies are made at (scene/preset.h "review"): the caller applies it.
  scene.cameras.clear();
  for (const char* view : {"side", "persp", "close", "turntable", "top"}) {
    CameraSpec c;
    c.name = view;
    c.view = view;
    scene.cameras.push_back(c);
  }
  return out;
}

std::unique_ptr<rig::Clip> fileShotTravel(const FileShot& shot, std::size_t pair) {
  const rig::GltfShot::Pair& p = shot.shot->pairs().at(pair);
  rig::KeyedHorseOptions options;
  options.skin = p.horse_skin;
  options.every_animation = true;  // as GltfShot reads the file (GltfShotOptions::animation empty)
  options.keyed_travel_only = true;
  return std::make_unique<rig::KeyedHorseClip>(shot.file, "", rig::keyedHorseMapping(p.horse), nullptr, options);
}

}  // namespace stirrup::scene
