// stirrup render SCENE: writes the frames of a shot as NAME.####.png, and a movie with --movie.
#include <cstdio>
#include <filesystem>

#include "render/cli/commands.h"
#include "render/cli/progress.h"
#include "render/image.h"
#include "render/movie.h"
#include "render/scene.h"
#include "render/shot.h"
#include "rig/error.h"
#include "rig/frame_range.h"
#include "rig/rig_profile.h"

namespace stirrup::cli {
namespace {

struct RenderOptions {
  std::string scene;
  std::string frames;
  std::string camera;
  std::string out;
  std::string movie;
  int threads = 0;
  int padding = 4;
  bool progress = false;
  bool resume = false;
};

std::string frameName(const std::string& base, int frame, int padding) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%0*d", padding, frame);
  return base + "." + digits + ".png";
}

void runRender(const RenderOptions& o) {
  namespace fs = std::filesystem;
  if (!o.movie.empty() && fs::path(o.movie).extension() != ".mp4")
    throw InputError("--movie: " + o.movie + ": expected a file name ending in .mp4");
  const render::SceneSpec scene = render::loadScene(o.scene);
  const render::CameraSpec& camera = render::findCamera(scene, o.camera);
  const std::vector<int> frames = rig::parseFrameList(o.frames.empty() ? scene.frames : o.frames, "--frames");
  const rig::RigProfile profile = render::resolveProfile(scene);
  const fs::path dir = o.out.empty() ? scene.output : fs::path(o.out);
  fs::create_directories(dir);
  const std::string base = (dir / (scene.name + "_" + camera.name)).string();

  render::Shot shot(scene, profile, camera, o.threads);
  ProgressBar bar("render " + scene.name + "_" + camera.name, static_cast<int>(frames.size()), o.progress);
  std::vector<fs::path> written;
  int done = 0;
  for (int frame : frames) {
    const fs::path file = frameName(base, frame, o.padding);
    if (!(o.resume && fs::exists(file))) render::writePng(shot.renderFrame(frame), file);
    written.push_back(file);
    bar.step(++done);
  }
  if (!o.movie.empty()) {
    render::encodeMovie({written, scene.fps, o.movie, 18});
    std::printf("%s\n", o.movie.c_str());
  }
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto opts = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene's frames (NAME.####.png) and optionally a movie");
  cmd->footer(
      "Frames are written as OUT/SCENE_CAMERA.####.png, each to a temporary name renamed when complete.\n"
      "Frame lists: 1-120, 1-120x2 (every 2nd), 1-10,20-30, 7.\n"
      "Example: stirrup render scenes/trot.json --frames 1-48 --movie out/trot_side.mp4");
  cmd->add_option("scene", opts->scene, "Scene file (JSON), e.g. scenes/trot.json")->required();
  cmd->add_option("--frames,-f", opts->frames, "Frames to render (default: the scene's frames)");
  cmd->add_option("--camera,-c", opts->camera, "Camera name (default: the scene's first camera)");
  cmd->add_option("--out,-o", opts->out, "Output folder (default: the scene's output)");
  cmd->add_option("--movie,-m", opts->movie, "Also encode the frames as an H.264 .mp4 movie");
  cmd->add_option("--threads,-t", opts->threads, "Render threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--padding", opts->padding, "Digits in frame numbers")->check(CLI::Range(1, 9));
  cmd->add_flag("--resume", opts->resume, "Skip frames whose file already exists");
  cmd->add_flag("--progress", opts->progress, "Show the progress bar even when stderr is not a terminal");
  cmd->callback([opts] { runRender(*opts); });
}

}  // namespace stirrup::cli
