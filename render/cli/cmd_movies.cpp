// stirrup movies: the review set (the thesis's Appendix A movies, more movements, turntables and the
// Muybridge comparison) with contact sheets, channel plots and an index.html, in one command.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "render/cli/commands.h"
#include "render/cli/progress.h"
#include "render/cli/options.h"
#include "render/data_dir.h"
#include "render/review/index_page.h"
#include "render/review/movie_set.h"
#include "render/preset.h"
#include "rig/error.h"

namespace stirrup::cli {
namespace {

struct MoviesOptions {
  std::string out = "out/movies";
  std::string preset = "review";
  std::vector<std::string> only;
  int frames_limit = 0;
  std::string resolution;
  std::string scenes;
  std::string mov;  // "", "prores" or "h264"
  bool no_mp4 = false;
  bool keep_frames = false;
  bool list = false;
  bool progress = false;
  int threads = 0;
  std::string date;
};

void runMovies(const MoviesOptions& o) {
  namespace fs = std::filesystem;
  render::findPreset(o.preset);  // a bad name is an error before any work
  render::MovieOptions mo;
  mo.out = o.out;
  mo.preset = o.preset;
  mo.frames_limit = o.frames_limit;
  mo.keep_frames = o.keep_frames;
  mo.threads = o.threads;
  mo.date = o.date;
  mo.mp4 = !o.no_mp4;
  if (!o.mov.empty()) {
    if (o.mov != "prores" && o.mov != "h264") throw InputError("--mov: expected prores or h264, got \"" + o.mov + "\"");
    mo.mov = true;
    mo.mov_codec = o.mov == "prores" ? render::MovieCodec::ProRes : render::MovieCodec::H264;
  }
  if (!mo.mp4 && !mo.mov) throw InputError("--no-mp4: expected --mov as well (there would be no movie)");
  if (!o.resolution.empty()) std::tie(mo.width, mo.height) = parseResolution(o.resolution);
  // The default scenes are the data folder's (render/data_dir.h); Muybridge's plate is in ../shared beside
  // it (the repository's, in a build tree) or $STIRRUP_SHARED_DIR.
  const fs::path scenes = o.scenes.empty() ? render::dataDir() / "scenes" : fs::path(o.scenes);
  if (!fs::is_directory(scenes)) throw InputError("--scenes: " + scenes.string() + ": no such folder");
  const std::optional<fs::path> data = render::findDataDir();
  mo.reference_dir = render::sharedDir(data ? *data : fs::weakly_canonical(scenes).parent_path()) / "reference";

  std::vector<render::MovieJob> jobs = render::defaultMovieSet(scenes, mo.reference_dir);
  if (!o.only.empty()) {
    std::set<std::string> known;
    for (const auto& j : jobs) known.insert(j.name);
    for (const std::string& n : o.only)
      if (!known.count(n)) {
        std::string names;
        for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
        throw InputError("--only: no movie named \"" + n + "\" (expected one of " + names + ")");
      }
    std::erase_if(jobs, [&](const render::MovieJob& j) {
      return std::find(o.only.begin(), o.only.end(), j.name) == o.only.end();
    });
  }
  if (o.list) {
    for (const auto& j : jobs) std::printf("%s\t%s\t%s\n", j.name.c_str(), j.scene.string().c_str(), j.camera.c_str());
    return;
  }
  if (fs::exists(o.out) && !fs::is_directory(o.out)) throw InputError("--out: " + o.out + ": not a folder");
  fs::create_directories(o.out);

  int total = 0;
  for (const auto& j : jobs) total += render::movieFrameCount(j, mo);
  ProgressBar bar("movies", total, o.progress);
  int done = 0;
  const auto start = std::chrono::steady_clock::now();
  std::map<fs::path, fs::path> plots;  // scene file -> its plot
  std::vector<render::MovieResult> results;
  for (const auto& j : jobs) {
    if (!plots.count(j.scene)) plots[j.scene] = render::writeMovementPlot(j.scene, o.out);
    render::MovieResult r = render::renderMovie(j, mo, [&] { bar.step(++done); });
    r.plot = plots[j.scene];
    results.push_back(std::move(r));
  }
  const fs::path index = render::writeIndexPage(o.out, results);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The one line a script needs; details live in the index.
  std::printf("%s\n", index.string().c_str());
  if (o.progress || isatty(STDERR_FILENO))
    std::fprintf(stderr, "%zu movies, %d frames in %.1f s\n", results.size(), total, seconds);
}

}  // namespace

void addMoviesCommand(CLI::App& app) {
  auto opts = std::make_shared<MoviesOptions>();
  CLI::App* cmd = app.add_subcommand("movies", "Render the review movie set with contact sheets, plots and index.html");
  cmd->footer(
      "Writes OUT/NAME.mp4 (H.264 yuv420p CRF 18; --mov adds NAME.mov), OUT/NAME_sheet.png, OUT/SCENE_plot.png\n"
      "and OUT/index.html. Every movie starts with a one-second slate; every frame has burn-ins.\n"
      "gallop_layered is included when ../shared/reference (or $STIRRUP_SHARED_DIR/reference) holds the\n"
      "Muybridge plate. Example: stirrup movies --out out/movies --only trot_side,trot_persp");
  cmd->add_option("--out,-o", opts->out, "Output folder")->capture_default_str();
  cmd->add_option("--preset,-p", opts->preset, "Quality preset: draft, review or final")->capture_default_str();
  cmd->add_option("--only", opts->only, "Only these movies (comma-separated names; see --list)")->delimiter(',');
  cmd->add_option("--frames-limit", opts->frames_limit, "Render at most the first N frames of each movie")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--resolution", opts->resolution, "WIDTHxHEIGHT instead of the scenes' (e.g. 640x360)");
  cmd->add_option("--scenes", opts->scenes, "Folder of scene files (default: scenes/ in stirrup's data folder, docs/install.md)");
  cmd->add_option("--mov", opts->mov, "Also write QuickTime NAME.mov: prores (ProRes 422 HQ) or h264");
  cmd->add_flag("--no-mp4", opts->no_mp4, "Write no .mp4 (with --mov)");
  cmd->add_flag("--keep-frames", opts->keep_frames, "Keep the frames as OUT/frames/NAME/NAME.####.png");
  cmd->add_option("--date", opts->date, "The slate's date (default: today, UTC)");
  cmd->add_option("--threads,-t", opts->threads, "Render threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--list", opts->list, "Print the movies of the set (name, scene, camera) and exit");
  cmd->add_flag("--progress", opts->progress, "Show the progress bar even when stderr is not a terminal");
  cmd->callback([opts] { runMovies(*opts); });
}

}  // namespace stirrup::cli
