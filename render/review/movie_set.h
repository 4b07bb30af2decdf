// Review movies of scenes (or of a glTF shot, scene/file_shot.h): each movie renders a scene through one of its cameras (a view), burns in
// the facts on every frame, puts a one-second slate first, encodes .mp4 (H.264) and/or .mov (ProRes
// 422 HQ or H.264), and writes a contact sheet; each movement also gets a channel plot. The default
// set (`stirrup movies`) is the thesis's Appendix A movies plus buck, canter, gallop and turntables.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "render/review/movie.h"

namespace stirrup::render {

struct MovieJob {
  std::string name;             // e.g. "trot_side": files NAME.mp4, NAME_sheet.png
  std::filesystem::path scene;  // scene file, or a glTF shot (.glb/.gltf) rendered as the file keys it
  std::string camera;           // the scene's camera (a view)
  std::string frames;           // empty: the scene's frames
  // Layered: "" (a plain movie), "rigid" (the rigged rider beside the rider rigidly fixed to the
  // saddle) or "reference" (the scene's reference footage, or Muybridge's gallop plate).
  std::string layered;
  // A glTF shot's look: the scene whose cameras, image size, quality, sun, haze and ground it renders
  // with (scene/file_shot.h loadFileShot); empty: the shot's own named views.
  std::filesystem::path look;
};

// ../shared beside the repository: $STIRRUP_SHARED_DIR when set, else DATA_DIR/../shared (in a build
// tree the data folder is the source tree, scene/data_dir.h; an installed stirrup needs the variable).
std::filesystem::path sharedDir(const std::filesystem::path& source_dir);

// The default set for the scenes in `scenes_dir`; gallop_layered only when `reference_dir` (the shared
// reference folder) holds Muybridge's plate.
std::vector<MovieJob> defaultMovieSet(const std::filesystem::path& scenes_dir,
                                      const std::filesystem::path& reference_dir);

// The set for a glTF shot (a `stirrup bake`, or Blender's export of one): STEM_side, STEM_persp,
// STEM_close, STEM_turntable and STEM_top (STEM the file's stem), each over the shot's frames, rendered
// as `stirrup render SHOT.glb` renders them (scene/file_shot.h); with a `look` scene, one movie a camera
// of it instead (STEM_CAMERA), as `stirrup render SHOT.glb --scene LOOK.json` renders them. Reads the
// files: one that is not a shot, or a look that is no scene, is a one-line InputError naming it.
std::vector<MovieJob> shotMovieSet(const std::filesystem::path& shot_file, const std::filesystem::path& look = {});
// Why the scene set's view `view` (e.g. "layered") cannot be made from a glTF shot; empty for the views
// shotMovieSet makes, and for names that are no view of the set at all.
std::string shotViewRefusal(const std::string& view);

struct MovieOptions {
  std::filesystem::path out = "out/movies";
  std::string preset = "review";  // scene/preset.h
  int width = 0, height = 0;      // 0: the scene's resolution
  int frames_limit = 0;           // > 0: only the first N frames of each movie (quick looks, tests)
  bool mp4 = true;                // NAME.mp4, H.264 yuv420p CRF 18
  bool mov = false;               // NAME.mov as well
  MovieCodec mov_codec = MovieCodec::ProRes;
  bool keep_frames = false;       // keep OUT/frames/NAME/NAME.####.png
  int threads = 0;
  std::string date;               // the slate's date; empty: today (UTC)
  std::filesystem::path reference_dir;  // Muybridge's plate for reference layering
  int contact_count = 12;
  bool allow_impossible = false;  // scenes beyond a horse's limits load, with a warning per frame
};

struct MovieResult {
  std::string name, scene, view, movement, profile;
  std::vector<std::filesystem::path> movies;  // encoded files
  std::filesystem::path contact_sheet;
  std::filesystem::path plot;                 // the movement's channel plot
  int frames = 0;                             // rendered frames (without the slate)
  int slate_frames = 0;
  double fps = 24.0;
  double seconds = 0.0;                       // wall time to render and encode
  double encode_cpu_s = 0.0;                  // renderMovie: the encoders' (ffmpeg's) CPU seconds
};

// The frames `job` renders with `options`, in playing order (the scene's or the job's frames, cut to
// frames_limit).
std::vector<int> movieFrameList(const MovieJob& job, const MovieOptions& options);
// Its length (for progress bars).
int movieFrameCount(const MovieJob& job, const MovieOptions& options);

// A movie is made in two stages, so a farm can split the first across many tasks and run the second
// once (render/farm/): `stirrup movies` runs both, one after the other, through the same functions.
//
// Stage 1 renders `frames` (any of movieFrameList; empty: all of them) into OUT/frames/NAME/: each frame
// with its burn-ins as NAME.####.png, and the contact sheet's frames also without burn-ins as
// NAME.####.sheet.exr (the exact linear pixels the sheet is made from). Every file is written to a
// temporary name and renamed, so a task killed mid-frame leaves no truncated frame. With `resume`, a
// frame whose files are all there is skipped. Returns the number of frames rendered. InputError for a
// frame that is not one of the movie's.
int renderMovieFrames(const MovieJob& job, const MovieOptions& options, const std::vector<int>& frames, bool resume,
                      const std::function<void()>& frame_done = {});
// The folder stage 1 writes into, OUT/frames/NAME.
std::filesystem::path movieFrameDir(const MovieJob& job, const MovieOptions& options);
// What stage 2 writes for the movie: NAME.mp4 and/or NAME.mov, and NAME_sheet.png.
std::vector<std::filesystem::path> movieOutputs(const MovieJob& job, const MovieOptions& options);
// The frames of `job` its contact sheet shows (every stage-1 run writes their EXRs too).
std::vector<int> movieSheetFrames(const MovieJob& job, const MovieOptions& options);
// The files stage 1 writes for `frame` (the PNG, and the EXR when the frame is on the contact sheet).
// Finding the sheet's frames reads the scene: a caller asking about many frames passes them, found once.
std::vector<std::filesystem::path> movieFrameFiles(const MovieJob& job, const MovieOptions& options, int frame);
std::vector<std::filesystem::path> movieFrameFiles(const MovieJob& job, const MovieOptions& options, int frame,
                                                   const std::vector<int>& sheet_frames);

// Stage 2, from stage 1's files: the slate, the encoded movies and the contact sheet; then the frames are
// removed unless keep_frames. InputError naming the first missing frame (nothing is encoded then).
MovieResult finishMovie(const MovieJob& job, const MovieOptions& options);

// One movie at once, its frames never on disk: each frame rendered and burnt in goes straight to the
// encoders (MovieEncoder, ffmpeg reading raw frames on a pipe) while the next one renders, and the
// contact sheet is made from the frames kept in memory. The movie's pixels are those stage 2 makes from
// stage 1's PNGs. With keep_frames the frames and the slate are also written as stage 1 writes them
// (NAME.####.png, NAME.slate.png). `frame_done` is called after each frame. Throws rig::InputError
// on bad input and std::runtime_error when encoding fails (no movie is left then).
MovieResult renderMovie(const MovieJob& job, const MovieOptions& options,
                        const std::function<void()>& frame_done = {});

// The movement's channel plot: OUT/SCENE_plot.png (the scene's frames). A glTF shot has none (its rider's
// channels are not evaluated: it is posed as the file keys it); movies of one are made without a plot. Returns the file. With
// allow_impossible a scene beyond a horse's limits is plotted too, as its movie was rendered.
std::filesystem::path writeMovementPlot(const std::filesystem::path& scene_file, const std::filesystem::path& out,
                                        bool allow_impossible = false);

}  // namespace stirrup::render
