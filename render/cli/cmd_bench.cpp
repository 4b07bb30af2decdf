// stirrup bench: renders a fixed trot scene at 640 x 360 with each quality preset and reports where
// a frame's time goes (pose, skin, BVH, trace, write), the renderer's rays per second, and the bound:
// the same rays replayed through Embree alone, with no shading, on the same threads.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <chrono>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <tbb/info.h>

#include "render/cli/commands.h"
#include "render/frame_writer.h"
#include "render/image.h"
#include "render/preset.h"
#include "render/sample_lanes.h"
#include "render/scene.h"
#include "render/shot.h"
#include "rig/rig_profile.h"

namespace stirrup::cli {
namespace {

struct BenchOptions {
  bool json = false;
  int threads = 0;
  int frames = 12;
};

// The benchmark scene: scenes/trot.json's content, built in so the numbers never depend on a file
// someone edited. The quality is set per preset.
render::SceneSpec benchScene() {
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
  return render::parseScene(trot, "bench");
}

struct PresetResult {
  std::string name;
  int samples = 0;
  double pose = 0, skin = 0, bvh = 0, trace = 0, write = 0;  // ms per frame
  double rays_per_frame = 0;
  double rays_per_second = 0, bound_rays_per_second = 0;
  double fps = 0;
};

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Keep at most this many rays for the replay (48 bytes each); above it every Nth pixel's rays are
// kept, which samples the frame evenly. The bound is a rate, so a sample of the rays measures it.
constexpr double kMaxLoggedRays = 8e6;

PresetResult benchPreset(const render::QualityPreset& preset, const BenchOptions& o,
                         const std::filesystem::path& scratch) {
  render::SceneSpec scene = benchScene();
  render::applyPreset(scene, preset);
  render::Shot shot(scene, rig::RigProfile::thesis(), scene.cameras.front(), o.threads);
  PresetResult r;
  r.name = std::string(preset.name);
  r.samples = preset.samples;

  // Warm-up, and the rays of one frame: render frame 1 once to count them, again keeping them
  // (sampled when there are many), then replay them while the BVH is that frame's.
  shot.renderFrame(1);
  render::RayLog log;
  log.pixel_stride = std::max(1, int(std::ceil(double(shot.lastTimings().rays) / kMaxLoggedRays)));
  shot.renderFrame(1, &log);
  double replay_s = shot.renderer().replay(log);
  replay_s = std::min(replay_s, shot.renderer().replay(log));  // the faster of two: less noise
  r.bound_rays_per_second = replay_s > 0.0 ? double(log.rays) / replay_s : 0.0;

  // Frames as `stirrup render` makes them: each PNG written on the background thread while the next
  // frame renders (render/frame_writer.h). fps is frames over the wall-clock time of the whole run,
  // writes included; the write column is a write's own time on its thread.
  double rays = 0;
  double write_ms = 0;  // touched only by the writer thread, read after its last wait()
  render::FrameWriter writer;
  const auto run0 = Clock::now();
  for (int i = 0; i < o.frames; ++i) {
    const int frame = 1 + i % 72;
    render::Image image = shot.renderFrame(frame);
    const render::FrameTimings& t = shot.lastTimings();
    const std::filesystem::path file = scratch / ("bench." + std::to_string(i % 2) + ".png");
    writer.submit([image = std::move(image), file, &write_ms] {
      const auto w0 = Clock::now();
      render::writePng(image, file);
      write_ms += secondsSince(w0) * 1000.0;
    });
    r.pose += t.pose_ms;
    r.skin += t.skin_ms;
    r.bvh += t.bvh_ms;
    r.trace += t.trace_ms - t.bvh_ms;
    rays += double(t.rays);
  }
  writer.wait();
  const double run_s = secondsSince(run0);
  r.write = write_ms;
  const double n = double(o.frames);
  r.pose /= n, r.skin /= n, r.bvh /= n, r.trace /= n, r.write /= n;
  r.rays_per_frame = rays / n;
  const double compute_s = (r.pose + r.skin + r.bvh + r.trace) / 1000.0;
  r.rays_per_second = compute_s > 0.0 ? r.rays_per_frame / compute_s : 0.0;
  r.fps = run_s > 0.0 ? n / run_s : 0.0;
  return r;
}

void runBench(const BenchOptions& o) {
  namespace fs = std::filesystem;
  const fs::path scratch = fs::temp_directory_path() / ("stirrup-bench-" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  std::vector<PresetResult> results;
  try {
    for (const render::QualityPreset& p : render::qualityPresets()) results.push_back(benchPreset(p, o, scratch));
  } catch (...) {
    fs::remove_all(scratch);
    throw;
  }
  fs::remove_all(scratch);
  const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();

  if (o.json) {
    nlohmann::json presets = nlohmann::json::object();
    for (const PresetResult& r : results) {
      presets[r.name] = {{"fps", r.fps},
                         {"rays_per_second", r.rays_per_second},
                         {"bound_rays_per_second", r.bound_rays_per_second},
                         {"ms", {{"pose", r.pose}, {"skin", r.skin}, {"bvh", r.bvh}, {"trace", r.trace}, {"write", r.write}}}};
    }
    const nlohmann::json out = {{"presets", presets}, {"threads", threads}, {"resolution", {640, 360}},
                                {"simd", render::simdTargetName()}};
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  std::printf("stirrup bench: trot side view, 640x360, %d thread%s, %d frame%s a preset, SIMD %s (ms per frame)\n\n",
              threads, threads == 1 ? "" : "s", o.frames, o.frames == 1 ? "" : "s", render::simdTargetName().c_str());
  std::printf("%-7s %4s %7s %6s %6s %6s %8s %6s %9s %9s %10s %6s\n", "preset", "spp", "fps", "pose", "skin",
              "bvh", "trace", "write", "Mrays/f", "Mrays/s", "bound Mr/s", "ratio");
  for (const PresetResult& r : results) {
    std::printf("%-7s %4d %7.2f %6.1f %6.1f %6.1f %8.1f %6.1f %9.2f %9.2f %10.2f %5.0f%%\n", r.name.c_str(),
                r.samples, r.fps, r.pose, r.skin, r.bvh, r.trace, r.write, r.rays_per_frame / 1e6,
                r.rays_per_second / 1e6, r.bound_rays_per_second / 1e6,
                r.bound_rays_per_second > 0 ? 100.0 * r.rays_per_second / r.bound_rays_per_second : 0.0);
  }
  std::printf("\nratio: the renderer's rays per second (frame time without write) over the bound, the same\n"
              "rays cast through Embree alone with no shading.\n");
}

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto opts = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Measure the renderer per quality preset against Embree alone");
  cmd->footer(
      "Renders a built-in trot side view at 640x360 with each preset (draft, review, final) and prints\n"
      "milliseconds per frame (pose, skin, bvh, trace, write), rays per second, and the bound: the same\n"
      "rays replayed through Embree alone. Example: stirrup bench --json --threads 2");
  cmd->add_flag("--json", opts->json, "Print one JSON object instead of the table");
  cmd->add_option("--threads,-t", opts->threads, "Render threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--frames,-n", opts->frames, "Timed frames per preset")->check(CLI::Range(1, 1000));
  cmd->callback([opts] { runBench(*opts); });
}

}  // namespace stirrup::cli
