#include "render/farm/farm_shots.h"

#include <sys/vfs.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <map>
#include <system_error>

#include "rig/error.h"
#include "scene/frame_range.h"
#include "scene/frame_sequence.h"
#include "scene/rig_profile_json.h"
#include "scene/scene.h"
#include "scene/shot_camera.h"
#include "scene/shot_evaluator.h"
#include "scene/view.h"

namespace stirrup::render {
namespace fs = std::filesystem;

namespace {

std::string relativeTo(const fs::path& file, const fs::path& out) { return fs::relative(file, out).generic_string(); }

FarmPlan emptyPlan(const FarmRequest& r, const std::string& kind) {
  FarmPlan plan;
  plan.out = r.out;
  plan.kind = kind;
  plan.submitted = r.submitted;
  plan.sbatch = r.sbatch;
  return plan;
}

}  // namespace

FarmPlan planRender(const FarmRequest& r, const fs::path& scene_file, const std::string& camera_name,
                    const std::string& frames_spec, const std::vector<std::string>& render_args,
                    const std::optional<PlannedCamera>& framed) {
  // The tasks render it with --allow-impossible when asked to: it loads here as it will there.
  const bool allow = std::find(render_args.begin(), render_args.end(), "--allow-impossible") != render_args.end();
  const scene::SceneSpec scene = scene::loadScene(scene_file, {allow});
  const scene::CameraSpec& camera = scene::findCamera(scene, camera_name);
  const std::vector<int> frames = scene::parseFrameList(frames_spec.empty() ? scene.frames : frames_spec, "--frames");
  FarmPlan plan = emptyPlan(r, "render");
  const std::string name = scene.name + "_" + camera.name;
  const std::vector<std::string> shot_args = {"render", fs::absolute(scene_file).string(), "--camera", camera.name,
                                              "--out", r.out.string()};
  FarmShot shot;
  shot.name = name;
  shot.command = {r.stirrup.string()};
  shot.command.insert(shot.command.end(), shot_args.begin(), shot_args.end());
  shot.command.insert(shot.command.end(), render_args.begin(), render_args.end());
  shot.command.push_back("--resume");
  if (framed) {
    if (framed->name != camera.name)
      throw std::invalid_argument("planRender: the framed camera is " + framed->name + "'s, not " + camera.name + "'s");
    shot.camera = framed;
    shot.command.insert(shot.command.end(), {"--camera-plan", manifestFile(r.out).string()});
  }
  shot.frames_dir = ".";
  const scene::FrameSequence frames_named = scene::FrameSequence::named("", name, ".png");  // as `stirrup render` names them
  shot.outputs = {name + ".mp4"};
  int task = 0;
  for (std::vector<int>& chunk : chunkFrames(frames, r.chunk)) {
    FarmChunk c;
    c.task = ++task;
    for (int f : chunk) c.files.push_back(frames_named.fileName(f));
    c.frames = std::move(chunk);
    shot.chunks.push_back(std::move(c));
  }
  plan.shots.push_back(std::move(shot));
  plan.finish_command = {r.stirrup.string()};
  plan.finish_command.insert(plan.finish_command.end(), shot_args.begin(), shot_args.end());
  plan.finish_command.insert(plan.finish_command.end(), render_args.begin(), render_args.end());
  plan.finish_command.insert(plan.finish_command.end(), {"--frames", scene::formatFrameList(frames), "--encode-only",
                                                         "--movie", (r.out / (name + ".mp4")).string()});
  return plan;
}

std::string framingKey(const scene::SceneSpec& scene, const rig::RigProfile& profile) {
  std::string text;
  if (!scene.file.empty()) {
    std::ifstream in(scene.file, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text += "\nframes " + scene.frames + "\nsize " + std::to_string(scene.width) + "x" + std::to_string(scene.height);
  text += "\nprofile " + scene::profileToJson(profile).dump();
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bits
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

std::optional<PlannedCamera> planCamera(const scene::SceneSpec& scene, const rig::RigProfile& profile, const scene::CameraSpec& camera,
                                        int threads) {
  if (camera.view.empty()) return std::nullopt;
  scene::ShotEvaluator characters(scene, profile, threads);
  const scene::ShotCamera framed(characters, camera);
  const scene::CameraSpec& s = framed.spec();
  PlannedCamera c;
  c.name = camera.name;
  c.key = framingKey(scene, profile);
  c.position = s.position, c.target = s.target, c.up = s.up, c.seat_from_pivot_cm = s.seat_from_pivot_cm;
  c.ortho_height_cm = s.ortho_height_cm, c.fov_deg = s.fov_deg;
  return c;
}

scene::CameraSpec plannedCameraSpec(const scene::SceneSpec& scene, const rig::RigProfile& profile, const scene::CameraSpec& camera,
                             const PlannedCamera& planned, const std::string& where) {
  if (planned.name != camera.name)
    throw rig::InputError(where + ".name: expected \"" + camera.name + "\" (the camera rendered), got \"" + planned.name + "\"");
  if (camera.view.empty())
    throw rig::InputError(where + ": expected no camera for " + camera.name + ", which has no view to frame");
  const std::string key = framingKey(scene, profile);
  if (planned.key != key)
    throw rig::InputError(where + ".key: expected " + key + " (the scene, its frames, the image size and the rig profile as they "
                     "are now), got " + planned.key + ": they changed since the plan was made; submit the farm again");
  scene::CameraSpec spec = camera;
  scene::applyViewPreset(spec);
  spec.view.clear();  // framed already: Shot takes it as it is
  spec.position = planned.position, spec.target = planned.target, spec.up = planned.up;
  spec.seat_from_pivot_cm = planned.seat_from_pivot_cm;
  spec.ortho_height_cm = planned.ortho_height_cm, spec.fov_deg = planned.fov_deg;
  return spec;
}

PlannedCamera plannedCameraOf(const fs::path& file, const std::string& shot, std::string& where) {
  const FarmPlan plan = readManifestFile(file);
  for (std::size_t i = 0; i < plan.shots.size(); ++i) {
    if (plan.shots[i].name != shot) continue;
    where = file.string() + ": shots[" + std::to_string(i) + "].camera";
    if (!plan.shots[i].camera) throw rig::InputError(where + ": expected the framed camera of " + shot + " (missing)");
    return *plan.shots[i].camera;
  }
  throw rig::InputError(file.string() + ": shots: expected a shot named " + shot + " (the scene's and camera's names)");
}

FarmPlan planMovies(const FarmRequest& r, const std::vector<MovieJob>& jobs, const MovieOptions& options,
                    const std::vector<std::string>& movie_args, bool subset) {
  if (jobs.empty()) throw rig::InputError("--movies: no movies to render");
  MovieOptions o = options;
  o.out = r.out;
  FarmPlan plan = emptyPlan(r, "movies");
  std::string names;
  for (const MovieJob& job : jobs) {
    FarmShot shot;
    shot.name = job.name;
    // --only after the movies' own arguments: before a glTF shot's path, the option (a list) would take
    // the path for a second name.
    shot.command = {r.stirrup.string(), "movies", "--out", r.out.string()};
    shot.command.insert(shot.command.end(), movie_args.begin(), movie_args.end());
    shot.command.insert(shot.command.end(), {"--only", job.name, "--resume"});
    shot.frames_dir = relativeTo(movieFrameDir(job, o), r.out);
    for (const fs::path& f : movieOutputs(job, o)) shot.outputs.push_back(relativeTo(f, r.out));
    int task = 0;
    const std::vector<int> sheet_frames = movieSheetFrames(job, o);  // the scene read once, not once a frame
    for (std::vector<int>& chunk : chunkFrames(movieFrameList(job, o), r.chunk)) {
      FarmChunk c;
      c.task = ++task;
      for (int f : chunk)
        for (const fs::path& file : movieFrameFiles(job, o, f, sheet_frames)) c.files.push_back(relativeTo(file, r.out));
      c.frames = std::move(chunk);
      shot.chunks.push_back(std::move(c));
    }
    plan.shots.push_back(std::move(shot));
    names += (names.empty() ? "" : ",") + job.name;
  }
  plan.finish_command = {r.stirrup.string(), "movies", "--out", r.out.string(), "--finish"};
  plan.finish_command.insert(plan.finish_command.end(), movie_args.begin(), movie_args.end());
  if (subset) plan.finish_command.insert(plan.finish_command.end(), {"--only", names});
  return plan;
}

void checkSharedOutput(const fs::path& out, int cluster_nodes) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) throw rig::InputError("--out: " + out.string() + ": not a folder");
  // The filesystem is judged at the nearest folder that exists, before anything is made.
  fs::path existing = out;
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  struct statfs fs_info {};
  if (::statfs(existing.c_str(), &fs_info) != 0)
    throw rig::InputError("--out: " + out.string() + ": cannot read its filesystem");
  // Filesystem magic numbers from linux/magic.h and the network filesystems' own headers.
  const std::map<long, const char*> in_memory = {{0x01021994L, "tmpfs"}, {0x858458f6L, "ramfs"}};
  const std::map<long, const char*> network = {
      {0x6969L, "NFS"},          {0x0BD00BD0L, "Lustre"}, {0x00C36400L, "CephFS"}, {0x47504653L, "GPFS"},
      {0x19830326L, "BeeGFS"},   {0xFE534D42L, "SMB2"},   {0xFF534D42L, "CIFS"},   {0x517BL, "SMB"},
      {0xAAD7AAEAL, "PanFS"},    {0x65735546L, "FUSE (e.g. a network mount)"}, {0x61756673L, "AFS"},
      {0x5346414FL, "OpenAFS"}};
  const long type = static_cast<long>(fs_info.f_type) & 0xFFFFFFFFL;
  if (const auto it = in_memory.find(type); it != in_memory.end())
    throw rig::InputError("--out: " + out.string() + ": on " + it->second +
                     ", in this machine's memory, which the cluster's nodes do not share; use a folder on a shared "
                     "filesystem (NFS, Lustre, CephFS)");
  if (cluster_nodes > 1 && !network.count(type))
    throw rig::InputError("--out: " + out.string() + ": on a local disk, not shared by the cluster's " +
                     std::to_string(cluster_nodes) + " nodes; use a folder on a shared filesystem (NFS, Lustre, CephFS)");
  fs::create_directories(out, ec);
  if (ec) throw rig::InputError("--out: " + out.string() + ": cannot make the folder (" + ec.message() + ")");
  if (::access(out.c_str(), W_OK) != 0)
    throw rig::InputError("--out: " + out.string() + ": not writable (the farm's tasks write their frames here)");
}

}  // namespace stirrup::render
