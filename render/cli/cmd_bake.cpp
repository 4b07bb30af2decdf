// stirrup bake SCENE: evaluates the clip and the rider rig for every frame of the scene; --channels
// writes them as CSV, -o writes the posed characters, their animation and the cameras as glTF 2.0.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "render/cli/commands.h"
#include "render/scene.h"
#include "rig/bake.h"
#include "rig/io/channel_csv.h"
#include "rig/error.h"
#include "rig/io/frame_range.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/motion/clip_factory.h"
#include "rig/motion/procedural_gait.h"
#include "rig/rig_profile.h"

namespace stirrup::cli {
namespace {

struct BakeOptions {
  std::string scene;
  std::string frames;
  std::string channels;
  std::string output;
};

// The whole shot as one glTF: both characters posed at every frame, and every camera of the scene.
void writeBakedGlb(const render::SceneSpec& scene, const rig::RigProfile& profile, const rig::Clip& clip,
                   std::vector<int> frames, const std::string& output) {
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const rig::Character horse = rig::resolveCharacter(rig::CharacterKind::Horse, scene.horse, scene.horse_mapping);
  const rig::Character rider = rig::resolveCharacter(rig::CharacterKind::Rider, scene.rider, scene.rider_mapping);
  rig::BakedShot shot;
  shot.name = scene.name;
  for (const render::CameraSpec& c : scene.cameras) {
    rig::BakedCamera bc;
    bc.name = c.name;
    bc.orthographic = c.orthographic;
    bc.fov_deg = c.fov_deg;
    bc.ortho_height_cm = c.ortho_height_cm;
    bc.aspect = static_cast<double>(scene.width) / scene.height;
    shot.cameras.push_back(bc);
  }
  for (int frame : frames) {
    const rig::BakedFrame b = rig::bakeFrame(clip, profile, frame, render::frameTime(scene, frame));
    shot.seconds.push_back(static_cast<float>(b.seconds));
    shot.poses.push_back(rig::poseMounted(horse, rider, b.horse, b.rider, profile.rider_unit_cm));
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
      const render::CameraSpec& c = scene.cameras[i];
      const glm::dvec3 offset = c.follow ? glm::dvec3(b.horse.travel_cm, 0.0, 0.0) : glm::dvec3(0.0);
      shot.cameras[i].world.push_back(rig::lookAtWorld(glm::dvec3(c.position[0], c.position[1], c.position[2]) + offset,
                                                       glm::dvec3(c.target[0], c.target[1], c.target[2]) + offset));
    }
  }
  rig::writeFileAtomically(output, rig::bakedShotGlb(horse, rider, shot));
}

void runBake(const BakeOptions& o) {
  namespace fs = std::filesystem;
  const render::SceneSpec scene = render::loadScene(o.scene);
  const std::vector<int> frames = rig::parseFrameList(o.frames.empty() ? scene.frames : o.frames, "--frames");
  const rig::RigProfile profile = render::resolveProfile(scene);
  const std::unique_ptr<rig::Clip> clip = rig::makeClip(scene.clip);

  if (o.channels.empty() && o.output.empty()) throw InputError("bake: nothing to write (expected --channels FILE or -o FILE.glb)");
  if (!o.output.empty()) {
    if (fs::path(o.output).extension() != ".glb") throw InputError("bake: -o: expected a .glb file, got " + o.output);
    writeBakedGlb(scene, profile, *clip, frames, o.output);
  }
  if (o.channels.empty()) return;
  // Columns: time, every horse channel, every rider channel, in contract order.
  std::vector<std::string_view> names;
  names.reserve(1 + rig::kHorseChannelCount + rig::kRiderChannelCount);
  names.push_back("time");
  for (std::string_view n : rig::kHorseChannelNames) names.push_back(n);
  for (std::string_view n : rig::kRiderChannelNames) names.push_back(n);
  std::vector<double> frame_numbers, values;
  values.reserve(frames.size() * names.size());
  for (int frame : frames) {
    const rig::BakedFrame b = rig::bakeFrame(*clip, profile, frame, render::frameTime(scene, frame));
    frame_numbers.push_back(b.frame);
    values.push_back(b.seconds);
    values.insert(values.end(), b.horse.controls.value.begin(), b.horse.controls.value.end());
    values.insert(values.end(), b.rider.value.begin(), b.rider.value.end());
  }
  std::vector<const double*> rows;
  for (std::size_t i = 0; i < frames.size(); ++i) rows.push_back(values.data() + i * names.size());
  if (const fs::path parent = fs::path(o.channels).parent_path(); !parent.empty()) fs::create_directories(parent);
  rig::writeChannelCsv(o.channels, names, frame_numbers, rows);
}

}  // namespace

void addBakeCommand(CLI::App& app) {
  auto opts = std::make_shared<BakeOptions>();
  CLI::App* cmd = app.add_subcommand("bake", "Evaluate a scene's clip and rider rig for every frame");
  cmd->footer(
      "--channels writes CSV: a header `frame,time,` then every horse channel and every rider channel in\n"
      "the names of ../shared/rig-channels.md (horse: cm and degrees; rider: degrees and rider units),\n"
      "one row per frame.\n"
      "-o writes one glTF 2.0 binary: both characters as skinned meshes, their joints at every frame\n"
      "(translation and rotation, LINEAR) and the scene's cameras, animated where they follow the horse.\n"
      "Example: stirrup bake scenes/trot.json --channels out/trot.csv\n"
      "         stirrup bake scenes/rear.json -o out/rear.glb");
  cmd->add_option("scene", opts->scene, "Scene file (JSON), e.g. scenes/trot.json")->required();
  cmd->add_option("--frames,-f", opts->frames, "Frames to bake (default: the scene's frames), e.g. 1-120x2");
  cmd->add_option("--channels", opts->channels, "Write the channels of every frame as CSV to FILE");
  cmd->add_option("-o,--output", opts->output, "Write the baked shot as glTF 2.0 (.glb)");
  cmd->callback([opts] { runBake(*opts); });
}

}  // namespace stirrup::cli
