// stirrup bake SCENE: evaluates the clip and the rider rig for every frame of the scene; --channels
// writes them as CSV, -o writes the posed characters, their animation and the cameras as glTF 2.0
// (docs/round-trip.md), or with --rider-only the rider's motion alone, for the user's rider rig.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "render/camera.h"
#include "render/cli/commands.h"
#include "render/profile_resolver.h"
#include "render/scene.h"
#include "render/shot.h"
#include "rig/bake.h"
#include "rig/io/channel_csv.h"
#include "rig/error.h"
#include "rig/io/frame_range.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/io/ridden_pair.h"
#include "rig/io/gltf_rider_motion.h"
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
  bool rider_only = false;
  bool allow_impossible = false;
};

// The camera node's transform as glTF wants it (looks down -Z, +Y up): the render camera's own basis,
// so the file sees exactly what CameraFrame traces, in the same centimetres.
glm::dmat4 cameraToWorld(const render::Camera& camera, const render::SceneSpec& scene) {
  const render::CameraFrame f(camera, scene.width, scene.height);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(f.right(), 0.0);
  m[1] = glm::dvec4(f.upward(), 0.0);
  m[2] = glm::dvec4(-f.forward(), 0.0);
  m[3] = glm::dvec4(camera.position, 1.0);
  return m;
}

// A baked terrain: 50 cm cells (the hooves sit on it to a few millimetres on rolling hills) over the
// track and 20 m around it, coarser past 600 cells a side (a few MB at most).
constexpr double kBakedGroundCellCm = 50.0;
constexpr double kBakedGroundMarginCm = 2000.0;
constexpr int kBakedGroundMaxCells = 600;

// The whole shot as one glTF: both characters posed at every frame, and every camera of the scene as
// `stirrup render` resolves it (render::Shot: views framed, follow and orbit motion) at every frame.
void writeBakedGlb(const render::SceneSpec& scene, const rig::RigProfile& profile, const rig::Clip& clip,
                   std::vector<int> frames, const std::string& output) {
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const rig::RiddenPair pair = rig::resolveRiddenPair(scene.horse, scene.horse_mapping, scene.rider, scene.rider_mapping, profile);
  const rig::Character& horse = pair.horse;
  const rig::Character& rider = pair.rider;
  rig::BakedShot shot;
  shot.seat = pair.seat;
  shot.name = scene.name;
  shot.fps = scene.fps;
  std::vector<rig::BakedFrame> baked;
  for (int frame : frames) {
    const rig::BakedFrame b = rig::bakeFrame(clip, profile, frame, render::frameTime(scene, frame));
    shot.seconds.push_back(static_cast<float>(b.seconds));
    shot.poses.push_back(rig::poseMounted(horse, rider, b.horse, b.rider, profile));
    baked.push_back(b);
  }
  if (scene.terrain && !scene.terrain->flat()) {
    // The ground under the baked frames' track and well around it (kBakedGroundMarginCm).
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const rig::BakedFrame& b : baked) {
      lo = glm::min(lo, glm::dvec2(b.horse.travel_cm, b.horse.travel_z_cm));
      hi = glm::max(hi, glm::dvec2(b.horse.travel_cm, b.horse.travel_z_cm));
    }
    scene.terrain->triangulate(lo - kBakedGroundMarginCm, hi + kBakedGroundMarginCm, kBakedGroundCellCm,
                               kBakedGroundMaxCells, shot.ground_vertices, shot.ground_indices);
  }
  for (const render::CameraSpec& spec : scene.cameras) {
    const render::Shot view(scene, profile, spec, 1);
    const render::CameraSpec& c = view.camera();
    rig::BakedCamera bc;
    bc.name = c.name;
    bc.orthographic = c.orthographic;
    bc.fov_deg = c.fov_deg;
    bc.ortho_height_cm = c.ortho_height_cm;
    bc.width = scene.width;
    bc.height = scene.height;
    bc.view = c.view;
    bc.hold_frame = c.hold_frame;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      render::Camera cam = view.cameraAtFrame(frames[i]);
      // A treadmill render takes the travel out of the horse; the file's horse travels, so the camera
      // travels with it instead (the same picture: both move by the same vector).
      if (c.treadmill) {
        const glm::dvec3 travel(baked[i].horse.travel_cm, 0.0, baked[i].horse.travel_z_cm);
        cam.position += travel;
        cam.target += travel;
      }
      bc.world.push_back(cameraToWorld(cam, scene));
    }
    shot.cameras.push_back(bc);
  }
  rig::writeFileAtomically(output, rig::bakedShotGlb(horse, rider, shot));
}

// Only the rider's skeleton animation, in the rider file's own joint names, units and axes
// (rig/io/gltf_rider_motion.h), to put on the user's rider rig.
void writeRiderGlb(const render::SceneSpec& scene, const rig::RigProfile& profile, const rig::Clip& clip,
                   std::vector<int> frames, const std::string& output) {
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const rig::RiddenPair pair = rig::resolveRiddenPair(scene.horse, scene.horse_mapping, scene.rider, scene.rider_mapping, profile);
  const rig::Character& horse = pair.horse;
  const rig::Character& rider = pair.rider;
  rig::RiderMotion motion;
  motion.seat = pair.seat;
  motion.name = scene.name;
  motion.fps = scene.fps;
  for (int frame : frames) {
    const rig::BakedFrame b = rig::bakeFrame(clip, profile, frame, render::frameTime(scene, frame));
    motion.seconds.push_back(static_cast<float>(b.seconds));
    motion.world.push_back(rig::poseMounted(horse, rider, b.horse, b.rider, profile).rider);
  }
  rig::writeFileAtomically(output, rig::riderMotionGlb(rider, motion));
}

void runBake(const BakeOptions& o) {
  namespace fs = std::filesystem;
  const render::SceneSpec scene = render::loadScene(o.scene, {o.allow_impossible});
  const std::vector<int> frames = rig::parseFrameList(o.frames.empty() ? scene.frames : o.frames, "--frames");
  for (int frame : frames) render::warnImpossibleFrame(scene, frame);  // once a frame, whatever is written
  const rig::RigProfile profile = render::resolveProfile(scene);
  const std::unique_ptr<rig::Clip> clip = render::makeSceneClip(scene);

  if (o.channels.empty() && o.output.empty()) throw InputError("bake: nothing to write (expected --channels FILE or -o FILE.glb)");
  if (o.rider_only && o.output.empty()) throw InputError("bake: --rider-only: expected -o FILE.glb to write the rider's motion to");
  if (!o.output.empty()) {
    if (fs::path(o.output).extension() != ".glb") throw InputError("bake: -o: expected a .glb file, got " + o.output);
    if (o.rider_only)
      writeRiderGlb(scene, profile, *clip, frames, o.output);
    else
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
      "the names of docs/channels.md (horse: cm and degrees; rider: degrees and rider units),\n"
      "one row per frame.\n"
      "-o writes one glTF 2.0 binary: both characters as skinned meshes, each under its own root node\n"
      "(one armature each), their joints at every frame (translation and rotation, LINEAR), and every\n"
      "camera exactly as `stirrup render` frames and moves it, keyed at every frame (image size in the\n"
      "camera's extras). Frame F is at time (F - 1) / fps (docs/round-trip.md).\n"
      "--rider-only -o writes only the rider's skeleton and its animation, in the rider file's own joint\n"
      "names, units and axes (the scene's rider mapping undone), to put on the user's own rider rig.\n"
      "Example: stirrup bake scenes/trot.json --channels out/trot.csv\n"
      "         stirrup bake scenes/rear.json -o out/rear.glb");
  cmd->add_option("scene", opts->scene, "Scene file (JSON), e.g. scenes/trot.json")->required();
  cmd->add_option("--frames,-f", opts->frames, "Frames to bake (default: the scene's frames), e.g. 1-120x2");
  cmd->add_option("--channels", opts->channels, "Write the channels of every frame as CSV to FILE");
  cmd->add_option("-o,--output", opts->output, "Write the baked shot as glTF 2.0 (.glb)");
  cmd->add_flag("--rider-only", opts->rider_only,
                "With -o: write only the rider's skeleton animation, in the rider file's joint names");
  cmd->add_flag("--allow-impossible", opts->allow_impossible,
                "Bake a scene beyond a horse's limits (docs/horse-limits.md) anyway, warning on stderr for each frame");
  cmd->callback([opts] { runBake(*opts); });
}

}  // namespace stirrup::cli
