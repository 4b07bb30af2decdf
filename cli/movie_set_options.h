// The movie set's options, shared by `stirrup movies` and `stirrup farm submit --movies`, so a farm
// renders exactly the set `stirrup movies` would, and can hand the same options to its tasks.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "render/review/movie_set.h"

namespace stirrup::cli {

struct MovieSetArgs {
  std::string out = "out/movies";
  std::string preset = "review";
  std::vector<std::string> only;
  int frames_limit = 0;
  std::string resolution;
  std::string scenes;
  std::string shot;  // a glTF shot: its views' movies instead of the scene set (render::shotMovieSet)
  std::string look;  // --scene: the glTF shot's look, a scene whose cameras, size, quality, sun and ground it renders with
  std::string mov;  // "", "prores" or "h264"
  bool no_mp4 = false;
  bool keep_frames = false;
  int threads = 0;
  std::string date;
  bool allow_impossible = false;
};

// Adds the options that choose and shape the set (not --out or --threads, which each command words its
// own way).
void addMovieSetOptions(CLI::App* cmd, MovieSetArgs& args);

// The library's options, checked (InputError naming the option).
render::MovieOptions movieOptions(const MovieSetArgs& args);
// The set for these options (the scene set, or the glTF shot's views), cut to --only (InputError for an
// unknown name, and for a view a glTF shot cannot make, naming it).
std::vector<render::MovieJob> selectMovies(const MovieSetArgs& args, const render::MovieOptions& options);
// The same choices as `stirrup movies` arguments (without --out, --only and --threads; the shot first), for a
// farm task.
std::vector<std::string> movieSetArguments(const MovieSetArgs& args);

}  // namespace stirrup::cli
