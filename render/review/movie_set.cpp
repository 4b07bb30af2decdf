#include "render/review/movie_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "render/review/burn_in.h"
#include "render/review/channel_plot.h"
#include "render/review/contact_sheet.h"
#include "render/review/layer.h"
#include "render/shot.h"
#include "render/tracer/frame_writer.h"
#include "render/tracer/image.h"
#include "rig/error.h"
#include "rig/motion/crowd.h"
#include "rig/motion/shifted_clip.h"
#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "scene/file_shot.h"
#include "scene/frame_range.h"
#include "scene/frame_sequence.h"
#include "scene/preset.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "scene/shot_evaluator.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

// The scene's own reference block, when the scene format has one (scene/reference_spec.h ReferenceSpec).
template <typename S>
std::optional<scene::ReferenceSpec> sceneReference(const S& scene) {
  if constexpr (requires { scene.reference; }) {
    if constexpr (requires { scene.reference.has_value(); }) {
      if (scene.reference.has_value()) return scene::ReferenceSpec(*scene.reference);
    } else {
      return scene::ReferenceSpec(scene.reference);
    }
  }
  return std::nullopt;
}

// Muybridge's horse-and-rider plate (2872x1008, 6x2 cells), laid beside the render.
scene::ReferenceSpec muybridgePlate(const fs::path& reference_dir) {
  scene::ReferenceSpec r;
  r.file = reference_dir / "muybridge" / "horse-and-rider-gallop-plate.jpg";
  scene::PlateGrid grid;
  grid.rows = 2;
  grid.columns = 6;
  r.grid = grid;
  r.edge = scene::FootageEdge::Loop;
  r.mode = scene::LayerMode::SideBySide;
  r.label = "MUYBRIDGE 1887";
  return r;
}

// The scene a job renders: its scene file, or its glTF shot's (whose own frames and named views).
scene::SceneSpec jobScene(const MovieJob& job, const MovieOptions& o) {
  return scene::isGltfFile(job.scene) ? scene::loadFileShot(job.scene, 24.0, job.look).scene : scene::loadScene(job.scene, {o.allow_impossible});
}

std::vector<int> movieFrames(const MovieJob& job, const scene::SceneSpec& scene, const MovieOptions& o) {
  std::vector<int> frames = scene::parseFrameList(job.frames.empty() ? scene.frames : job.frames,
                                                job.scene.string() + ": frames");
  if (o.frames_limit > 0 && static_cast<int>(frames.size()) > o.frames_limit) frames.resize(std::size_t(o.frames_limit));
  return frames;
}

// What a movie renders: a scene, or a glTF shot's pairs as the file keys them and the scene the shot
// gives (scene/file_shot.h), at the movie's preset and size.
struct MovieInput {
  scene::SceneSpec scene;
  std::optional<scene::FileShot> file;
};

MovieInput loadForMovie(const MovieJob& job, const MovieOptions& o) {
  MovieInput in;
  if (scene::isGltfFile(job.scene)) {
    in.file = scene::loadFileShot(job.scene, 24.0, job.look);
    in.scene = in.file->scene;
  } else {
    in.scene = scene::loadScene(job.scene, {o.allow_impossible});
  }
  scene::applyPreset(in.scene, scene::findPreset(o.preset));
  if (o.width > 0) in.scene.width = o.width;
  if (o.height > 0) in.scene.height = o.height;
  if (in.file) in.file->scene = in.scene;
  return in;
}

// The views a glTF shot gives (scene/file_shot.cpp names them), in the set's order.
constexpr const char* kShotViews[] = {"side", "persp", "close", "turntable", "top"};

}  // namespace

fs::path sharedDir(const fs::path& source_dir) {
  if (const char* env = std::getenv("STIRRUP_SHARED_DIR"); env && *env) return env;
  return source_dir.parent_path() / "shared";
}

std::vector<MovieJob> defaultMovieSet(const fs::path& scenes_dir, const fs::path& reference_dir) {
  auto s = [&](const std::string& n) { return scenes_dir / (n + ".json"); };
  std::vector<MovieJob> set = {
      {"jump_side", s("jump"), "side", "", "", {}},     {"jump_persp", s("jump"), "persp", "", "", {}},
      {"rear_side", s("rear"), "side", "", "", {}},     {"rear_persp", s("rear"), "persp", "", "", {}},
      {"stop_side", s("stop"), "side", "", "", {}},     {"stop_persp", s("stop"), "persp", "", "", {}},
      {"stop_close", s("stop"), "close", "", "", {}},   {"stop_layered", s("stop"), "side", "", "rigid", {}},
      {"trot_side", s("trot"), "side", "", "", {}},     {"trot_persp", s("trot"), "persp", "", "", {}},
      {"trot_close", s("trot"), "close", "", "", {}},   {"trot_layered", s("trot"), "side", "", "rigid", {}},
      {"walk_side", s("walk"), "side", "", "", {}},     {"walk_persp", s("walk"), "persp", "", "", {}},
      {"walk_close", s("walk"), "close", "", "", {}},   {"walk_layered", s("walk"), "side", "", "rigid", {}},
      {"buck_side", s("buck"), "side", "", "", {}},     {"buck_persp", s("buck"), "persp", "", "", {}},
      {"canter_side", s("canter"), "side", "", "", {}}, {"gallop_side", s("gallop"), "side", "", "", {}},
      // The characters turning: horse and rider together (the rider rig rides the horse; neither is
      // shown alone), once holding a pose and once trotting in place.
      {"turntable_pose", s("trot"), "turntable_pose", "1-96", "", {}},
      {"turntable_trot", s("trot"), "turntable", "1-96", "", {}},
      // A horse on a path (issue 15): turns, gait changes, lead changes and hills.
      {"cross_country_persp", s("cross_country"), "persp", "", "", {}},
      {"figure_eight_persp", s("figure_eight"), "persp", "", "", {}},
      {"figure_eight_top", s("figure_eight"), "top", "", "", {}},
      {"trail_persp", s("trail"), "persp", "", "", {}},
      // Crowds (issue 19): a troop cantering into a gallop over rolling ground, seen whole and with
      // one rider followed; eight riders of mixed profiles walking and trotting a trail.
      {"cavalry_persp", s("cavalry"), "persp", "", "", {}},
      {"cavalry_follow", s("cavalry"), "follow", "", "", {}},
      {"ride_out_persp", s("ride_out"), "persp", "", "", {}},
      {"ride_out_close", s("ride_out"), "close", "", "", {}},
  };
  if (fs::is_regular_file(reference_dir / "muybridge" / "horse-and-rider-gallop-plate.jpg"))
    set.push_back({"gallop_layered", s("gallop"), "side", "", "reference", {}});
  return set;
}

std::vector<MovieJob> shotMovieSet(const fs::path& shot_file, const fs::path& look) {
  const scene::FileShot shot = scene::loadFileShot(shot_file, 24.0, look);  // a file that is not a shot is an error before any work
  const std::string stem = shot_file.stem().string();
  std::vector<MovieJob> set;
  if (look.empty()) {
    for (const char* view : kShotViews) set.push_back({stem + "_" + view, shot_file, view, "", "", {}});
  } else {
    for (const scene::CameraSpec& c : shot.scene.cameras) set.push_back({stem + "_" + c.name, shot_file, c.name, "", "", look});
  }
  return set;
}

std::string shotViewRefusal(const std::string& view) {
  if (view == "layered")
    return "the layered view cannot be made from a glTF shot: it lays the rider beside one fixed rigidly to the saddle, "
           "posed by the rider rig, and a shot's rider is posed as the file keys her";
  if (view == "follow")
    return "the follow view cannot be made from a glTF shot: it is a crowd scene's camera following one pair "
           "(the shot's views frame every pair)";
  if (view == "turntable_pose")
    return "the turntable_pose view cannot be made from a glTF shot: it is a scene's camera holding one pose "
           "(the shot's turntable turns over its frames)";
  return "";
}

std::vector<int> movieFrameList(const MovieJob& job, const MovieOptions& o) {
  return movieFrames(job, jobScene(job, o), o);
}

int movieFrameCount(const MovieJob& job, const MovieOptions& o) { return static_cast<int>(movieFrameList(job, o).size()); }

fs::path writeMovementPlot(const fs::path& scene_file, const fs::path& out, bool allow_impossible) {
  const scene::SceneSpec scene = scene::loadScene(scene_file, {allow_impossible});
  // A crowd's plot is one pair's: the one a camera follows (the first such), else the first pair, as
  // the shot's evaluator bakes it (its own clip at its start phase, its own profile).
  scene::ShotEvaluator characters(scene, scene::resolveProfile(scene), 0);
  int pair = 0;
  std::string title = scene.name, profile_name = scene.profile;
  if (characters.isCrowd()) {
    for (const scene::CameraSpec& c : scene.cameras)
      if (c.follow_pair >= 0) {
        pair = c.follow_pair;
        break;
      }
    title += " pair " + std::to_string(pair);
    profile_name = scene.pairs.at(std::size_t(pair)).profile;
  }
  std::vector<rig::BakedFrame> baked;
  scene::ShotFrame frame;
  for (int f : scene::parseFrameList(scene.frames, scene_file.string() + ": frames")) {
    scene::FrameRequest request;
    request.frame = f;
    request.until = scene::EvalStage::Bake;
    request.only_pair = pair;
    characters.evaluate(request, frame);
    baked.push_back(frame.pairs[std::size_t(pair)].baked);
  }
  const rig::Clip& clip = characters.clip(pair);
  const fs::path file = out / (scene.name + "_plot.png");
  ChannelPlot plot = movementPlot(title + " (" + clip.name() + ", profile " + profile_name + "): horse and rider channels", baked,
                                  characters.profile(pair).rider_unit_cm);
  if (const auto* path = dynamic_cast<const rig::PathClip*>(&clip))
    for (PlotPanel& p : pathPanels(*path, baked, characters.clipOffsetS(pair))) plot.panels.push_back(std::move(p));
  writeChannelPlot(plot, file);
  return file;
}

namespace {

fs::path frameDir(const MovieJob& job, const MovieOptions& o) { return o.out / "frames" / job.name; }
fs::path framePng(const MovieJob& job, const MovieOptions& o, int f) {
  return scene::FrameSequence::named(frameDir(job, o), job.name, ".png").path(f);
}
fs::path sheetExr(const MovieJob& job, const MovieOptions& o, int f) {
  return scene::FrameSequence::named(frameDir(job, o), job.name, ".sheet.exr").path(f);
}

std::string movieView(const MovieJob& job) { return job.layered.empty() ? job.camera : "layered (" + job.camera + ")"; }

// What the slate and the burn-ins say: a function of the job, the options and the movie's frames only,
// so every farm task burns in the same facts.
BurnInFacts movieFacts(const MovieJob& job, const MovieOptions& o, const MovieInput& in, const std::vector<int>& frames) {
  const scene::SceneSpec& scene = in.scene;
  BurnInFacts facts;
  facts.scene = scene.name;
  facts.view = movieView(job);
  if (in.file) {  // the motion is the file's: no clip or profile of stirrup's made it
    const std::string animation = in.file->shot->animationName();
    facts.movement = "as keyed" + (animation.empty() ? std::string() : " (" + animation + ")");
    facts.profile = "as keyed";
  } else {
    facts.movement = scene::makeClip(scene.clip)->name();  // the name only: no need to read the horse for its hooves
    facts.profile = scene.profile;
  }
  facts.fps = scene.fps;
  facts.frames = std::to_string(frames.front()) + "-" + std::to_string(frames.back());
  facts.frame_count = static_cast<int>(frames.size());
  const scene::QualityPreset& preset = scene::findPreset(o.preset);
  facts.quality = std::string(preset.name) + " (samples a pixel: " + std::to_string(preset.samples) + ")";
  facts.date = o.date.empty() ? todayUtc() : o.date;
  return facts;
}

bool onSheet(const std::vector<int>& sheet_frames, int f) {
  return std::find(sheet_frames.begin(), sheet_frames.end(), f) != sheet_frames.end();
}

}  // namespace

fs::path movieFrameDir(const MovieJob& job, const MovieOptions& o) { return frameDir(job, o); }

std::vector<fs::path> movieOutputs(const MovieJob& job, const MovieOptions& o) {
  std::vector<fs::path> files;
  if (o.mp4) files.push_back(o.out / (job.name + ".mp4"));
  if (o.mov) files.push_back(o.out / (job.name + ".mov"));
  files.push_back(o.out / (job.name + "_sheet.png"));
  return files;
}

std::vector<int> movieSheetFrames(const MovieJob& job, const MovieOptions& o) {
  return contactFrames(movieFrameList(job, o), o.contact_count);
}

std::vector<fs::path> movieFrameFiles(const MovieJob& job, const MovieOptions& o, int frame,
                                      const std::vector<int>& sheet_frames) {
  std::vector<fs::path> files = {framePng(job, o, frame)};
  if (onSheet(sheet_frames, frame)) files.push_back(sheetExr(job, o, frame));
  return files;
}

std::vector<fs::path> movieFrameFiles(const MovieJob& job, const MovieOptions& o, int frame) {
  return movieFrameFiles(job, o, frame, movieSheetFrames(job, o));
}

namespace {

// What a movie's frames are made of, set up once a movie whichever way it is made (stage 1's files, or
// renderMovie's frames in memory): the shot, the rigid rider's beside it or the reference footage, how
// they are laid side by side, and what the burn-ins say.
class MovieFrameMaker {
 public:
  MovieFrameMaker(const MovieJob& job, const MovieOptions& o, const MovieInput& in, const std::vector<int>& all);
  // Frame f composed (both panels, or the footage laid over), before its burn-ins; `next` is the
  // frame made after it, evaluated while f traces (Shot::renderFrame).
  Image compose(int f, std::optional<int> next);
  // The burn-ins (and the panels' labels) on a composed frame.
  void burnIn(Image& image, int f) const {
    render::burnIn(image, facts_, f);
    if (style_.mode == scene::LayerMode::SideBySide) labelPanels(image, panel_labels_);
  }
  const BurnInFacts& facts() const { return facts_; }

 private:
  static Shot makeShot(const MovieInput& in, const scene::CameraSpec& camera, const rig::RigProfile& profile, int threads) {
    // A glTF shot's pairs through the same evaluator and tracer as `stirrup render SHOT.glb`.
    return in.file ? Shot(std::make_shared<scene::ShotEvaluator>(*in.file, profile, threads), camera, threads)
                   : Shot(in.scene, profile, camera, threads);
  }

  const scene::SceneSpec& scene_;
  Shot shot_;
  std::unique_ptr<Shot> rigid_;
  std::optional<FootageSequence> footage_;
  LayerStyle style_;
  std::vector<std::string> panel_labels_;
  BurnInFacts facts_;
};

MovieFrameMaker::MovieFrameMaker(const MovieJob& job, const MovieOptions& o, const MovieInput& in,
                                 const std::vector<int>& all)
    : scene_(in.scene),
      shot_(makeShot(in, scene::findCamera(in.scene, job.camera), scene::resolveProfile(in.scene), o.threads)),
      facts_(movieFacts(job, o, in, all)) {
  // The colour alone, except under reference footage, which may be laid by our matte (LayerCoverage).
  shot_.setPasses(job.layered == "reference");
  if (job.layered == "rigid") {
    scene::CameraSpec same = shot_.camera();  // exactly the rigged shot's framed camera
    same.view.clear();
    rigid_ = std::make_unique<Shot>(shot_.sharedCharacters(), same, o.threads);  // the same characters, read once
    rigid_->setRigidRider(true);
    panel_labels_ = {"rigged rider (stirrup)", "rider fixed to the saddle"};
    style_.mode = scene::LayerMode::SideBySide;
    style_.labels = false;  // labelled below the burn-in band instead (labelPanels)
  } else if (job.layered == "reference") {
    const scene::ReferenceSpec ref = sceneReference(scene_).value_or(muybridgePlate(o.reference_dir));
    if (!referenceAvailable(ref)) throw rig::InputError(job.scene.string() + ": reference: " + ref.file.string() + ": not found");
    footage_ = openReference(ref, job.scene.string() + ": reference");
    style_ = referenceStyle(ref, "STIRRUP");
    if (style_.mode == scene::LayerMode::SideBySide) {
      panel_labels_ = {"stirrup", ref.label};
      style_.labels = false;
    }
  } else if (!job.layered.empty()) {
    throw rig::InputError(job.name + ": layered: expected \"rigid\" or \"reference\", got \"" + job.layered + "\"");
  }
}

Image MovieFrameMaker::compose(int f, std::optional<int> next) {
  // Each frame evaluated while the one before traces (Shot::renderFrame); the rigid panel's shot
  // shares the characters and takes its turn after, each joining its evaluation before it returns.
  scene::warnImpossibleFrame(scene_, f);
  Image image = shot_.renderFrame(f, next);
  if (rigid_) return layerFrame(image, rigid_->renderFrame(f, next), style_);
  if (footage_) {
    const std::optional<int> theirs = footage_->theirFrame(f);
    const Image other = style_.mode == scene::LayerMode::SideBySide && theirs ? footage_->source(*theirs)
                                                                       : footage_->frame(f, image.width, image.height);
    return layerFrame(image, other, style_);
  }
  return image;
}

// A movie's frames, checked: the job's frames (all of them, cut to frames_limit), or InputError.
std::vector<int> checkedFrames(const MovieJob& job, const MovieOptions& o, const MovieInput& in) {
  if (in.file && !job.layered.empty())
    throw rig::InputError(job.name + ": " + shotViewRefusal("layered") + " (" + job.scene.string() + ")");
  std::vector<int> all = movieFrames(job, in.scene, o);
  if (all.empty()) throw rig::InputError(job.scene.string() + ": frames: no frames to render");
  return all;
}

std::optional<int> nextFrame(const std::vector<int>& frames, std::size_t k) {
  return k + 1 < frames.size() ? std::optional<int>(frames[k + 1]) : std::nullopt;
}

}  // namespace

int renderMovieFrames(const MovieJob& job, const MovieOptions& o, const std::vector<int>& wanted, bool resume,
                      const std::function<void()>& frame_done) {
  const MovieInput in = loadForMovie(job, o);
  const std::vector<int> all = checkedFrames(job, o, in);
  for (int f : wanted)
    if (std::find(all.begin(), all.end(), f) == all.end())
      throw rig::InputError(job.name + ": frame " + std::to_string(f) + " is not one of the movie's frames (" +
                       std::to_string(all.front()) + "-" + std::to_string(all.back()) + ")");
  const std::vector<int> sheet_frames = contactFrames(all, o.contact_count);
  std::vector<int> frames;
  for (int f : wanted.empty() ? all : wanted) {
    bool done = resume && fs::is_regular_file(framePng(job, o, f));
    if (done && onSheet(sheet_frames, f)) done = fs::is_regular_file(sheetExr(job, o, f));
    if (!done) frames.push_back(f);
  }
  if (frames.empty()) return 0;

  MovieFrameMaker maker(job, o, in, all);
  fs::create_directories(frameDir(job, o));
  // Burn-ins and the writes of frame f happen on the writer's thread while f + 1 renders.
  FrameWriter writer;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const int f = frames[k];
    Image image = maker.compose(f, nextFrame(frames, k));
    const bool sheet = onSheet(sheet_frames, f);
    writer.submit([image = std::move(image), &maker, f, sheet, png = framePng(job, o, f),
                   exr = sheetExr(job, o, f)]() mutable {
      if (sheet) writeRgbaExr(image, exr);  // before the PNG: a PNG present means the frame is whole
      maker.burnIn(image, f);
      writePng(image, png);
    });
    if (frame_done) frame_done();
  }
  writer.wait();
  return static_cast<int>(frames.size());
}

namespace {

// What a movie is, as the index lists it, before anything is encoded.
MovieResult describeMovie(const MovieJob& job, const scene::SceneSpec& scene, const BurnInFacts& facts,
                          const std::vector<int>& frames) {
  MovieResult result;
  result.name = job.name;
  result.scene = scene.name;
  result.view = facts.view;
  result.movement = facts.movement;
  result.profile = facts.profile;
  result.fps = scene.fps;
  result.frames = static_cast<int>(frames.size());
  // The slate: one second before the first frame.
  result.slate_frames = std::max(1, static_cast<int>(std::lround(scene.fps)));
  return result;
}

// The movies a job makes (NAME.mp4, NAME.mov), each with its codec.
std::vector<std::pair<fs::path, MovieCodec>> movieFiles(const MovieJob& job, const MovieOptions& o) {
  std::vector<std::pair<fs::path, MovieCodec>> files;
  if (o.mp4) files.emplace_back(o.out / (job.name + ".mp4"), MovieCodec::H264);
  if (o.mov) files.emplace_back(o.out / (job.name + ".mov"), o.mov_codec);
  return files;
}

void writeSheet(const MovieJob& job, const MovieOptions& o, const scene::SceneSpec& scene, const std::vector<ContactFrame>& sheet,
                MovieResult& result) {
  result.contact_sheet = o.out / (job.name + "_sheet.png");
  writeContactSheet(job.name + "  (" + scene.name + ", " + result.view + ", profile " + result.profile + ")", sheet,
                    result.contact_sheet);
}

fs::path slatePng(const MovieJob& job, const MovieOptions& o) { return frameDir(job, o) / (job.name + ".slate.png"); }

}  // namespace

MovieResult finishMovie(const MovieJob& job, const MovieOptions& o) {
  const MovieInput in = loadForMovie(job, o);
  const scene::SceneSpec& scene = in.scene;
  const std::vector<int> frames = movieFrames(job, scene, o);
  if (frames.empty()) throw rig::InputError(job.scene.string() + ": frames: no frames to render");
  const std::vector<int> sheet_frames = contactFrames(frames, o.contact_count);
  std::vector<fs::path> files;
  for (int f : frames) {
    for (const fs::path& file : movieFrameFiles(job, o, f, sheet_frames))  // (the scene read once, above)
      if (!fs::is_regular_file(file))
        throw rig::InputError(job.name + ": frame " + std::to_string(f) + " is missing (" + file.string() + ")");
    files.push_back(framePng(job, o, f));
  }
  std::vector<ContactFrame> sheet;
  for (int f : sheet_frames) sheet.push_back({f, readRgbaExr(sheetExr(job, o, f))});

  const BurnInFacts facts = movieFacts(job, o, in, frames);
  MovieResult result = describeMovie(job, scene, facts, frames);
  // The slate at the frames' size.
  const fs::path slate_file = slatePng(job, o);
  writePng(makeSlate(sheet.front().image.width, sheet.front().image.height, facts), slate_file);
  std::vector<fs::path> playlist(static_cast<std::size_t>(result.slate_frames), slate_file);
  playlist.insert(playlist.end(), files.begin(), files.end());
  for (const auto& [movie, codec] : movieFiles(job, o)) {
    encodeMovie({playlist, scene.fps, movie, 18, codec});
    result.movies.push_back(movie);
  }
  writeSheet(job, o, scene, sheet, result);
  if (!o.keep_frames) {
    std::error_code ec;
    fs::remove_all(frameDir(job, o), ec);
    fs::remove(frameDir(job, o).parent_path(), ec);  // only when empty
  } else {
    for (int f : sheet_frames) fs::remove(sheetExr(job, o, f));  // kept frames are the PNGs
  }
  return result;
}

namespace {

// A movie's encoders fed from memory (MovieEncoder), started at its first frame, whose size they take:
// the slate first, then each frame. With keep_frames the same frames (and the slate) are also written
// as stage 1 writes them, for a look or a later --finish.
class MovieStreams {
 public:
  MovieStreams(const MovieJob& job, const MovieOptions& o, const BurnInFacts& facts, int slate_frames, double fps)
      : job_(job), o_(o), facts_(facts), slate_frames_(slate_frames), fps_(fps) {}

  // Frame f, burnt in.
  void add(const Image& image, int f) {
    if (!started_) start(image.width, image.height);
    bytes_.resize(image.pixelCount() * 3);
    encodeSrgb8(image.rgba, bytes_);
    for (auto& e : encoders_) e->addFrame(bytes_);
    if (o_.keep_frames) writePng(image, framePng(job_, o_, f));
  }
  // Waits for the encoders; returns the movies and the encoders' CPU seconds.
  double finish(std::vector<fs::path>& movies) {
    double cpu_s = 0.0;
    for (auto& e : encoders_) {
      e->finish();
      cpu_s += e->cpuSeconds();
    }
    for (const auto& file : movieFiles(job_, o_)) movies.push_back(file.first);
    return cpu_s;
  }

 private:
  void start(int width, int height) {
    started_ = true;
    const Image slate = makeSlate(width, height, facts_);
    if (o_.keep_frames) writePng(slate, slatePng(job_, o_));
    bytes_.resize(slate.pixelCount() * 3);
    encodeSrgb8(slate.rgba, bytes_);
    for (const auto& [movie, codec] : movieFiles(job_, o_)) {
      encoders_.push_back(std::make_unique<MovieEncoder>(MovieEncoder::Spec{movie, fps_, 18, codec}, width, height));
      for (int k = 0; k < slate_frames_; ++k) encoders_.back()->addFrame(bytes_);
    }
  }

  const MovieJob& job_;
  const MovieOptions& o_;
  const BurnInFacts& facts_;
  int slate_frames_;
  double fps_;
  std::vector<std::unique_ptr<MovieEncoder>> encoders_;
  std::vector<uint8_t> bytes_;  // the frame being sent, reused
  bool started_ = false;
};

}  // namespace

MovieResult renderMovie(const MovieJob& job, const MovieOptions& o, const std::function<void()>& frame_done) {
  const auto start = std::chrono::steady_clock::now();
  const MovieInput in = loadForMovie(job, o);
  const std::vector<int> frames = checkedFrames(job, o, in);
  const std::vector<int> sheet_frames = contactFrames(frames, o.contact_count);
  MovieFrameMaker maker(job, o, in, frames);
  MovieResult result = describeMovie(job, in.scene, maker.facts(), frames);
  if (o.keep_frames) fs::create_directories(frameDir(job, o));
  MovieStreams streams(job, o, maker.facts(), result.slate_frames, in.scene.fps);
  std::vector<ContactFrame> sheet;
  {
    // Burn-ins and the encoding of frame f happen on the writer's thread while f + 1 renders; the
    // encoders (ffmpeg's own threads) take what the tracer leaves of the cores.
    FrameWriter writer;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const int f = frames[k];
      Image image = maker.compose(f, nextFrame(frames, k));
      if (onSheet(sheet_frames, f)) {  // the sheet's frames without burn-ins, as stage 1 keeps them
        Image plain(image.width, image.height);
        plain.rgba = image.rgba;
        sheet.push_back({f, std::move(plain)});
      }
      writer.submit([image = std::move(image), &maker, &streams, f]() mutable {
        maker.burnIn(image, f);
        streams.add(image, f);
      });
      if (frame_done) frame_done();
    }
    writer.wait();
  }
  result.encode_cpu_s = streams.finish(result.movies);
  writeSheet(job, o, in.scene, sheet, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace stirrup::render
