// stirrup bake SCENE: evaluates the clip and the rider rig for every frame of the scene, for every pair
// of it (scene/shot_evaluator.h: one horse and rider, or a crowd's); --channels writes them as CSV,
// -o writes the posed characters, their animation and the cameras as glTF 2.0 (docs/round-trip.md), or
// with --rider-only the rider's motion alone, for the user's rider rig. A crowd bakes into one glTF
// with two armatures a pair (docs/crowds.md); its CSV and rider-only files are one a pair.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "cli/commands.h"
#include "rig/bake.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "rig/io/channel_csv.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_rider_motion.h"
#include "rig/rig_profile.h"
#include "scene/camera.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "scene/shot_bake.h"
#include "scene/shot_evaluator.h"

namespace stirrup::cli {
namespace {

struct BakeOptions {
  std::string scene;
  std::string frames;
  std::string channels;
  std::string output;
  bool rider_only = false;
  bool allow_impossible = false;
  int detail = 0;
};

// The whole shot as one glTF (scene/shot_bake.h).
void writeBakedGlb(scene::ShotEvaluator& characters, const std::vector<int>& frames, int level, const std::string& output) {
  rig::writeFileAtomically(output, rig::bakedShotGlb(scene::bakeShot(characters, frames, level)));
}

// A crowd writes one file a pair: FILE's name with the pair's before its extension (out/c.csv ->
// out/c_pair03.csv); a scene of one pair writes FILE itself.
std::string pairFile(const std::string& file, const std::string& pair) {
  if (pair.empty()) return file;
  const std::filesystem::path f(file);
  return (f.parent_path() / (f.stem().string() + "_" + pair + f.extension().string())).string();
}

// Only the rider's skeleton animation, in the rider file's own joint names, units and axes
// (rig/io/gltf_rider_motion.h), to put on the user's rider rig: one file a pair.
void writeRiderGlb(scene::ShotEvaluator& characters, std::vector<int> frames, const std::string& output) {
  const scene::SceneSpec& scene = characters.scene();
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  std::vector<rig::RiderMotion> motions(std::size_t(characters.pairCount()));
  for (std::size_t i = 0; i < motions.size(); ++i) {
    motions[i].seat = characters.seat(int(i));
    motions[i].name = scene.name;
    motions[i].fps = scene.fps;
  }
  scene::ShotFrame evaluated;
  for (int frame : frames) {
    scene::FrameRequest request;
    request.frame = frame;
    request.until = scene::EvalStage::Pose;
    characters.evaluate(request, evaluated);
    for (std::size_t i = 0; i < motions.size(); ++i) {
      motions[i].seconds.push_back(static_cast<float>(evaluated.pairs[i].baked.seconds));
      motions[i].world.push_back(std::move(evaluated.pairs[i].pose.rider));
    }
  }
  for (std::size_t i = 0; i < motions.size(); ++i)
    rig::writeFileAtomically(pairFile(output, characters.pairName(int(i))),
                             rig::riderMotionGlb(characters.riderAt(int(i), 0), motions[i]));
}

// Columns: time, every horse channel, every rider channel, in contract order; one file a pair.
void writeChannels(scene::ShotEvaluator& characters, const std::vector<int>& frames, const std::string& output) {
  namespace fs = std::filesystem;
  std::vector<std::string_view> names;
  names.reserve(1 + rig::kHorseChannelCount + rig::kRiderChannelCount);
  names.push_back("time");
  for (std::string_view n : rig::kHorseChannelNames) names.push_back(n);
  for (std::string_view n : rig::kRiderChannelNames) names.push_back(n);
  std::vector<double> frame_numbers;
  std::vector<std::vector<double>> values(std::size_t(characters.pairCount()));
  scene::ShotFrame evaluated;
  for (int frame : frames) {
    scene::FrameRequest request;
    request.frame = frame;
    request.until = scene::EvalStage::Bake;
    characters.evaluate(request, evaluated);
    frame_numbers.push_back(frame);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const rig::BakedFrame& b = evaluated.pairs[i].baked;
      values[i].push_back(b.seconds);
      values[i].insert(values[i].end(), b.horse.controls.value.begin(), b.horse.controls.value.end());
      values[i].insert(values[i].end(), b.rider.value.begin(), b.rider.value.end());
    }
  }
  if (const fs::path parent = fs::path(output).parent_path(); !parent.empty()) fs::create_directories(parent);
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::vector<const double*> rows;
    for (std::size_t k = 0; k < frames.size(); ++k) rows.push_back(values[i].data() + k * names.size());
    rig::writeChannelCsv(pairFile(output, characters.pairName(int(i))), names, frame_numbers, rows);
  }
}

void runBake(const BakeOptions& o) {
  namespace fs = std::filesystem;
  const scene::SceneSpec scene = scene::loadScene(o.scene, {o.allow_impossible});
  const std::vector<int> frames = scene::parseFrameList(o.frames.empty() ? scene.frames : o.frames, "--frames");
  for (int frame : frames) scene::warnImpossibleFrame(scene, frame);  // once a frame, whatever is written
  if (o.channels.empty() && o.output.empty()) throw rig::InputError("bake: nothing to write (expected --channels FILE or -o FILE.glb)");
  if (o.rider_only && o.output.empty()) throw rig::InputError("bake: --rider-only: expected -o FILE.glb to write the rider's motion to");
  if (!o.output.empty() && fs::path(o.output).extension() != ".glb")
    throw rig::InputError("bake: -o: expected a .glb file, got " + o.output);
  // Every pair of the scene (one, or a crowd's), on all cores: the frames are the same at any count.
  scene::ShotEvaluator characters(scene, scene::resolveProfile(scene), 0);
  if (o.detail > 0 && (!characters.isCrowd() || o.output.empty() || o.rider_only))
    throw rig::InputError("bake: --detail " + std::to_string(o.detail) +
                     ": expected 0 unless -o bakes a crowd (a single pair has only its own characters; --rider-only and "
                     "--channels write no mesh)");
  if (!o.output.empty()) {
    if (o.rider_only)
      writeRiderGlb(characters, frames, o.output);
    else
      writeBakedGlb(characters, frames, o.detail, o.output);
  }
  if (!o.channels.empty()) writeChannels(characters, frames, o.channels);
}

}  // namespace

void addBakeCommand(CLI::App& app) {
  auto opts = std::make_shared<BakeOptions>();
  CLI::App* cmd = app.add_subcommand("bake", "Evaluate a scene's clip and rider rig for every frame");
  cmd->footer(
      "--channels writes CSV: a header `frame,time,` then every horse channel and every rider channel in\n"
      "the names of docs/channels.md (horse: cm and degrees; rider: degrees and rider units),\n"
      "one row per frame.\n"
      "-o writes one glTF 2.0 binary: both characters as skinned meshes, each under its own root node\n"
      "(one armature each), their joints at every frame (translation and rotation, LINEAR), and every\n"
      "camera exactly as `stirrup render` frames and moves it, keyed at every frame (image size in the\n"
      "camera's extras). Frame F is at time (F - 1) / fps (docs/round-trip.md).\n"
      "--rider-only -o writes only the rider's skeleton and its animation, in the rider file's own joint\n"
      "names, units and axes (the scene's rider mapping undone), to put on the user's own rider rig.\n"
      "A crowd scene (docs/crowds.md): -o writes every pair into the one file, two armatures a pair\n"
      "(pair03_horse, pair03_rider: the pair's index from 0), their joints named as the skeleton names them;\n"
      "--channels and --rider-only write one file a pair, the pair's name before the extension\n"
      "(out/cavalry.csv -> out/cavalry_pair00.csv ... out/cavalry_pair29.csv), each as a single pair's.\n"
      "--detail 1 or 2 bakes a crowd's meshes at half or quarter detail: a file of a fraction of the size.\n"
      "Example: stirrup bake scenes/trot.json --channels out/trot.csv\n"
      "         stirrup bake scenes/rear.json -o out/rear.glb\n"
      "         stirrup bake scenes/cavalry.json -o out/cavalry.glb");
  cmd->add_option("scene", opts->scene, "Scene file (JSON), e.g. scenes/trot.json")->required();
  cmd->add_option("--frames,-f", opts->frames, "Frames to bake (default: the scene's frames), e.g. 1-120x2");
  cmd->add_option("--channels", opts->channels, "Write the channels of every frame as CSV to FILE");
  cmd->add_option("-o,--output", opts->output, "Write the baked shot as glTF 2.0 (.glb)");
  cmd->add_flag("--rider-only", opts->rider_only,
                "With -o: write only the rider's skeleton animation, in the rider file's joint names");
  cmd->add_option("--detail", opts->detail,
                  "With -o on a crowd: every pair's meshes at this level of detail, 0 full (default), 1 half, 2 quarter "
                  "(the cell the render uses for far pairs; the same skeletons and animation, a smaller file)")
      ->check(CLI::Range(0, 2));
  cmd->add_flag("--allow-impossible", opts->allow_impossible,
                "Bake a scene beyond a horse's limits (docs/horse-limits.md) anyway, warning on stderr for each frame");
  cmd->callback([opts] { runBake(*opts); });
}

}  // namespace stirrup::cli
