// Benchmarks of the render pipeline on the default trot shot (scenes/trot.json at its resolution):
// building the characters, posing and skinning a frame, and a whole frame through the renderer.
// Run: build/tests/bench/stirrup_bench --benchmark_filter=Trot
#include <benchmark/benchmark.h>

#include "render/scene.h"
#include "render/shot.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "rig/skin.h"

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
  const render::SceneSpec scene = render::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const rig::RigProfile profile = render::resolveProfile(scene);
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

// A whole frame of the default trot side view: bake, pose, skin, BVH, trace (no PNG write).
void BM_TrotFrame(benchmark::State& state) {
  const render::SceneSpec scene = render::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const rig::RigProfile profile = render::resolveProfile(scene);
  render::Shot shot(scene, profile, scene.cameras.front(), 0);
  int frame = 1;
  for (auto _ : state) {
    render::Image image = shot.renderFrame(frame++);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TrotFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
