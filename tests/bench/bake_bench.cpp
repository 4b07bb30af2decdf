// The crowd's bake (stirrup bake scenes/cavalry.json -o): 30 pairs over the scene's 240 frames, as the
// command does it (scene/shot_bake.h, then rig::bakedShotGlb), with the file's size; and one frame of
// the evaluator posing every pair (what each baked frame costs once the characters are built).
// Run: build/tests/bench/stirrup_bench --benchmark_filter=Cavalry
#include <benchmark/benchmark.h>

#include "rig/io/gltf_bake.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "scene/shot_bake.h"
#include "scene/shot_evaluator.h"

namespace stirrup {
namespace {

// The whole bake from the scene: characters built at full detail, every frame posed, both cameras
// resolved (the persp view framed over the ride), the glTF's bytes made (not written to disk).
void BM_CavalryBake(benchmark::State& state) {
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/cavalry.json");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
  std::size_t bytes = 0;
  for (auto _ : state) {
    scene::ShotEvaluator characters(scene, profile, 0);
    const std::vector<unsigned char> glb = rig::bakedShotGlb(scene::bakeShot(characters, frames));
    bytes = glb.size();
    benchmark::DoNotOptimize(glb.data());
  }
  state.counters["pairs"] = double(scene.pairs.size());
  state.counters["frames"] = double(frames.size());
  state.counters["file_MB"] = double(bytes) / 1e6;
}
BENCHMARK(BM_CavalryBake)->Unit(benchmark::kSecond)->Iterations(1);

// One frame of the 30 pairs baked and posed, the characters already built.
void BM_CavalryPoseFrame(benchmark::State& state) {
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/cavalry.json");
  scene::ShotEvaluator characters(scene, scene::resolveProfile(scene), 0);
  scene::ShotFrame frame;
  scene::FrameRequest request;
  request.until = scene::EvalStage::Pose;
  characters.evaluate(request, frame);  // builds every pair's coarsest level, which posing uses
  int f = 1;
  for (auto _ : state) {
    request.frame = f;
    f = f % 240 + 1;
    characters.evaluate(request, frame);
    benchmark::DoNotOptimize(frame.pairs.data());
  }
}
BENCHMARK(BM_CavalryPoseFrame)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stirrup
