// Rider rig throughput: frames evaluated per second on one core. A baked clip of a few thousand
// frames should cost nothing next to rendering; this keeps it that way.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "rig/rider_rig.h"
#include "rig/rig_profile.h"

namespace {

using stirrup::rig::HorseChannel;
using stirrup::rig::HorseChannels;

// One second of a trot at 1000 frames: every hoof, the pivot and the back moving, so every branch
// and clamp of the rig is exercised (hoof heights sweep past the 15/18/20 limits at the peaks).
std::vector<HorseChannels> trotClip(int frames) {
  std::vector<HorseChannels> clip(static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) {
    const double phase = 2 * std::numbers::pi * i / frames;
    HorseChannels& h = clip[static_cast<std::size_t>(i)];
    const double reach = 70 * std::cos(phase);
    h[HorseChannel::lfHoofTx] = reach;
    h[HorseChannel::rbHoofTx] = -reach;
    h[HorseChannel::rfHoofTx] = -reach;
    h[HorseChannel::lbHoofTx] = reach;
    h[HorseChannel::lfHoofTy] = h[HorseChannel::rbHoofTy] = 90 * std::max(0.0, std::sin(phase));
    h[HorseChannel::rfHoofTy] = h[HorseChannel::lbHoofTy] = 90 * std::max(0.0, -std::sin(phase));
    h[HorseChannel::rearPivotTy] = 4 * std::sin(2 * phase);
    h[HorseChannel::rearPivotRz] = 25 * std::sin(phase);
    h[HorseChannel::rearPivotRx] = 3 * std::cos(phase);
    h[HorseChannel::backMidRz] = 2 * std::sin(2 * phase);
  }
  return clip;
}

void BM_EvaluateRider(benchmark::State& state) {
  const std::vector<HorseChannels> clip = trotClip(1000);
  const stirrup::rig::RigProfile profile = stirrup::rig::RigProfile::thesis();
  for (auto _ : state) {
    for (const HorseChannels& h : clip) benchmark::DoNotOptimize(stirrup::rig::evaluateRider(h, profile));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(clip.size()));
  state.SetLabel("items = frames");
}
BENCHMARK(BM_EvaluateRider);

}  // namespace

BENCHMARK_MAIN();
