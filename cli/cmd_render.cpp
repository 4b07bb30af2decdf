// stirrup render SCENE: writes the frames of a shot as NAME.####.png (and/or linear NAME.####.exr
// with the compositing passes), and a movie with --movie.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <tuple>
#include <vector>

#include "cli/commands.h"
#include "cli/options.h"
#include "cli/output_folder.h"
#include "cli/progress.h"
#include "render/farm/farm_shots.h"
#include "render/review/movie.h"
#include "render/shot.h"
#include "render/tracer/frame_writer.h"
#include "render/tracer/image.h"
#include "rig/error.h"
#include "scene/file_shot.h"
#include "scene/frame_range.h"
#include "scene/frame_sequence.h"
#include "scene/preset.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace stirrup::cli {
namespace {

struct RenderOptions {
  std::string scene;
  std::string frames;
  std::string camera;
  std::string out;
  std::string movie;
  std::string preset;
  std::string resolution;
  std::vector<std::string> sets;
  std::string format = "png";
  bool exr = false;
  int threads = 0;
  int padding = scene::kDefaultFramePadding;
  int png_compression = -1;  // -1: the scene's default (scene::defaultPngCompression)
  bool progress = false;
  bool resume = false;
  std::string camera_plan;  // a farm plan (farm.json) whose framed camera this shot uses
  bool encode_only = false;
  bool allow_impossible = false;
  double fps = 24.0;      // a glTF shot whose file says none
  std::string look;      // a glTF shot: the scene whose cameras, size, quality, sun and ground it renders with
};

// What renders: a scene's pairs evaluated, or a glTF shot's as the file keys them
// (scene/file_shot.h), both through one evaluator and one tracer.
struct RenderInput {
  scene::SceneSpec scene;
  std::optional<scene::FileShot> file;
  rig::RigProfile profile;
};

RenderInput loadRenderInput(const RenderOptions& o) {
  RenderInput in;
  if (scene::isGltfFile(o.scene)) {
    if (!o.camera_plan.empty()) throw rig::InputError("--camera-plan: a farm's plan applies to a scene, not to the glTF shot " + o.scene);
    in.file = scene::loadFileShot(o.scene, o.fps, o.look);
    in.scene = in.file->scene;
    if (!o.preset.empty() || o.look.empty()) scene::applyPreset(in.scene, scene::findPreset(o.preset.empty() ? "review" : o.preset));
  } else {
    if (!o.look.empty()) throw rig::InputError("--scene: applies to a glTF shot, and " + o.scene + " is a scene");
    in.scene = scene::loadScene(o.scene, {o.allow_impossible});
    if (!o.preset.empty()) scene::applyPreset(in.scene, scene::findPreset(o.preset));
  }
  if (!o.resolution.empty()) std::tie(in.scene.width, in.scene.height) = parseResolution(o.resolution);
  in.profile = scene::resolveProfileForEveryPair(in.scene, parseSets(o.sets));
  if (in.file) in.file->scene = in.scene;
  return in;
}

void runRender(const RenderOptions& o) {
  namespace fs = std::filesystem;
  if (!o.movie.empty() && fs::path(o.movie).extension() != ".mp4")
    throw rig::InputError("--movie: " + o.movie + ": expected a file name ending in .mp4");
  const std::string format = o.exr ? "both" : o.format;
  const bool png = format != "exr", exr = format != "png";
  if (!o.movie.empty() && !png) throw rig::InputError("--movie: needs PNG frames; use --format png or both");
  if (o.encode_only && o.movie.empty()) throw rig::InputError("--encode-only: expected --movie FILE.mp4 to encode");
  const RenderInput in = loadRenderInput(o);
  const scene::SceneSpec& scene = in.scene;
  const rig::RigProfile& profile = in.profile;
  const scene::CameraSpec& camera = scene::findCamera(scene, o.camera);
  const std::vector<int> frames = scene::parseFrameList(o.frames.empty() ? scene.frames : o.frames, "--frames");
  const fs::path dir = o.out.empty() ? scene.output : fs::path(o.out);
  const OutputFolder folder(dir);  // taken back if the render fails before writing a frame
  const std::string shot_name = scene.name + "_" + camera.name;
  const scene::FrameSequence png_frames = scene::FrameSequence::named(dir, shot_name, ".png", o.padding);
  const scene::FrameSequence exr_frames = scene::FrameSequence::named(dir, shot_name, ".exr", o.padding);

  if (o.encode_only) {
    // A farm's last step: every frame must already be there; render nothing, encode.
    std::vector<fs::path> written;
    for (int frame : frames) {
      written.push_back(png_frames.path(frame));
      if (!fs::is_regular_file(written.back()))
        throw rig::InputError("--encode-only: frame " + std::to_string(frame) + " is missing (" + written.back().string() + ")");
    }
    render::encodeMovie({written, scene.fps, o.movie, 18});
    std::printf("%s\n", o.movie.c_str());
    return;
  }

  // A farm task's camera, framed once when the farm was planned (render/farm/farm_plan.h).
  scene::CameraSpec shown = camera;
  if (!o.camera_plan.empty()) {
    std::string where;
    const render::PlannedCamera planned = render::plannedCameraOf(o.camera_plan, shot_name, where);
    shown = render::plannedCameraSpec(scene, profile, camera, planned, where);
  }
  const int png_level = o.png_compression >= 0 ? o.png_compression : scene::defaultPngCompression(scene);
  render::Shot shot = in.file ? render::Shot(std::make_shared<scene::ShotEvaluator>(*in.file, profile, o.threads), shown, o.threads)
                              : render::Shot(scene, profile, shown, o.threads);
  shot.setPasses(exr);  // PNG frames need the colour alone
  ProgressBar bar("render " + scene.name + "_" + camera.name, static_cast<int>(frames.size()), o.progress);
  // The frames to render (with --resume, those not yet written), so each can be evaluated while the
  // one before it traces (render::Shot::renderFrame's next frame).
  std::vector<int> to_render;
  for (int frame : frames) {
    const bool complete = (!png || fs::exists(png_frames.path(frame))) && (!exr || fs::exists(exr_frames.path(frame)));
    if (!(o.resume && complete)) to_render.push_back(frame);
  }
  std::vector<fs::path> written;
  render::FrameWriter writer;
  int done = 0;
  std::size_t next = 0;  // into to_render
  for (int frame : frames) {
    const fs::path png_file = png_frames.path(frame), exr_file = exr_frames.path(frame);
    if (next < to_render.size() && to_render[next] == frame) {
      ++next;
      scene::warnImpossibleFrame(scene, frame);
      const std::optional<int> next_frame = next < to_render.size() ? std::optional<int>(to_render[next]) : std::nullopt;
      render::Image image = shot.renderFrame(frame, next_frame);
      const render::ExrMetadata metadata =
          exr ? render::exrFrameMetadata(shot.cameraAtFrame(frame), camera.name, frame, scene::frameTime(scene, frame),
                                         scene.name)
              : render::ExrMetadata{};
      // Written while the next frame renders (render/tracer/frame_writer.h); still each to a temporary name.
      writer.submit([image = std::move(image), metadata, png_file, exr_file, png, exr, png_level] {
        if (png) render::writePng(image, png_file, png_level);
        if (exr) render::writeExr(image, exr_file, metadata);
      });
    }
    if (png) written.push_back(png_file);
    bar.step(++done);
  }
  writer.wait();
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
      "Frames are written as OUT/SCENE_CAMERA.####.png (or .exr), each to a temporary name renamed when complete.\n"
      "Frame lists: 1-120, 1-120x2 (every 2nd), 1-10,20-30, 7.\n"
      "A glTF shot (.glb/.gltf) renders as it is, at review quality unless --preset says otherwise, through its\n"
      "views side, persp, close, turntable and top, to out/NAME (NAME the file's stem).\n"
      "Example: stirrup render scenes/trot.json --frames 1-48 --movie out/trot_side.mp4\n"
      "         stirrup render shot.glb --camera close --movie out/shot_close.mp4");
  cmd->add_option("scene", opts->scene,
                  "Scene file (JSON), e.g. scenes/trot.json; or a glTF shot (a stirrup bake, or Blender's export of one), "
                  "rendered as the file keys it")
      ->required();
  cmd->add_option("--fps", opts->fps, "glTF shot: its frame rate where the file does not say (default 24)")
      ->check(CLI::Range(0.001, 240.0));
  cmd->add_option("--scene", opts->look,
                  "glTF shot: the scene it was baked from, whose cameras, resolution, quality, sun, haze, ground and "
                  "output it renders with (its clip and characters are the file's)");
  cmd->add_option("--frames,-f", opts->frames, "Frames to render (default: the scene's frames)");
  cmd->add_option("--camera,-c", opts->camera, "Camera name (default: the scene's first camera)");
  cmd->add_option("--out,-o", opts->out, "Output folder (default: the scene's output)");
  cmd->add_option("--movie,-m", opts->movie, "Also encode the frames as an H.264 .mp4 movie");
  cmd->add_option("--preset", opts->preset, "Quality preset: draft, review or final (default: the scene's quality)");
  cmd->add_option("--set,-s", opts->sets,
                  "Override one rig-profile parameter after the scene's (every pair's in a crowd), KEY=NUMBER (repeatable), "
                  "e.g. --set eq7.w2_scale=0.015 (stirrup rig params lists them)");
  cmd->add_option("--resolution", opts->resolution, "WIDTHxHEIGHT instead of the scene's (e.g. 320x180)");
  cmd->add_option("--format", opts->format,
                  "png (sRGB review frames), exr (linear half float with RGBA, N, Z, matte and objectId "
                  "passes and the camera in the header) or both")
      ->check(CLI::IsMember({"png", "exr", "both"}));
  cmd->add_option("--png-compression", opts->png_compression,
                  "zlib level of the PNG frames, 0 (stored: the fastest write, the largest file) to 9 (the "
                  "smallest file); the pixels are the same at every level. Default: 0 for a draft (one sample "
                  "a pixel), else 1")
      ->check(CLI::Range(scene::kPngCompressionMin, scene::kPngCompressionMax));
  cmd->add_flag("--exr", opts->exr, "Also write the EXR frames (same as --format both)");
  cmd->add_option("--threads,-t", opts->threads, "Render threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--padding", opts->padding, "Digits in frame numbers")->check(CLI::Range(1, scene::kMaxFramePadding));
  cmd->add_flag("--resume", opts->resume, "Skip frames whose file already exists");
  cmd->add_option("--camera-plan", opts->camera_plan,
                  "Use the view camera framed in this farm plan (OUT/farm.json; stirrup farm's tasks pass it) instead "
                  "of framing the view again");
  cmd->add_flag("--allow-impossible", opts->allow_impossible,
                "Render a scene beyond a horse's limits (docs/horse-limits.md) anyway, warning on stderr for each frame");
  cmd->add_flag("--encode-only", opts->encode_only,
                "Render nothing: encode --movie from the frames already written (a farm's last step); an error "
                "names the first missing frame");
  cmd->add_flag("--progress", opts->progress, "Show the progress bar even when stderr is not a terminal");
  cmd->callback([opts] { runRender(*opts); });
}

}  // namespace stirrup::cli
