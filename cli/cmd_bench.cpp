// stirrup bench: renders a fixed trot scene at 640 x 360 with each quality preset and reports where
// a frame's time goes (pose, skin, BVH, trace, write), the renderer's rays per second, and the bound:
// the same rays replayed through Embree alone, with no shading, on the same threads.
// With --scene (a crowd: issue 19) it renders that scene's frames instead, and reports the same split,
// what was skinned and refitted per frame and per pair, the pairs at each level of detail, the set-up
// time and the process's peak memory, against the built-in trot's frame at the same preset in the same
// run.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <chrono>
#include <sys/resource.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <tbb/info.h>

#include "cli/commands.h"
#include "render/shot.h"
#include "render/tracer/frame_writer.h"
#include "render/tracer/image.h"
#include "render/tracer/sample_lanes.h"
#include "render/tracer/stopwatch.h"
#include "rig/rig_profile.h"
#include "scene/frame_range.h"
#include "scene/preset.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace stirrup::cli {
namespace {

struct BenchOptions {
  bool json = false;
  int threads = 0;
  int frames = 12;
  std::string scene;      // a scene file: bench it instead of the built-in trot
  std::string camera;     // its camera (empty: the first)
  std::string preset;     // one preset (empty: every one)
  int detail = -1;        // levels of detail: -1 automatic, 0-2 every pair at that level
  int png_compression = -1;  // the frames' zlib level; -1: as `stirrup render` picks it for the preset
  bool no_overlap = false;   // evaluate each frame before its trace instead of during the one before
  bool allow_impossible = false;  // --scene beyond a horse's limits is benched anyway
};

// The frame rendered after frames[i], for Shot::renderFrame to evaluate during frames[i]'s trace.
std::optional<int> nextOf(const BenchOptions& o, const std::vector<int>& frames, std::size_t i) {
  if (o.no_overlap || i + 1 >= frames.size()) return std::nullopt;
  return frames[i + 1];
}

// The render threads: the option's, or every core.
int threadCount(const BenchOptions& o) { return o.threads > 0 ? o.threads : tbb::info::default_concurrency(); }

// The zlib level a benched frame is written at: the option's, or what `stirrup render` would use.
int pngLevel(const BenchOptions& o, const scene::SceneSpec& scene) {
  return o.png_compression >= 0 ? o.png_compression : scene::defaultPngCompression(scene);
}

// The benchmark scene: scenes/trot.json's content, built in so the numbers never depend on a file
// someone edited. The quality is set per preset.
scene::SceneSpec benchScene() {
  const nlohmann::json trot = nlohmann::json::parse(R"({
    "name": "trot",
    "clip": {"generator": "trot", "speed_cm_s": 360, "stride_hz": 1.26, "hoof_lift_cm": 14},
    "fps": 24,
    "frames": "1-72",
    "resolution": [640, 360],
    "sun": {"direction": [0.45, 0.75, 0.5], "angular_radius": 2.0},
    "cameras": [
      {"name": "side", "type": "orthographic", "ortho_height": 320,
       "position": [20, 255, 900], "target": [20, 100, 0], "follow": true}
    ]
  })");
  return scene::parseScene(trot, "bench");
}

struct PresetResult {
  std::string name;
  int samples = 0;
  double pose = 0, skin = 0, bvh = 0, trace = 0, write = 0;  // ms per frame
  double wait = 0;  // ms per frame waiting after the trace for the next frame's evaluation
  double rays_per_frame = 0;
  double rays_per_second = 0, bound_rays_per_second = 0;
  double fps = 0;
  double page_faults = 0;  // per timed frame
  int png_level = 0;  // the zlib level the frames were written at
};

using Clock = std::chrono::steady_clock;

// Keep at most this many rays for the replay (48 bytes each); above it every Nth pixel's rays are
// kept, which samples the frame evenly. The bound is a rate, so a sample of the rays measures it.
constexpr double kMaxLoggedRays = 8e6;

// Writes the frame as a PNG on the writer's thread, as `stirrup render` does, adding the write's own
// time to write_ms (touched only by the writer thread; read after its last wait()).
void writeInBackground(render::FrameWriter& writer, render::Image&& image, const std::filesystem::path& file,
                       int png_level, double& write_ms) {
  writer.submit([image = std::move(image), file, png_level, &write_ms] {
    const auto w0 = Clock::now();
    render::writePng(image, file, png_level);
    write_ms += render::secondsSince(w0) * 1000.0;
  });
}

// The timed frames, as `stirrup render` makes them: each frame rendered (evaluating the next during its
// trace unless --no-overlap) and its PNG written on the background thread while the next frame renders
// (render/tracer/frame_writer.h), two scratch files in turn. `add` is given each timed frame's timings.
struct TimedRun {
  double run_s = 0;        // wall clock of the timed frames, their writes included
  double write_ms = 0;     // the timed frames' writes' own time on their thread, summed
  double page_faults = 0;  // the process's minor page faults during the timed frames, every thread's
};

// The process's minor page faults so far (every thread's): memory touched for the first time.
double minorPageFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_minflt);
}

// Before the clock starts, the first frames go through the same loop (overlapped, written, the writer
// still busy with the last of them when the first timed frame starts), until the memory a frame uses is
// memory the run already has. A frame's image (3.7 MB at 640x360) is above malloc's threshold for
// mapping a block on its own: the first two images are mapped and, freed, given back, which raises the
// threshold; the next two come from the heap, which grows; from the fifth frame on, the two images in
// flight (one rendering, one being written) reuse the heap's pages. Each of the first four frames
// faults in some 900 to 4 000 pages; timed, they added a run's start to a steady frame rate, about a
// tenth of a 12-frame draft run (docs/performance-history.md, "The bench's warm-up").
constexpr std::size_t kWarmUpFrames = 4;

TimedRun timeFrames(render::Shot& shot, const std::vector<int>& frames, const BenchOptions& o, int png_level,
                    const std::filesystem::path& scratch, const std::function<void(const render::FrameTimings&)>& add) {
  // The warm-up's frames (the timed ones', round again if they are fewer), then them.
  const std::size_t warm = frames.empty() ? 0 : kWarmUpFrames;
  std::vector<int> run_frames(warm + frames.size());
  for (std::size_t k = 0; k < run_frames.size(); ++k) run_frames[k] = k < warm ? frames[k % frames.size()] : frames[k - warm];
  TimedRun run;
  double warm_write_ms = 0, write_ms = 0;  // touched only by the writer thread, read after its last wait()
  render::FrameWriter writer;
  double faults0 = 0;
  auto run0 = Clock::now();
  for (std::size_t i = 0; i < run_frames.size(); ++i) {
    const bool timed = i >= warm;
    if (i == warm) faults0 = minorPageFaults(), run0 = Clock::now();
    render::Image image = shot.renderFrame(run_frames[i], nextOf(o, run_frames, i));
    const render::FrameTimings& t = shot.lastTimings();
    writeInBackground(writer, std::move(image), scratch / ("bench." + std::to_string(i % 2) + ".png"), png_level,
                      timed ? write_ms : warm_write_ms);
    if (timed) add(t);
  }
  writer.wait();
  run.run_s = render::secondsSince(run0);
  run.page_faults = minorPageFaults() - faults0;
  run.write_ms = write_ms;
  return run;
}

// Runs `bench` with a scratch folder for its frames, removed afterwards whatever happens.
template <typename Bench>
auto withScratch(Bench bench) {
  namespace fs = std::filesystem;
  const fs::path scratch = fs::temp_directory_path() / ("stirrup-bench-" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  try {
    auto results = bench(scratch);
    fs::remove_all(scratch);
    return results;
  } catch (...) {
    fs::remove_all(scratch);
    throw;
  }
}

PresetResult benchPreset(const scene::QualityPreset& preset, const BenchOptions& o,
                         const std::filesystem::path& scratch) {
  scene::SceneSpec scene = benchScene();
  scene::applyPreset(scene, preset);
  render::Shot shot(scene, rig::RigProfile::thesis(), scene.cameras.front(), o.threads);
  shot.setPasses(false);  // PNG frames, as `stirrup render` writes them
  PresetResult r;
  r.name = std::string(preset.name);
  r.samples = preset.samples;
  r.png_level = pngLevel(o, scene);

  // The rays of one frame: render frame 1 once to count them, again keeping them (sampled when there
  // are many), then replay them while the BVH is that frame's.
  shot.renderFrame(1);
  render::RayLog log;
  log.pixel_stride = std::max(1, int(std::ceil(double(shot.lastTimings().rays) / kMaxLoggedRays)));
  shot.renderFrame(1, &log);
  double replay_s = shot.renderer().replay(log);
  replay_s = std::min(replay_s, shot.renderer().replay(log));  // the faster of two: less noise
  r.bound_rays_per_second = replay_s > 0.0 ? double(log.rays) / replay_s : 0.0;

  // Frames as `stirrup render` makes them: each PNG written on the background thread while the next
  // frame renders (render/tracer/frame_writer.h). fps is frames over the wall-clock time of the whole run,
  // writes included; the write column is a write's own time on its thread.
  double rays = 0;
  double frame_ms = 0;  // renderFrame's own wall-clock time, summed
  std::vector<int> frames;
  for (int i = 0; i < o.frames; ++i) frames.push_back(1 + i % 72);
  const TimedRun run = timeFrames(shot, frames, o, r.png_level, scratch, [&](const render::FrameTimings& t) {
    r.pose += t.pose_ms;
    r.skin += t.skin_ms;
    r.bvh += t.bvh_ms;
    r.trace += t.trace_ms - t.bvh_ms - t.wait_ms;
    r.wait += t.wait_ms;
    frame_ms += t.frame_ms;
    rays += double(t.rays);
  });
  const double run_s = run.run_s;
  r.write = run.write_ms;
  const double n = double(o.frames);
  r.pose /= n, r.skin /= n, r.bvh /= n, r.trace /= n, r.write /= n, r.wait /= n;
  r.rays_per_frame = rays / n;
  // The frame's time without the write: renderFrame's wall clock (with frames overlapped, the pose and
  // skin that ran during the previous trace are not in it; the trace they slowed and any wait are).
  const double compute_s = frame_ms / n / 1000.0;
  r.rays_per_second = compute_s > 0.0 ? r.rays_per_frame / compute_s : 0.0;
  r.fps = run_s > 0.0 ? n / run_s : 0.0;
  r.page_faults = run.page_faults / n;
  return r;
}

// The process's peak resident memory so far (bytes): Linux reports ru_maxrss in kilobytes.
double peakMemoryBytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) * 1024.0;
}

struct SceneResult {
  std::string preset;
  double setup_s = 0, peak_bytes = 0;
  render::SetupTimings setup;  // the set-up's parts (ms)
  double bake = 0, skin = 0, bvh = 0, trace = 0, write = 0;  // ms per frame; skin without build
  double wait = 0;      // ms per frame waiting after the trace for the next frame's evaluation
  double build = 0;     // ms per frame building levels of detail first needed (a one-time cost)
  double fps = 0;
  double page_faults = 0;  // per timed frame
  double pairs = 0, skinned_vertices = 0, triangles = 0;     // per frame
  std::array<double, 3> pairs_at_level{};                   // per frame
  // The frame (pose to trace) against others measured frame for frame with the scene's, interleaved
  // so that a busy machine slows them alike: the scene's own, the built-in trot's at this preset, and
  // over a terrain the same shot on flat ground (0: the scene has no terrain).
  double scene_ms = 0, trot_ms = 0, flat_ms = 0;
  int png_level = 0;    // the zlib level the frames were written at
};

// A frame's pose-to-trace time (ms), as the split above sums it.
double frameTotalMs(const render::FrameTimings& t) { return t.pose_ms + t.skin_ms - t.build_ms + t.trace_ms; }

SceneResult benchScenePreset(const scene::QualityPreset& preset, const BenchOptions& o,
                             const std::filesystem::path& scratch) {
  scene::SceneSpec scene = scene::loadScene(o.scene, {o.allow_impossible});
  scene::applyPreset(scene, preset);
  SceneResult r;
  r.preset = std::string(preset.name);
  r.png_level = pngLevel(o, scene);
  const auto setup0 = Clock::now();
  render::Shot shot(scene, scene::resolveProfile(scene), scene::findCamera(scene, o.camera), o.threads);
  shot.setDetailLevel(o.detail);
  shot.setPasses(false);  // PNG frames, as `stirrup render` writes them
  r.setup_s = render::secondsSince(setup0);
  r.setup = shot.setupTimings();
  // o.frames of the scene's frames, spread evenly over them.
  const std::vector<int> all = scene::parseFrameList(scene.frames, "frames");
  std::vector<int> frames;
  for (int i = 0; i < o.frames; ++i) frames.push_back(all[std::size_t(i) * all.size() / std::size_t(o.frames)]);
  const TimedRun run = timeFrames(shot, frames, o, r.png_level, scratch, [&](const render::FrameTimings& t) {
    r.bake += t.pose_ms, r.skin += t.skin_ms - t.build_ms, r.build += t.build_ms, r.bvh += t.bvh_ms,
        r.trace += t.trace_ms - t.bvh_ms - t.wait_ms;
    r.wait += t.wait_ms;
    r.skinned_vertices += double(t.skinned_vertices);
    r.triangles += double(t.triangles);
    for (int k = 0; k < 3; ++k) r.pairs_at_level[std::size_t(k)] += t.pairs_at_level[std::size_t(k)];
  });
  const double n = double(frames.size());
  r.fps = n / run.run_s;
  r.page_faults = run.page_faults / n;
  r.write = run.write_ms / n;
  r.wait /= n;
  r.bake /= n, r.skin /= n, r.build /= n, r.bvh /= n, r.trace /= n, r.skinned_vertices /= n, r.triangles /= n;
  for (double& l : r.pairs_at_level) l /= n;
  r.pairs = std::max(1, shot.pairCount());
  r.peak_bytes = peakMemoryBytes();  // the scene's: the shots below come after

  // The ratios: the same frames again, each followed by a frame of the built-in trot and, over a
  // terrain, by the same frame of the shot with its ground made flat (its clip, cameras and characters
  // made again on the plane), so the ratio is what the terrain costs.
  scene::SceneSpec trot_scene = benchScene();
  scene::applyPreset(trot_scene, preset);
  render::Shot trot(trot_scene, rig::RigProfile::thesis(), trot_scene.cameras.front(), o.threads);
  trot.setPasses(false);
  trot.renderFrame(1);
  std::unique_ptr<render::Shot> flat;
  if (scene.terrain && !scene.terrain->flat()) {
    scene::SceneSpec flat_scene = scene;
    flat_scene.terrain.reset();
    flat = std::make_unique<render::Shot>(flat_scene, scene::resolveProfile(flat_scene),
                                          scene::findCamera(flat_scene, o.camera), o.threads);
    flat->setDetailLevel(o.detail);
    flat->setPasses(false);
    flat->renderFrame(frames.front());
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    shot.renderFrame(frames[i]);
    r.scene_ms += frameTotalMs(shot.lastTimings());
    trot.renderFrame(1 + int(i % 72));
    r.trot_ms += frameTotalMs(trot.lastTimings());
    if (flat) {
      flat->renderFrame(frames[i]);
      r.flat_ms += frameTotalMs(flat->lastTimings());
    }
  }
  r.scene_ms /= n, r.trot_ms /= n, r.flat_ms /= n;
  return r;
}

void runSceneBench(const BenchOptions& o) {
  const std::vector<SceneResult> results = withScratch([&](const std::filesystem::path& scratch) {
    std::vector<SceneResult> out;
    // The scene first, so the peak memory is the scene's (the trot's is far smaller).
    for (const scene::QualityPreset& p : scene::qualityPresets())
      if (o.preset.empty() || o.preset == p.name) out.push_back(benchScenePreset(p, o, scratch));
    return out;
  });
  const int threads = threadCount(o);
  if (o.json) {
    nlohmann::json presets = nlohmann::json::object();
    for (const SceneResult& r : results) {
      presets[r.preset] = {
          {"fps", r.fps}, {"page_faults_per_frame", r.page_faults}, {"setup_s", r.setup_s},
          {"peak_memory_bytes", r.peak_bytes},
          {"setup_ms", {{"characters", r.setup.characters_ms}, {"terrain", r.setup.terrain_ms},
                        {"framing", r.setup.framing_ms}}},
          {"ms", {{"bake", r.bake}, {"skin", r.skin}, {"bvh", r.bvh}, {"trace", r.trace}, {"write", r.write},
                  {"build", r.build}, {"wait", r.wait}}},
          {"pairs", r.pairs}, {"skinned_vertices", r.skinned_vertices}, {"refit_triangles", r.triangles},
          {"pairs_at_level", r.pairs_at_level}, {"trot_ms", r.trot_ms}, {"times_trot", r.scene_ms / r.trot_ms},
          {"flat_ms", r.flat_ms > 0 ? nlohmann::json(r.flat_ms) : nlohmann::json(nullptr)},
          {"times_flat", r.flat_ms > 0 ? nlohmann::json(r.scene_ms / r.flat_ms) : nlohmann::json(nullptr)},
          {"png_level", r.png_level}};
    }
    const nlohmann::json out = {{"scene", o.scene}, {"presets", presets}, {"threads", threads},
                                {"detail", o.detail}, {"simd", render::simdTargetName()}, {"overlap", !o.no_overlap}};
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf("stirrup bench: %s, %d thread%s, %d frame%s a preset, levels of detail %s, frames %s (ms per frame)\n\n",
              o.scene.c_str(), threads, threads == 1 ? "" : "s", o.frames, o.frames == 1 ? "" : "s",
              o.detail < 0 ? "by size on screen" : ("all at level " + std::to_string(o.detail)).c_str(),
              o.no_overlap ? "one after another" : "overlapped");
  std::printf("%-7s %7s %6s %6s %6s %8s %6s %6s %3s %6s %8s %8s %7s %8s %9s %9s %7s %8s\n", "preset", "fps", "bake",
              "skin", "bvh", "trace", "wait", "write", "png", "build", "x trot", "x flat", "setup", "peak MB", "skin kv/f",
              "refit kt/f", "kt/pair", "levels");
  for (const SceneResult& r : results) {
    char levels[48];
    std::snprintf(levels, sizeof levels, "%.0f/%.0f/%.0f", r.pairs_at_level[0], r.pairs_at_level[1], r.pairs_at_level[2]);
    char flat[16] = "       -";
    if (r.flat_ms > 0) std::snprintf(flat, sizeof flat, "%7.2fx", r.scene_ms / r.flat_ms);
    std::printf("%-7s %7.2f %6.1f %6.1f %6.1f %8.1f %6.1f %6.1f %3d %6.1f %7.2fx %8s %6.1fs %8.0f %9.0f %9.0f %7.1f %8s\n",
                r.preset.c_str(), r.fps, r.bake, r.skin, r.bvh, r.trace, r.wait, r.write, r.png_level, r.build,
                r.scene_ms / r.trot_ms, flat,
                r.setup_s, r.peak_bytes / 1e6,
                r.skinned_vertices / 1e3, r.triangles / 1e3, r.triangles / 1e3 / r.pairs, levels);
  }
  std::printf("\n%-7s %7s %11s %8s %8s\n", "set-up", "total", "characters", "terrain", "framing");
  for (const SceneResult& r : results)
    std::printf("%-7s %6.2fs %10.2fs %7.2fs %7.2fs\n", r.preset.c_str(), r.setup_s, r.setup.characters_ms / 1e3,
                r.setup.terrain_ms / 1e3, r.setup.framing_ms / 1e3);
  std::printf("\nbake: every pair's channels; skin: posing and skinning every pair at its level; bvh: the refit;\n"
              "build: building levels of detail the frame was the first to need (once per pair and level, like\n"
              "the set-up: in fps, which is wall clock, not in x trot); x trot: the frame (bake, skin, bvh,\n"
              "trace) over the built-in trot's at the same preset, measured frame for frame in turn with it;\n"
              "x flat: over the same frame of the shot on flat ground (a scene with a terrain), likewise;\n"
              "skin kv/f, refit kt/f: thousands of vertices skinned and triangles refitted a frame (kt/pair: per\n"
              "pair); levels: pairs at full, half and quarter detail a frame (scene/detail_level.h);\n"
              "overlapped: each frame's bake, pose and skin run while the frame before it traces; wait: after a\n"
              "trace, waiting for the next frame's evaluation; png: the zlib level the frames were written at;\n"
              "fps: the timed frames over their wall clock, writes included, after four untimed frames that\n"
              "touch the memory a run reuses; peak MB: the process's peak resident memory; set-up: making the\n"
              "shot, of which reading, seating and building the characters and their clips, meshing the terrain\n"
              "(normals, sun horizon), and framing the view camera over every frame it shows (the terrain is\n"
              "built alongside the framing).\n");
}

void runBench(const BenchOptions& o) {
  if (!o.scene.empty()) return runSceneBench(o);
  const std::vector<PresetResult> results = withScratch([&](const std::filesystem::path& scratch) {
    std::vector<PresetResult> out;
    for (const scene::QualityPreset& p : scene::qualityPresets()) out.push_back(benchPreset(p, o, scratch));
    return out;
  });
  const int threads = threadCount(o);

  if (o.json) {
    nlohmann::json presets = nlohmann::json::object();
    for (const PresetResult& r : results) {
      presets[r.name] = {{"fps", r.fps},
                         {"page_faults_per_frame", r.page_faults},
                         {"rays_per_second", r.rays_per_second},
                         {"bound_rays_per_second", r.bound_rays_per_second},
                         {"png_level", r.png_level},
                         {"ms", {{"pose", r.pose}, {"skin", r.skin}, {"bvh", r.bvh}, {"trace", r.trace}, {"write", r.write},
                                 {"wait", r.wait}}}};
    }
    const nlohmann::json out = {{"presets", presets}, {"threads", threads}, {"resolution", {640, 360}},
                                {"simd", render::simdTargetName()}, {"overlap", !o.no_overlap}};
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf("stirrup bench: trot side view, 640x360, %d thread%s, %d frame%s a preset, SIMD %s, frames %s (ms per frame)\n\n",
              threads, threads == 1 ? "" : "s", o.frames, o.frames == 1 ? "" : "s", render::simdTargetName().c_str(),
              o.no_overlap ? "one after another" : "overlapped");
  std::printf("%-7s %4s %7s %6s %6s %6s %8s %6s %6s %3s %9s %9s %10s %6s\n", "preset", "spp", "fps", "pose", "skin",
              "bvh", "trace", "wait", "write", "png", "Mrays/f", "Mrays/s", "bound Mr/s", "ratio");
  for (const PresetResult& r : results) {
    std::printf("%-7s %4d %7.2f %6.1f %6.1f %6.1f %8.1f %6.1f %6.1f %3d %9.2f %9.2f %10.2f %5.0f%%\n", r.name.c_str(),
                r.samples, r.fps, r.pose, r.skin, r.bvh, r.trace, r.wait, r.write, r.png_level, r.rays_per_frame / 1e6,
                r.rays_per_second / 1e6, r.bound_rays_per_second / 1e6,
                r.bound_rays_per_second > 0 ? 100.0 * r.rays_per_second / r.bound_rays_per_second : 0.0);
  }
  std::printf("\nratio: the renderer's rays per second (frame time without write) over the bound, the same\n"
              "rays cast through Embree alone with no shading; overlapped: each frame's pose and skin run while\n"
              "the frame before it traces; wait: after a trace, waiting for the next frame's evaluation;\n"
              "png: the zlib level the frames were written at; fps: the timed frames over their wall clock,\n"
              "writes included, after four untimed frames that touch the memory a run reuses.\n");
}

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto opts = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Measure the renderer per quality preset against Embree alone");
  cmd->footer(
      "Renders a built-in trot side view at 640x360 with each preset (draft, review, final) and prints\n"
      "milliseconds per frame (pose, skin, bvh, trace, write), rays per second, and the bound: the same\n"
      "rays replayed through Embree alone. Example: stirrup bench --json --threads 2\n"
      "With --scene, renders --frames of that scene's frames (spread over them) with its camera and\n"
      "prints the same split, the pairs' skinning and refit counts, levels of detail, set-up time and\n"
      "peak memory, and the frame against the trot's and, over a terrain, against the same shot on flat ground.\n"
      "Example: stirrup bench --scene scenes/cavalry.json -p review");
  cmd->add_flag("--json", opts->json, "Print one JSON object instead of the table");
  cmd->add_option("--threads,-t", opts->threads, "Render threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--frames,-n", opts->frames, "Timed frames per preset")->check(CLI::Range(1, 1000));
  cmd->add_option("--scene", opts->scene, "Bench this scene (e.g. scenes/cavalry.json) instead of the built-in trot");
  cmd->add_option("--camera,-c", opts->camera, "With --scene: its camera (default: the first)");
  cmd->add_option("--preset,-p", opts->preset, "With --scene: only this preset (draft, review, final)")
      ->check(CLI::IsMember({"draft", "review", "final"}));
  cmd->add_option("--png-compression", opts->png_compression,
                  "zlib level of the written frames, 0-9 (default: as stirrup render picks it, 0 for draft, else 1)")
      ->check(CLI::Range(scene::kPngCompressionMin, scene::kPngCompressionMax));
  cmd->add_flag("--no-overlap", opts->no_overlap,
                "Evaluate each frame before its trace, as before frames were overlapped (for comparison)");
  cmd->add_option("--detail", opts->detail, "With --scene: -1 picks each pair's level of detail by its size on "
                  "screen (default), 0-2 draws every pair at that level")->check(CLI::Range(-1, 2));
  cmd->add_flag("--allow-impossible", opts->allow_impossible,
                "With --scene: bench a scene beyond a horse's limits (docs/horse-limits.md) anyway");
  cmd->callback([opts] { runBench(*opts); });
}

}  // namespace stirrup::cli
