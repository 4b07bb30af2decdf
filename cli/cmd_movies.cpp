// stirrup movies: the review set (the thesis's Appendix A movies, more movements, turntables and the
// Muybridge comparison) with contact sheets, channel plots and an index.html, in one command.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include <sys/resource.h>

#include "cli/commands.h"
#include "cli/movie_set_options.h"
#include "cli/options.h"
#include "cli/progress.h"
#include "render/review/index_page.h"
#include "render/review/movie_set.h"
#include "render/tracer/stopwatch.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "scene/data_dir.h"
#include "scene/file_shot.h"
#include "scene/frame_range.h"
#include "scene/preset.h"

namespace stirrup::cli {
namespace {

struct MoviesOptions {
  MovieSetArgs set;
  std::string frames;  // stage 1 only, for one movie (a farm task's share)
  bool resume = false;
  bool finish = false;
  bool list = false;
  bool progress = false;
  std::string timings;  // a TSV of where the time went, movie by movie
};

// One row a movie: its rendered frames, the seconds its frames took (set-up included; frames encoded from
// memory: with the encoding and the sheet) and the seconds its movie, sheet and plot took after them
// (from memory: the plot), and the encoders' CPU seconds (ffmpeg's: 0 for movies encoded from PNGs, which
// this table does not count), in the set's order. Written to a temporary name, then renamed.
void writeTimings(const std::filesystem::path& file, const std::vector<render::MovieResult>& results,
                  const std::vector<double>& render_s, const std::vector<double>& finish_s) {
  rig::replaceFileAtomically(file, [&](const std::filesystem::path& partial) {
    std::ofstream o(partial);
    if (!o) throw rig::InputError("--timings: " + file.string() + ": cannot write (does its folder exist?)");
    o << "movie\tframes\trender_s\tfinish_s\trender_s_per_frame\tencode_cpu_s\n";
    char line[512];
    for (std::size_t i = 0; i < results.size(); ++i) {
      const int frames = results[i].frames;
      std::snprintf(line, sizeof line, "%s\t%d\t%.3f\t%.3f\t%.4f\t%.3f\n", results[i].name.c_str(), frames, render_s[i],
                    finish_s[i], frames > 0 ? render_s[i] / frames : 0.0, results[i].encode_cpu_s);
      o << line;
    }
    if (!o.flush()) throw rig::InputError("--timings: " + file.string() + ": write failed");
  });
}

// The movement's channel plot beside a movie (one a scene file, written once); a glTF shot's rider is
// posed as the file keys her: no channels of the rig's to plot.
void addPlot(const render::MovieJob& job, const render::MovieOptions& mo, const std::filesystem::path& out,
             std::map<std::filesystem::path, std::filesystem::path>& plots, render::MovieResult& result) {
  if (scene::isGltfFile(job.scene)) return;
  if (!plots.count(job.scene)) plots[job.scene] = render::writeMovementPlot(job.scene, out, mo.allow_impossible);
  result.plot = plots[job.scene];
}

// This process's CPU seconds so far, its own and its finished children's (the encoders).
double cpuSeconds() {
  double total = 0.0;
  for (const int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage u{};
    getrusage(who, &u);
    total += double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  return total;
}

void runMovies(const MoviesOptions& o) {
  namespace fs = std::filesystem;
  const render::MovieOptions mo = movieOptions(o.set);
  const std::vector<render::MovieJob> jobs = selectMovies(o.set, mo);
  if (o.list) {
    for (const auto& j : jobs) std::printf("%s\t%s\t%s\n", j.name.c_str(), j.scene.string().c_str(), j.camera.c_str());
    return;
  }
  if (!o.frames.empty() && o.finish) throw rig::InputError("--frames: renders frames only; --finish makes movies of frames already rendered, not both");
  if (!o.timings.empty() && !o.frames.empty()) throw rig::InputError("--timings: a farm task's share (--frames) makes no movie to time");
  if (!o.timings.empty()) {  // checked before any frame is rendered
    const fs::path folder = fs::absolute(o.timings).parent_path();
    if (!fs::is_directory(folder)) throw rig::InputError("--timings: " + o.timings + ": cannot write (does its folder exist?)");
  }
  if (!o.frames.empty() && jobs.size() != 1)
    throw rig::InputError("--frames: expected exactly one movie with --only NAME, got " + std::to_string(jobs.size()));
  const fs::path out = o.set.out;
  if (fs::exists(out) && !fs::is_directory(out)) throw rig::InputError("--out: " + out.string() + ": not a folder");
  fs::create_directories(out);

  // Stage 1 (render/review/movie_set.h): the frames, unless --finish.
  std::vector<std::vector<int>> frames(jobs.size());
  int total = 0;
  if (!o.finish)
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      frames[i] = o.frames.empty() ? render::movieFrameList(jobs[i], mo) : scene::parseFrameList(o.frames, "--frames");
      total += static_cast<int>(frames[i].size());
    }
  ProgressBar bar("movies", total, o.progress);
  int done = 0;
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> render_s(jobs.size(), 0.0), finish_s(jobs.size(), 0.0);
  // A whole run makes each movie at once, its frames piped to the encoder from memory (frames on disk
  // only with --keep-frames); a farm's stages (--frames, --finish) and --resume go through the files.
  const bool from_memory = !o.finish && !o.resume && o.frames.empty();
  std::vector<render::MovieResult> results;
  std::map<fs::path, fs::path> plots;  // scene file -> its plot
  for (std::size_t i = 0; i < jobs.size() && from_memory; ++i) {
    results.push_back(render::renderMovie(jobs[i], mo, [&] { bar.step(++done); }));
    render_s[i] = results.back().seconds;
    const auto plot_start = std::chrono::steady_clock::now();
    addPlot(jobs[i], mo, out, plots, results.back());
    finish_s[i] = render::secondsSince(plot_start);
    results.back().seconds += finish_s[i];
  }
  for (std::size_t i = 0; i < jobs.size() && !o.finish && !from_memory; ++i) {
    const auto movie_start = std::chrono::steady_clock::now();
    render::renderMovieFrames(jobs[i], mo, frames[i], o.resume, [&] { bar.step(++done); });
    render_s[i] = render::secondsSince(movie_start);
  }
  if (!o.frames.empty()) return;  // a farm task: the finishing job makes the movie

  // Stage 2: movies, contact sheets, plots, the index.
  for (std::size_t i = 0; i < jobs.size() && !from_memory; ++i) {
    const auto movie_start = std::chrono::steady_clock::now();
    render::MovieResult r = render::finishMovie(jobs[i], mo);
    addPlot(jobs[i], mo, out, plots, r);
    finish_s[i] = render::secondsSince(movie_start);
    r.seconds = render_s[i] + finish_s[i];
    results.push_back(std::move(r));
  }
  const double seconds = render::secondsSince(start);
  if (!o.timings.empty()) writeTimings(o.timings, results, render_s, finish_s);
  const fs::path index = render::writeIndexPage(out, results);
  // The one line a script needs; details live in the index.
  std::printf("%s\n", index.string().c_str());
  if (o.progress || isatty(STDERR_FILENO)) {
    double encode_s = 0.0;
    for (const render::MovieResult& r : results) encode_s += r.encode_cpu_s;
    std::fprintf(stderr, "%zu movies, %d frames in %.1f s; CPU %.1f s, of which the encoders %.1f s\n", results.size(),
                 total, seconds, cpuSeconds(), encode_s);
  }
}

}  // namespace

void addMoviesCommand(CLI::App& app) {
  auto opts = std::make_shared<MoviesOptions>();
  CLI::App* cmd = app.add_subcommand("movies", "Render the review movie set with contact sheets, plots and index.html");
  cmd->footer(
      "Writes OUT/NAME.mp4 (H.264 yuv420p CRF 18; --mov adds NAME.mov), OUT/NAME_sheet.png, OUT/SCENE_plot.png\n"
      "and OUT/index.html. Every movie starts with a one-second slate; every frame has burn-ins.\n"
      "gallop_layered is included when ../shared/reference (or $STIRRUP_SHARED_DIR/reference) holds the\n"
      "Muybridge plate. Example: stirrup movies --out out/movies --only trot_side,trot_persp\n"
      "A glTF shot (a stirrup bake, or Blender's export of one) makes its own set instead, as stirrup render\n"
      "renders it: STEM_side, STEM_persp, STEM_close, STEM_turntable and STEM_top over the shot's frames, no plot\n"
      "(--only takes the names or the views; layered, follow and turntable_pose are refused, naming the view).\n"
      "With --scene LOOK.json a glTF shot's movies are the look's cameras instead (STEM_CAMERA), made with its image size,\n"
      "quality, sun, haze and ground, as stirrup render SHOT.glb --scene LOOK.json renders them.\n"
      "Example: stirrup movies out/trot.glb --out out/trot-movies --only side,close\n"
      "         stirrup movies out/cross_country.glb --scene scenes/cross_country.json --only persp");
  cmd->add_option("shot", opts->set.shot,
                  "A glTF shot (.glb/.gltf) to make the movies of, as the file keys it, instead of the scene set");
  cmd->add_option("--out,-o", opts->set.out, "Output folder")->capture_default_str();
  addMovieSetOptions(cmd, opts->set);
  cmd->add_option("--threads,-t", opts->set.threads, "Render threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--resume", opts->resume,
                "Skip frames already in OUT/frames/NAME/ (left by --keep-frames, an interrupted run or a farm task)");
  cmd->add_option("--frames,-f", opts->frames,
                  "Only render these frames of the one --only movie into OUT/frames/NAME/ and stop (a farm task's "
                  "share, docs/farm.md; --finish then makes the movie)");
  cmd->add_flag("--finish", opts->finish,
                "Render nothing: make the movies, contact sheets, plots and index from frames already in OUT/frames/ "
                "(a farm's last step); an error names the first missing frame");
  cmd->add_flag("--list", opts->list, "Print the movies of the set (name, scene, camera) and exit");
  cmd->add_flag("--progress", opts->progress, "Show the progress bar even when stderr is not a terminal");
  cmd->add_option("--timings", opts->timings,
                  "Also write where the time went as a TSV, a row a movie: frames, seconds rendering them (set-up "
                  "included), seconds making the movie, sheet and plot");
  cmd->callback([opts] { runMovies(*opts); });
}

}  // namespace stirrup::cli
