// stirrup bake SCENE: evaluates the clip and the rider rig for every frame of the scene.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "render/cli/commands.h"
#include "render/scene.h"
#include "rig/bake.h"
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
  const fs::path out = o.channels;
  const fs::path tmp = out.string() + ".tmp";
  if (!out.parent_path().empty()) fs::create_directories(out.parent_path());
  {
    std::ofstream csv(tmp);
    if (!csv) throw InputError(out.string() + ": cannot write the file");
    csv.precision(9);
    csv << "frame,time";
    for (std::string_view n : rig::kHorseChannelNames) csv << ',' << n;
    for (std::string_view n : rig::kRiderChannelNames) csv << ',' << n;
    csv << '\n';
    for (int frame : frames) {
      const rig::BakedFrame b = rig::bakeFrame(*clip, profile, frame, render::frameTime(scene, frame));
      csv << b.frame << ',' << b.seconds;
      for (double v : b.horse.controls.value) csv << ',' << v;
      for (double v : b.rider.value) csv << ',' << v;
      csv << '\n';
    }
    if (!csv.flush()) throw InputError(out.string() + ": write failed");
  }
  fs::rename(tmp, out);
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
