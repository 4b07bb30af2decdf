#include "cli/movie_set_options.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <set>
#include <tuple>

#include "cli/options.h"
#include "rig/error.h"
#include "scene/data_dir.h"
#include "scene/file_shot.h"
#include "scene/preset.h"
#include "scene/scene.h"

namespace stirrup::cli {
namespace fs = std::filesystem;

void addMovieSetOptions(CLI::App* cmd, MovieSetArgs& a) {
  cmd->add_option("--preset,-p", a.preset, "Quality preset: draft, review or final")->capture_default_str();
  cmd->add_option("--only", a.only, "Only these movies (comma-separated names, or the option again; see stirrup movies --list)")
      ->delimiter(',')
      ->allow_extra_args(false);  // one value an occurrence: `--only side SHOT.glb` leaves the shot its place
  cmd->add_option("--frames-limit", a.frames_limit, "Render at most the first N frames of each movie")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--resolution", a.resolution, "WIDTHxHEIGHT instead of the scenes' (e.g. 640x360)");
  cmd->add_option("--scenes", a.scenes, "Folder of scene files (default: scenes/ in stirrup's data folder, docs/install.md)");
  cmd->add_option("--scene", a.look,
                  "A glTF shot's look: the scene whose cameras (a movie each), image size, quality, sun, haze and ground its movies "
                  "are made with, as stirrup render SHOT.glb --scene renders it");
  cmd->add_option("--mov", a.mov, "Also write QuickTime NAME.mov: prores (ProRes 422 HQ) or h264");
  cmd->add_flag("--no-mp4", a.no_mp4, "Write no .mp4 (with --mov)");
  cmd->add_flag("--keep-frames", a.keep_frames, "Keep the frames as OUT/frames/NAME/NAME.####.png");
  cmd->add_option("--date", a.date, "The slate's date (default: today, UTC)");
  cmd->add_flag("--allow-impossible", a.allow_impossible,
                "Render scenes beyond a horse's limits (docs/horse-limits.md) anyway, warning on stderr for each frame");
}

render::MovieOptions movieOptions(const MovieSetArgs& a) {
  scene::findPreset(a.preset);  // a bad name is an error before any work
  render::MovieOptions mo;
  mo.out = a.out;
  mo.preset = a.preset;
  mo.frames_limit = a.frames_limit;
  mo.keep_frames = a.keep_frames;
  mo.threads = a.threads;
  mo.date = a.date;
  mo.mp4 = !a.no_mp4;
  mo.allow_impossible = a.allow_impossible;
  if (!a.mov.empty()) {
    if (a.mov != "prores" && a.mov != "h264") throw rig::InputError("--mov: expected prores or h264, got \"" + a.mov + "\"");
    mo.mov = true;
    mo.mov_codec = a.mov == "prores" ? render::MovieCodec::ProRes : render::MovieCodec::H264;
  }
  if (!mo.mp4 && !mo.mov) throw rig::InputError("--no-mp4: expected --mov as well (there would be no movie)");
  if (!a.resolution.empty()) std::tie(mo.width, mo.height) = parseResolution(a.resolution);
  // Muybridge's plate is in ../shared beside the data folder (the repository's, in a build tree) or
  // $STIRRUP_SHARED_DIR.
  const std::optional<fs::path> data = scene::findDataDir();
  const fs::path scenes = a.scenes.empty() ? scene::dataDir() / "scenes" : fs::path(a.scenes);
  mo.reference_dir = render::sharedDir(data ? *data : fs::weakly_canonical(scenes).parent_path()) / "reference";
  return mo;
}

namespace {

// A glTF shot's set, cut to --only: a name is the movie's (STEM_side) or its view's (side); a view of the
// scene set that a shot cannot make is refused by name, never skipped.
std::vector<render::MovieJob> selectShotMovies(const MovieSetArgs& a) {
  if (!scene::isGltfFile(a.shot)) throw rig::InputError(a.shot + ": expected a glTF shot (.glb or .gltf); the scene set is made without one");
  if (!a.scenes.empty()) throw rig::InputError("--scenes: chooses the scene set's scenes, not a glTF shot's (" + a.shot + ")");
  std::vector<render::MovieJob> jobs = render::shotMovieSet(a.shot, a.look);
  if (a.only.empty()) return jobs;
  const std::string prefix = fs::path(a.shot).stem().string() + "_";
  std::vector<std::string> wanted;
  for (const std::string& n : a.only) {
    const std::string name = n.rfind(prefix, 0) == 0 ? n : prefix + n;
    const std::string view = name.substr(prefix.size());
    // The shot's own views refuse the scene set's views they cannot make; a look's cameras are its own.
    if (const std::string why = render::shotViewRefusal(view); !why.empty() && a.look.empty())
      throw rig::InputError("--only: " + n + ": " + why + " (" + a.shot + ")");
    if (std::none_of(jobs.begin(), jobs.end(), [&](const render::MovieJob& j) { return j.name == name; })) {
      std::string names, views;
      for (const auto& j : jobs) names += (names.empty() ? "" : ", ") + j.name, views += (views.empty() ? "" : ", ") + j.camera;
      throw rig::InputError("--only: no movie named \"" + n + "\" for the glTF shot " + a.shot + " (expected one of " + names +
                       ", or a " + (a.look.empty() ? "view" : "camera of " + a.look) + ": " + views + ")");
    }
    wanted.push_back(name);
  }
  std::erase_if(jobs, [&](const render::MovieJob& j) { return std::find(wanted.begin(), wanted.end(), j.name) == wanted.end(); });
  return jobs;
}

}  // namespace

std::vector<render::MovieJob> selectMovies(const MovieSetArgs& a, const render::MovieOptions& mo) {
  if (!a.shot.empty()) return selectShotMovies(a);
  if (!a.look.empty()) throw rig::InputError("--scene: the look of a glTF shot's movies (stirrup movies SHOT.glb --scene LOOK.json); the scene set has its own");
  const fs::path scenes = a.scenes.empty() ? scene::dataDir() / "scenes" : fs::path(a.scenes);
  if (!fs::is_directory(scenes)) throw rig::InputError("--scenes: " + scenes.string() + ": no such folder");
  std::vector<render::MovieJob> jobs = render::defaultMovieSet(scenes, mo.reference_dir);
  if (a.only.empty()) return jobs;
  std::set<std::string> known;
  for (const auto& j : jobs) known.insert(j.name);
  for (const std::string& n : a.only)
    if (!known.count(n)) {
      std::string names;
      for (const auto& k : known) names += (names.empty() ? "" : ", ") + k;
      throw rig::InputError("--only: no movie named \"" + n + "\" (expected one of " + names + ")");
    }
  std::erase_if(jobs, [&](const render::MovieJob& j) { return std::find(a.only.begin(), a.only.end(), j.name) == a.only.end(); });
  return jobs;
}

std::vector<std::string> movieSetArguments(const MovieSetArgs& a) {
  std::vector<std::string> args;
  if (!a.shot.empty()) args.push_back(fs::absolute(a.shot).string());
  if (!a.look.empty()) args.insert(args.end(), {"--scene", fs::absolute(scene::findSceneFile(a.look)).string()});
  args.insert(args.end(), {"--preset", a.preset});
  if (a.frames_limit > 0) args.insert(args.end(), {"--frames-limit", std::to_string(a.frames_limit)});
  if (!a.resolution.empty()) args.insert(args.end(), {"--resolution", a.resolution});
  if (!a.scenes.empty()) args.insert(args.end(), {"--scenes", fs::absolute(a.scenes).string()});
  if (!a.mov.empty()) args.insert(args.end(), {"--mov", a.mov});
  if (a.no_mp4) args.push_back("--no-mp4");
  if (a.keep_frames) args.push_back("--keep-frames");
  if (a.allow_impossible) args.push_back("--allow-impossible");
  if (!a.date.empty()) args.insert(args.end(), {"--date", a.date});
  return args;
}

}  // namespace stirrup::cli
