// Path clip throughput (issue 15): sampling a path clip over rolling hills must stay far under
// 0.1 ms a frame, so it never shows in a render's time. Building the clip (once per shot) is
// measured apart.
#include <benchmark/benchmark.h>

#include <memory>

#include "rig/motion/path_clip.h"

namespace {

using namespace stirrup::rig;

// Walk, trot and canter over a path that turns right then left, on hills: every branch of sample().
PathClipParams params() {
  PathClipParams p;
  p.points = {{0, 0}, {1500, 0}, {2600, 500}, {3100, 1400}, {3500, 2400}, {3900, 3400}, {4800, 4000}, {6500, 4000}};
  p.speed = {{0, 180}, {4, 180}, {6, 360}, {11, 360}, {13, 560}, {60, 560}};
  return p;
}

std::shared_ptr<const Terrain> hills() {
  HillsParams h;
  h.seed = 5;
  h.amplitude_cm = 150;
  h.wavelength_cm = 2500;
  h.octaves = 3;
  return std::make_shared<const Terrain>(Terrain::hills(h, "bench"));
}

void BM_PathClipBuild(benchmark::State& state) {
  const auto ground = hills();
  for (auto _ : state) benchmark::DoNotOptimize(PathClip(params(), ground, "bench"));
}
BENCHMARK(BM_PathClipBuild)->Unit(benchmark::kMillisecond);

// One sample per 24 fps frame across the whole clip; items = frames.
void BM_PathClipSampleOnHills(benchmark::State& state) {
  const PathClip clip(params(), hills(), "bench");
  const int frames = static_cast<int>(clip.duration() * 24.0);
  for (auto _ : state)
    for (int k = 0; k < frames; ++k) benchmark::DoNotOptimize(clip.sample(k / 24.0));
  state.SetItemsProcessed(state.iterations() * frames);
  state.SetLabel("items = frames");
}
BENCHMARK(BM_PathClipSampleOnHills)->Unit(benchmark::kMicrosecond);

}  // namespace
