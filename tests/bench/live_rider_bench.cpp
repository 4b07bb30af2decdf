// The Blender add-on's Live toggle (scene/live_rider.h through `stirrup live`, docs/blender.md "Live"):
// what stirrup spends on a frame. Scrubbing or playing asks for the rider at one frame after another with
// the horse unchanged (the clip kept); an edited key hands in a frame of the horse, and the clip is made
// again from the table before the rider is posed. The horse is the default horse trotting in a file stirrup
// baked (tests/rig/io/baked_trot.h), 48 frames at 24 fps, under the default rider. The bar is 24
// frames a second for a pair during playback (under 42 ms a frame, Blender's own share included) and a
// rider within 0.2 s of an edit.
// Run: build/tests/bench/stirrup_bench --benchmark_filter=LiveRider
#include <benchmark/benchmark.h>
#include <tiny_gltf.h>

#include <memory>
#include <vector>

#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_mapping.h"
#include "rig/mapping/mapping_skeleton.h"
#include "scene/live_rider.h"
#include "scene/ridden_pair.h"
#include "tests/rig/io/baked_trot.h"

namespace {

using namespace stirrup::rig;
using stirrup::scene::LiveRider;
using stirrup::scene::LiveRiderSetup;
using stirrup::scene::RiddenPair;
using stirrup::scene::resolveRiddenPair;

LiveRiderSetup trotSetup() {
  const RigProfile profile;
  const RiddenPair pair = resolveRiddenPair(test::bakedTrot().file.string(), "", "default", "", profile);
  LiveRiderSetup setup;
  setup.horse_file = test::bakedTrot().file;
  setup.horse = std::make_shared<const Character>(pair.horse);
  setup.rider = std::make_shared<const Character>(pair.rider);
  setup.profile = profile;
  setup.fps = test::kFps;
  setup.first_frame = 0;
  setup.last_frame = test::kFrames - 1;
  return setup;
}

// The horse as the file keys it at a frame: what the add-on hands in after an edit.
std::vector<glm::dmat4> horseAt(int frame) {
  const std::string file = test::bakedTrot().file.string();
  const tinygltf::Model model = readGltfFile(test::bakedTrot().file, file);
  const std::vector<glm::dmat4> worlds = GltfAnimation::together(model, file).worlds(frame / test::kFps);
  const std::vector<glm::mat4> ibm = gltfInverseBinds(model, file, 0);
  std::vector<glm::dmat4> out;
  for (std::size_t k = 0; k < ibm.size(); ++k) out.push_back(worlds[std::size_t(model.skins[0].joints[k])] * glm::dmat4(ibm[k]));
  return out;
}

// Playback or scrubbing: the rider at the next frame, the horse unchanged.
void BM_LiveRiderPlayback(benchmark::State& state) {
  LiveRider live(trotSetup());
  int frame = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(live.rider(frame).data());
    frame = (frame + 1) % test::kFrames;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LiveRiderPlayback)->Unit(benchmark::kMillisecond);

// An edit: one frame of the horse handed in, then the rider at that frame (the clip made again).
void BM_LiveRiderAfterAnEdit(benchmark::State& state) {
  LiveRider live(trotSetup());
  const std::vector<glm::dmat4> horse = horseAt(20);
  for (auto _ : state) {
    live.setHorse(20, horse);
    benchmark::DoNotOptimize(live.rider(20).data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LiveRiderAfterAnEdit)->Unit(benchmark::kMillisecond);

}  // namespace
