// stirrup farm: renders a shot or the movie set on a Slurm cluster (render/farm/, docs/farm.md).
//   farm submit   one job array a shot (a task a chunk of frames) and a finishing job after them
//   farm status   what ran, failed or waits, per shot and chunk, from the manifest, the files and Slurm
//   farm resume   resubmits only the chunks whose frames are missing
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <tuple>

#include "cli/commands.h"
#include "cli/movie_set_options.h"
#include "cli/options.h"
#include "render/farm/farm_jobs.h"
#include "render/farm/farm_shots.h"
#include "render/farm/slurm.h"
#include "render/review/burn_in.h"
#include "rig/error.h"
#include "scene/data_dir.h"
#include "scene/file_shot.h"
#include "scene/preset.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace stirrup::cli {
namespace {

namespace fs = std::filesystem;

struct SubmitOptions {
  std::string scene;
  std::string camera;
  bool movies = false;
  MovieSetArgs set;
  std::string frames;
  std::vector<std::string> sets;
  std::string out;
  // 48 frames a task keeps the per-task cost (about 2 s of a slot: the scheduler's cycle and the program's
  // start) near a tenth of the task at the review preset; docs/farm.md has the measurements.
  int chunk = 48;
  render::SbatchSettings sbatch;
  std::string stirrup;
  bool dry_run = false;
};

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &tm);
  return text;
}

void printPlan(const render::FarmPlan& plan, bool dry_run) {
  std::size_t width = 6;
  for (const auto& shot : plan.shots) width = std::max(width, shot.name.size());
  for (const auto& shot : plan.shots) {
    std::printf("%-*s  ", static_cast<int>(width), shot.name.c_str());
    if (dry_run) std::printf("sbatch --array=1-%zu %s\n", shot.chunks.size(), render::scriptFile(plan, shot.name).c_str());
    else std::printf("job %s (%zu tasks)\n", shot.array_jobs.front().c_str(), shot.chunks.size());
  }
  std::printf("%-*s  ", static_cast<int>(width), "finish");
  if (dry_run) std::printf("sbatch --dependency=afterok:<the jobs above> %s\n", render::finishScriptFile(plan).c_str());
  else std::printf("job %s (after all of them)\n", plan.finish_jobs.front().c_str());
  std::printf("%s\n", render::manifestFile(plan.out).c_str());
}

void runSubmit(const SubmitOptions& o, const CLI::App& cmd) {
  // Everything is checked before anything is written or submitted.
  // --movies makes the movie set, or a glTF shot's movies (stirrup movies SHOT.glb) when SHOT.glb is given.
  const bool shot_movies = o.movies && scene::isGltfFile(o.scene);
  if (!shot_movies && o.movies == !o.scene.empty())
    throw rig::InputError("farm submit: expected a SCENE to render (with --camera), --movies for the movie set, or a glTF SHOT with --movies "
                     "for its movies, not " + std::string(o.movies ? "a scene with --movies" : "neither"));
  if (o.chunk <= 0) throw rig::InputError("--chunk: expected a positive number of frames a task, got " + std::to_string(o.chunk));
  if (o.sbatch.cpus_per_task <= 0)
    throw rig::InputError("--cpus-per-task: expected a positive number, got " + std::to_string(o.sbatch.cpus_per_task));
  if (o.out.empty()) throw rig::InputError("--out: expected the shared output folder");
  if (!o.movies)
    for (const char* movie_only : {"--only", "--frames-limit", "--scenes", "--scene", "--mov", "--no-mp4", "--keep-frames", "--date"})
      if (cmd.count(movie_only)) throw rig::InputError(std::string(movie_only) + ": only with --movies");
  if (o.movies)
    for (const char* render_only : {"--camera", "--frames", "--set"})
      if (cmd.count(render_only)) throw rig::InputError(std::string(render_only) + ": only with a SCENE, not with --movies");

  const fs::path stirrup = o.stirrup.empty() ? scene::programDir() / "stirrup" : fs::path(o.stirrup);
  if (!stirrup.is_absolute() || ::access(stirrup.c_str(), X_OK) != 0)
    throw rig::InputError("--stirrup: " + stirrup.string() + ": expected the absolute path of the stirrup program every node runs");

  render::requireSlurm();
  if (!o.sbatch.partition.empty()) {
    const std::vector<std::string> partitions = render::slurmPartitions();
    if (std::find(partitions.begin(), partitions.end(), o.sbatch.partition) == partitions.end()) {
      std::string names;
      for (const auto& p : partitions) names += (names.empty() ? "" : ", ") + p;
      throw rig::InputError("--partition: no partition \"" + o.sbatch.partition + "\" on this cluster (expected one of " + names + ")");
    }
  }
  const fs::path out = fs::absolute(o.out).lexically_normal();
  render::checkSharedOutput(out, render::slurmNodeCount());
  if (fs::exists(render::manifestFile(out)) && !o.dry_run)
    throw rig::InputError("--out: " + out.string() + " already holds a farm (farm.json): use stirrup farm status or resume, "
                     "or another folder");

  render::FarmRequest request;
  request.out = out;
  request.chunk = o.chunk;
  request.stirrup = stirrup;
  request.sbatch = o.sbatch;
  request.submitted = utcNow();
  render::FarmPlan plan;
  if (o.movies) {
    MovieSetArgs set = o.set;
    if (shot_movies) set.shot = o.scene;
    set.out = out.string();
    if (set.date.empty()) set.date = render::todayUtc();  // every task and the slate say the same day
    const render::MovieOptions mo = movieOptions(set);
    plan = render::planMovies(request, selectMovies(set, mo), mo, movieSetArguments(set), !set.only.empty());
  } else {
    std::vector<std::string> args;
    if (cmd.count("--preset")) args.insert(args.end(), {"--preset", o.set.preset});
    if (!o.set.resolution.empty()) {
      parseResolution(o.set.resolution);
      args.insert(args.end(), {"--resolution", o.set.resolution});
    }
    for (const std::string& s : o.sets) args.insert(args.end(), {"--set", s});
    if (o.set.allow_impossible) args.push_back("--allow-impossible");
    // The scene as the tasks must find it: absolute, after the data-folder lookup of a relative path.
    const fs::path scene_file = fs::absolute(scene::findSceneFile(o.scene));
    // A view camera framed once, here, as the tasks see the scene (preset, size, profile settings):
    // every chunk reads it from the plan instead of framing the view again.
    scene::SceneSpec scene = scene::loadScene(scene_file, {o.set.allow_impossible});
    if (cmd.count("--preset")) scene::applyPreset(scene, scene::findPreset(o.set.preset));
    if (!o.set.resolution.empty()) std::tie(scene.width, scene.height) = parseResolution(o.set.resolution);
    const rig::RigProfile profile = scene::resolveProfileForEveryPair(scene, parseSets(o.sets));
    const auto framed = render::planCamera(scene, profile, scene::findCamera(scene, o.camera));
    plan = render::planRender(request, scene_file, o.camera, o.frames, args, framed);
  }

  if (o.dry_run) {
    render::writeScripts(plan);
    render::writeManifest(plan);
  } else {
    render::submitPlan(plan);
  }
  printPlan(plan, o.dry_run);
}

void runStatus(const std::string& out, bool wait) {
  const render::FarmPlan plan = render::readManifest(out);
  render::requireSlurm();
  if (wait) render::waitForPlan(plan);
  const render::FarmStatus status = render::farmStatus(plan);
  std::fputs(render::describeStatus(plan, status).c_str(), stdout);
}

void runResume(const std::string& out) {
  render::FarmPlan plan = render::readManifest(out);
  render::requireSlurm();
  const render::ResumeResult r = render::resumePlan(plan);
  if (r.partial_files_removed > 0) std::printf("removed %d partial files left by killed tasks\n", r.partial_files_removed);
  for (const std::string& chunk : r.resubmitted) std::printf("resubmitted %s\n", chunk.c_str());
  if (!r.array_jobs.empty()) std::printf("jobs %s\n", r.array_jobs.c_str());
  if (!r.finish_job.empty()) std::printf("finish job %s\n", r.finish_job.c_str());
  if (r.resubmitted.empty() && r.finish_job.empty()) std::printf("nothing to resume\n");
}

}  // namespace

void addFarmCommand(CLI::App& app) {
  CLI::App* farm = app.add_subcommand("farm", "Render a shot or the movie set on a Slurm cluster (docs/farm.md)");
  farm->require_subcommand(1);
  farm->footer(
      "The output folder must be on a filesystem every node sees, and stirrup installed at the same path on\n"
      "every node. A local one-node cluster for trying it: scripts/slurm-local up.");

  auto submit = std::make_shared<SubmitOptions>();
  CLI::App* s = farm->add_subcommand("submit", "Submit one job array a shot and a finishing job after them");
  s->footer(
      "Each task renders one chunk of frames with stirrup render/movies --resume into OUT; the finishing job\n"
      "(--dependency=afterok) encodes the movies and makes the contact sheets, plots and index exactly as\n"
      "stirrup movies does. Job ids go to stdout and OUT/farm.json; scripts and logs to OUT/farm/.\n"
      "A glTF shot's movies (a stirrup bake, or Blender's export of one) as stirrup movies SHOT.glb makes them:\n"
      "SHOT.glb --movies, its look from --scene LOOK.json if given.\n"
      "Examples: stirrup farm submit --movies --out /shared/review --chunk 24 --partition render\n"
      "          stirrup farm submit scenes/trot.json --camera side --out /shared/trot --time 30:00\n"
      "          stirrup farm submit out/cavalry.glb --movies --scene scenes/cavalry.json --only persp --out /shared/cavalry");
  s->add_option("scene", submit->scene, "Scene file to render through --camera, or with --movies a glTF shot whose movies to make");
  s->add_option("--camera,-c", submit->camera, "The scene's camera (default: its first)");
  s->add_flag("--movies", submit->movies, "Render the movie set (stirrup movies --list) instead of one scene");
  addMovieSetOptions(s, submit->set);
  s->add_option("--frames,-f", submit->frames, "Frames of the SCENE to render (default: the scene's)");
  s->add_option("--set", submit->sets, "Rig-profile override KEY=NUMBER for the SCENE (repeatable; see stirrup render)");
  s->add_option("--out,-o", submit->out, "Output folder, shared by every node")->required();
  s->add_option("--chunk", submit->chunk, "Frames a task")->capture_default_str();
  s->add_option("--partition", submit->sbatch.partition, "Slurm partition (default: the cluster's default)");
  s->add_option("--account", submit->sbatch.account, "Slurm account to charge");
  s->add_option("--time", submit->sbatch.time, "Time limit a task, in Slurm's format (e.g. 30:00)");
  s->add_option("--mem", submit->sbatch.mem, "Memory a task, in Slurm's format (e.g. 2G)");
  s->add_option("--cpus-per-task", submit->sbatch.cpus_per_task, "CPUs a task (its render threads)")->capture_default_str();
  s->add_option("--stirrup", submit->stirrup,
                "The stirrup program the nodes run, an absolute path (default: this one)");
  s->add_flag("--dry-run", submit->dry_run, "Write the scripts and the manifest, submit nothing");
  s->callback([submit, s] { runSubmit(*submit, *s); });

  auto status_out = std::make_shared<std::string>();
  auto wait = std::make_shared<bool>(false);
  CLI::App* st = farm->add_subcommand("status", "What ran, failed or is pending, per shot and chunk");
  st->add_option("out", *status_out, "The output folder given to farm submit")->required();
  st->add_flag("--wait", *wait, "First wait until none of its jobs is pending or running");
  st->callback([status_out, wait] { runStatus(*status_out, *wait); });

  auto resume_out = std::make_shared<std::string>();
  CLI::App* r = farm->add_subcommand("resume", "Resubmit only the chunks whose frames are missing");
  r->add_option("out", *resume_out, "The output folder given to farm submit")->required();
  r->callback([resume_out] { runResume(*resume_out); });
}

}  // namespace stirrup::cli
