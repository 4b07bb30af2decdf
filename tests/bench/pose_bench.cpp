// Posing the rider's spine (rig/rider_pose.h poseRiderSpine): the curve spine is built and solved on every
// call, from the rider's channels. It runs once a frame for every rider, so it must stay far inside a
// frame's budget; this measures it (it was a timed test, issue 37: timing belongs here).
// Run: build/tests/bench/stirrup_bench --benchmark_filter=PoseRiderSpine
#include <benchmark/benchmark.h>

#include <vector>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/pose.h"
#include "rig/skeleton.h"

namespace {

using namespace stirrup::rig;

void BM_PoseRiderSpine(benchmark::State& state) {
  const Character rider = buildDefaultRider();
  RiderChannels ch;
  ch[RiderChannel::lowerBackRz] = 10.0;
  ch[RiderChannel::waistRz] = 17.0;
  std::vector<glm::mat4> local = restLocals(rider.skeleton);
  for (auto _ : state) {
    poseRiderSpine(rider, ch, 2.54, RiderPoseParams{}, local);
    benchmark::DoNotOptimize(local.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PoseRiderSpine)->Unit(benchmark::kMicrosecond);

}  // namespace
