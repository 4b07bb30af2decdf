// Posing the horse (rig/horse_leg.h): the whole-limb legs against the two-bone legs a horse without
// leg pivots gets, over a canter stride, one pose per 24 fps frame.
#include <benchmark/benchmark.h>

#include <string>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/pose.h"
#include "scene/clip_factory.h"

namespace {

using namespace stirrup::rig;
using stirrup::scene::ClipSpec;
using stirrup::scene::makeClip;

// Arg 0: the default horse with its pivot roles removed (two-bone legs); 1: the default horse.
void BM_PoseHorse(benchmark::State& state) {
  Character horse = buildDefaultHorse();
  if (state.range(0) == 0)
    for (const char* leg : {"lf", "rf", "lb", "rb"}) horse.roles.erase(std::string(leg) + "Pivot");
  ClipSpec spec;
  spec.generator = "canter";
  const auto clip = makeClip(spec, horse);
  const int frames = static_cast<int>(clip->duration() * 24.0);
  for (auto _ : state)
    for (int i = 0; i < frames; ++i) benchmark::DoNotOptimize(poseHorse(horse, clip->sample(i / 24.0)));
  state.SetItemsProcessed(state.iterations() * frames);
}
BENCHMARK(BM_PoseHorse)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
