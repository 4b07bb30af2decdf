#include "render/farm/farm_shots.h"

#include <sys/vfs.h>
#include <unistd.h>

#include <fstream>
#include <map>
#include <system_error>

#include "render/scene/frame_sequence.h"
#include "render/scene/scene.h"
#include "rig/error.h"
#include "rig/io/frame_range.h"

namespace stirrup::render::farm {
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
                    const std::string& frames_spec, const std::vector<std::string>& render_args) {
  const SceneSpec scene = loadScene(scene_file);
  const CameraSpec& camera = findCamera(scene, camera_name);
  const std::vector<int> frames = rig::parseFrameList(frames_spec.empty() ? scene.frames : frames_spec, "--frames");
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
  shot.frames_dir = ".";
  const FrameSequence frames_named = FrameSequence::named("", name, ".png");  // as `stirrup render` names them
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
  plan.finish_command.insert(plan.finish_command.end(), {"--frames", rig::formatFrameList(frames), "--encode-only",
                                                         "--movie", (r.out / (name + ".mp4")).string()});
  return plan;
}

FarmPlan planMovies(const FarmRequest& r, const std::vector<MovieJob>& jobs, const MovieOptions& options,
                    const std::vector<std::string>& movie_args, bool subset) {
  if (jobs.empty()) throw InputError("--movies: no movies to render");
  MovieOptions o = options;
  o.out = r.out;
  FarmPlan plan = emptyPlan(r, "movies");
  std::string names;
  for (const MovieJob& job : jobs) {
    FarmShot shot;
    shot.name = job.name;
    shot.command = {r.stirrup.string(), "movies", "--out", r.out.string(), "--only", job.name};
    shot.command.insert(shot.command.end(), movie_args.begin(), movie_args.end());
    shot.command.push_back("--resume");
    shot.frames_dir = relativeTo(movieFrameDir(job, o), r.out);
    for (const fs::path& f : movieOutputs(job, o)) shot.outputs.push_back(relativeTo(f, r.out));
    int task = 0;
    for (std::vector<int>& chunk : chunkFrames(movieFrameList(job, o), r.chunk)) {
      FarmChunk c;
      c.task = ++task;
      for (int f : chunk)
        for (const fs::path& file : movieFrameFiles(job, o, f)) c.files.push_back(relativeTo(file, r.out));
      c.frames = std::move(chunk);
      shot.chunks.push_back(std::move(c));
    }
    plan.shots.push_back(std::move(shot));
    names += (names.empty() ? "" : ",") + job.name;
  }
  plan.finish_command = {r.stirrup.string(), "movies", "--out", r.out.string(), "--finish"};
  if (subset) plan.finish_command.insert(plan.finish_command.end(), {"--only", names});
  plan.finish_command.insert(plan.finish_command.end(), movie_args.begin(), movie_args.end());
  return plan;
}

void checkSharedOutput(const fs::path& out, int cluster_nodes) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) throw InputError("--out: " + out.string() + ": not a folder");
  // The filesystem is judged at the nearest folder that exists, before anything is made.
  fs::path existing = out;
  while (!fs::exists(existing, ec) && existing.has_parent_path() && existing != existing.parent_path())
    existing = existing.parent_path();
  struct statfs fs_info {};
  if (::statfs(existing.c_str(), &fs_info) != 0)
    throw InputError("--out: " + out.string() + ": cannot read its filesystem");
  // Filesystem magic numbers from linux/magic.h and the network filesystems' own headers.
  const std::map<long, const char*> in_memory = {{0x01021994L, "tmpfs"}, {0x858458f6L, "ramfs"}};
  const std::map<long, const char*> network = {
      {0x6969L, "NFS"},          {0x0BD00BD0L, "Lustre"}, {0x00C36400L, "CephFS"}, {0x47504653L, "GPFS"},
      {0x19830326L, "BeeGFS"},   {0xFE534D42L, "SMB2"},   {0xFF534D42L, "CIFS"},   {0x517BL, "SMB"},
      {0xAAD7AAEAL, "PanFS"},    {0x65735546L, "FUSE (e.g. a network mount)"}, {0x61756673L, "AFS"},
      {0x5346414FL, "OpenAFS"}};
  const long type = static_cast<long>(fs_info.f_type) & 0xFFFFFFFFL;
  if (const auto it = in_memory.find(type); it != in_memory.end())
    throw InputError("--out: " + out.string() + ": on " + it->second +
                     ", in this machine's memory, which the cluster's nodes do not share; use a folder on a shared "
                     "filesystem (NFS, Lustre, CephFS)");
  if (cluster_nodes > 1 && !network.count(type))
    throw InputError("--out: " + out.string() + ": on a local disk, not shared by the cluster's " +
                     std::to_string(cluster_nodes) + " nodes; use a folder on a shared filesystem (NFS, Lustre, CephFS)");
  fs::create_directories(out, ec);
  if (ec) throw InputError("--out: " + out.string() + ": cannot make the folder (" + ec.message() + ")");
  if (::access(out.c_str(), W_OK) != 0)
    throw InputError("--out: " + out.string() + ": not writable (the farm's tasks write their frames here)");
}

}  // namespace stirrup::render::farm
