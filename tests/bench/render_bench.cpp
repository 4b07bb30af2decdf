// Benchmarks of the render pipeline on the default trot shot (scenes/trot.json at its resolution):
// building the characters, posing and skinning a frame, and a whole frame through the renderer.
// Run: build/tests/bench/stirrup_bench --benchmark_filter=Trot
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "render/shot.h"
#include "render/tracer/image.h"
#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "rig/skin.h"
#include "scene/preset.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace {

using namespace stirrup;

void BM_BuildDefaultCharacters(benchmark::State& state) {
  for (auto _ : state) {
    rig::Character horse = rig::buildDefaultHorse();
    rig::Character rider = rig::buildDefaultRider();
    benchmark::DoNotOptimize(horse.mesh.positions.data());
    benchmark::DoNotOptimize(rider.mesh.positions.data());
  }
}
BENCHMARK(BM_BuildDefaultCharacters)->Unit(benchmark::kMillisecond);

void BM_TrotPoseAndSkin(benchmark::State& state) {
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const rig::Character horse = rig::buildDefaultHorse(), rider = rig::buildDefaultRider();
  const render::Shot shot(scene, profile, scene.cameras.front(), 0);
  std::vector<glm::vec3> positions, normals;
  int frame = 1;
  for (auto _ : state) {
    const rig::BakedFrame b = shot.bake(frame++);
    std::vector<glm::mat4> hw = rig::poseHorse(horse, b.horse);
    const std::vector<glm::mat4> rw = rig::poseRider(rider, horse, hw, b.rider, profile.rider_unit_cm);
    rig::skinMesh(horse.mesh, horse.skeleton, hw, positions, normals);
    rig::skinMesh(rider.mesh, rider.skeleton, rw, positions, normals);
    benchmark::DoNotOptimize(positions.data());
  }
}
BENCHMARK(BM_TrotPoseAndSkin)->Unit(benchmark::kMillisecond);

// The skin alone: the default horse and rider at one pose of the trot (frame 12), positions and normals.
void BM_SkinTrotCharacters(benchmark::State& state) {
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const rig::Character horse = rig::buildDefaultHorse(), rider = rig::buildDefaultRider();
  const render::Shot shot(scene, profile, scene.cameras.front(), 0);
  const rig::BakedFrame b = shot.bake(12);
  const std::vector<glm::mat4> hw = rig::poseHorse(horse, b.horse);
  const std::vector<glm::mat4> rw = rig::poseRider(rider, horse, hw, b.rider, profile.rider_unit_cm);
  std::vector<glm::vec3> positions, normals;
  for (auto _ : state) {
    rig::skinMesh(horse.mesh, horse.skeleton, hw, positions, normals);
    rig::skinMesh(rider.mesh, rider.skeleton, rw, positions, normals);
    benchmark::DoNotOptimize(positions.data());
    benchmark::DoNotOptimize(normals.data());
  }
  state.counters["vertices"] = double(horse.mesh.vertexCount() + rider.mesh.vertexCount());
}
BENCHMARK(BM_SkinTrotCharacters)->Unit(benchmark::kMicrosecond);

// A whole frame of the default trot side view: bake, pose, skin, BVH, trace (no PNG write).
void BM_TrotFrame(benchmark::State& state) {
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  render::Shot shot(scene, profile, scene.cameras.front(), 0);
  int frame = 1;
  for (auto _ : state) {
    render::Image image = shot.renderFrame(frame++);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TrotFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

// A frame of the trot side view at each quality preset (arg: 0 draft, 1 review, 2 final): more
// samples a pixel cost more, which `stirrup bench` reports as fps; compared here, not in a timed test.
void BM_TrotFramePreset(benchmark::State& state) {
  scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const scene::QualityPreset& preset = scene::qualityPresets()[static_cast<std::size_t>(state.range(0))];
  scene::applyPreset(scene, preset);
  const rig::RigProfile profile = scene::resolveProfile(scene);
  render::Shot shot(scene, profile, scene.cameras.front(), 0);
  shot.renderFrame(1);  // the first frame builds what later frames refit; not timed
  int frame = 2;
  for (auto _ : state) {
    render::Image image = shot.renderFrame(frame);
    frame = frame % 72 + 1;
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(std::string(preset.name));
}
BENCHMARK(BM_TrotFramePreset)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The 8-bit sRGB encoding of a rendered 640 x 360 trot frame (review), as every PNG write makes it on the
// writer's thread: what a frame's write costs before zlib.
void BM_EncodeSrgb8(benchmark::State& state) {
  scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  scene::applyPreset(scene, scene::qualityPresets()[1]);
  const rig::RigProfile profile = scene::resolveProfile(scene);
  render::Shot shot(scene, profile, scene.cameras.front(), 0);
  const render::Image image = shot.renderFrame(30);
  std::vector<uint8_t> bytes(image.rgba.size() * 3);
  for (auto _ : state) {
    render::encodeSrgb8(image.rgba, bytes);
    benchmark::DoNotOptimize(bytes.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(image.rgba.size()));
}
BENCHMARK(BM_EncodeSrgb8)->Unit(benchmark::kMicrosecond);

// A whole PNG write of a rendered 640 x 360 trot frame, as the writer's thread makes it for `stirrup
// render` and `stirrup bench`: arg 0 a draft frame stored (zlib level 0), arg 1 a review frame at
// level 1. CPU time: on two cores the write takes its time from the tracer's threads.
void BM_WritePng(benchmark::State& state) {
  const bool review = state.range(0) == 1;
  scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  scene::applyPreset(scene, scene::findPreset(review ? "review" : "draft"));
  const rig::RigProfile profile = scene::resolveProfile(scene);
  render::Shot shot(scene, profile, scene.cameras.front(), 0);
  const render::Image image = shot.renderFrame(30);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("stirrup-bench-write-" + std::to_string(::getpid()) + ".png");
  const int level = scene::defaultPngCompression(scene);
  for (auto _ : state) render::writePng(image, file, level);
  std::filesystem::remove(file);
  state.SetLabel(std::string(review ? "review" : "draft") + ", level " + std::to_string(level));
}
BENCHMARK(BM_WritePng)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The BVH update modes on the trot side view (review preset, as the movies render): a frame's BVH
// update and trace, in ms per frame. The renderer's default (Refit) is the one with the least of the
// two together; a cheaper-looking update that slows the trace does not win.
void BM_TrotFrameBvh(benchmark::State& state) {
  scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  scene::applyPreset(scene, scene::findPreset("review"));
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const auto mode = static_cast<render::BvhUpdate>(state.range(0));
  render::Shot shot(scene, profile, scene.cameras.front(), 0, mode);
  shot.renderFrame(1);  // the first commit builds (Refit: over the rest pose); not timed
  int frame = 2;
  double bvh_ms = 0, trace_ms = 0;
  for (auto _ : state) {
    render::Image image = shot.renderFrame(frame);
    frame = frame % 72 + 1;
    bvh_ms += shot.lastTimings().bvh_ms;
    trace_ms += shot.lastTimings().trace_ms - shot.lastTimings().bvh_ms;
    benchmark::DoNotOptimize(image.rgba.data());
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["bvh_ms"] = bvh_ms / n;
  state.counters["trace_ms"] = trace_ms / n;
  state.SetLabel(mode == render::BvhUpdate::Refit                ? "refit"
                 : mode == render::BvhUpdate::RebuildPerMeshLow ? "rebuild LOW per mesh"
                 : mode == render::BvhUpdate::RebuildPerMesh    ? "rebuild MEDIUM per mesh"
                                                                : "rebuild MEDIUM, one BVH");
}
BENCHMARK(BM_TrotFrameBvh)
    ->Arg(static_cast<int>(render::BvhUpdate::Refit))
    ->Arg(static_cast<int>(render::BvhUpdate::RebuildPerMeshLow))
    ->Arg(static_cast<int>(render::BvhUpdate::RebuildPerMesh))
    ->Arg(static_cast<int>(render::BvhUpdate::Rebuild))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(3.0);

}  // namespace
