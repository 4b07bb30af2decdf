// stirrup bake SCENE: evaluates the clip and the rider rig for every frame of the scene.
#include <cstdio>
#include <filesystem>
#include <vector>

#include "render/cli/commands.h"
#include "render/scene.h"
#include "rig/bake.h"
#include "rig/channel_csv.h"
#include "rig/error.h"
#include "rig/frame_range.h"
#include "rig/clip_factory.h"
#include "rig/procedural_gait.h"
#include "rig/rig_profile.h"

namespace stirrup::cli {
namespace {

struct BakeOptions {
  std::string scene;
  std::string frames;
  std::string channels;
};

void runBake(const BakeOptions& o) {
  namespace fs = std::filesystem;
  const render::SceneSpec scene = render::loadScene(o.scene);
  const std::vector<int> frames = rig::parseFrameList(o.frames.empty() ? scene.frames : o.frames, "--frames");
  const rig::RigProfile profile = render::resolveProfile(scene);
  const std::unique_ptr<rig::Clip> clip = rig::makeClip(scene.clip);

  if (o.channels.empty()) throw InputError("bake: nothing to write (expected --channels FILE)");
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
      "Example: stirrup bake scenes/trot.json --channels out/trot.csv");
  cmd->add_option("scene", opts->scene, "Scene file (JSON), e.g. scenes/trot.json")->required();
  cmd->add_option("--frames,-f", opts->frames, "Frames to bake (default: the scene's frames), e.g. 1-120x2");
  cmd->add_option("--channels", opts->channels, "Write the channels of every frame as CSV to FILE")->required();
  cmd->callback([opts] { runBake(*opts); });
}

}  // namespace stirrup::cli
