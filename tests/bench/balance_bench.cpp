// The balance stage's cost (rig/balance.h, issue 21: under 0.05 ms a frame). BM_BalanceTrunk is the
// stage's decision alone; BM_PoseMounted poses both characters on the rear with the stage (balance 1)
// and without it (the rigid rider's path: no stage), so the difference is all the stage adds to a
// frame: the decision, the centre of mass, the stirrup targets and the second pass down the skeleton.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "rig/bake.h"
#include "rig/balance.h"
#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/pose.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace {

using namespace stirrup;

struct RearFrames {
  rig::Character horse = rig::buildDefaultHorse(), rider = rig::buildDefaultRider();
  rig::RigProfile profile;
  std::vector<rig::BakedFrame> frames;
  RearFrames() {
    const scene::SceneSpec scene = scene::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/rear.json");
    profile = scene::resolveProfile(scene);
    const auto clip = scene::makeClip(scene.clip);
    for (int f : scene::parseFrameList(scene.frames, "frames"))
      frames.push_back(rig::bakeFrame(*clip, profile, f, scene::frameTime(scene, f)));
  }
};
const RearFrames& rear() {
  static const RearFrames r;
  return r;
}

void BM_BalanceTrunk(benchmark::State& state) {
  const RearFrames& r = rear();
  std::vector<rig::BalanceInput> inputs;
  for (const rig::BakedFrame& b : r.frames) {
    const rig::MountedPose pose = rig::poseMounted(r.horse, r.rider, b.horse, b.rider, r.profile);
    rig::BalanceInput in;
    in.saddle = pose.horse[r.horse.role("saddle")];
    in.seat = glm::vec3(pose.rider[r.rider.role("pelvis")][3]);
    in.stirrups = 0.5f * (glm::vec3(pose.horse[r.horse.role("lStirrup")][3]) + glm::vec3(pose.horse[r.horse.role("rStirrup")][3]));
    in.trunk = glm::vec3(pose.rider[r.rider.role("neck")][3]) - in.seat;
    in.fold_scale = 2;
    inputs.push_back(in);
  }
  for (auto _ : state)
    for (const rig::BalanceInput& in : inputs) benchmark::DoNotOptimize(rig::balanceTrunk(in, r.profile.balance));
  state.SetItemsProcessed(state.iterations() * int64_t(inputs.size()));
  state.SetLabel("items = frames");
}
BENCHMARK(BM_BalanceTrunk);

// Arg 1: the balance stage on; 0: off.
void BM_PoseMounted(benchmark::State& state) {
  const RearFrames& r = rear();
  rig::RigProfile profile = r.profile;
  profile.rigid = state.range(0) == 0;  // rigid: poseMounted runs no stage (the channels are the same)
  for (auto _ : state)
    for (const rig::BakedFrame& b : r.frames)
      benchmark::DoNotOptimize(rig::poseMounted(r.horse, r.rider, b.horse, b.rider, profile));
  state.SetItemsProcessed(state.iterations() * int64_t(r.frames.size()));
  state.SetLabel(state.range(0) ? "balance stage on; items = frames" : "balance stage off; items = frames");
}
BENCHMARK(BM_PoseMounted)->Arg(0)->Arg(1);

}  // namespace
