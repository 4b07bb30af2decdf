// A horse with an animation of its own, made by stirrup (the default pair trotting for two seconds, posed as
// every consumer poses them, written by the bake): the file tests of a horse's own animation read, with
// the poses and frames it was made from as their oracle. Written once per test executable.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rig/bake.h"
#include "rig/io/gltf_bake.h"
#include "rig/motion/procedural_gait.h"
#include "rig/pose.h"
#include "tests/rig/default_characters.h"

namespace stirrup::rig::test {

inline constexpr double kFps = 24.0;
inline constexpr int kFrames = 48;

struct BakedTrot {
  std::filesystem::path file;
  std::vector<MountedPose> poses;
  std::vector<HorseFrame> frames;
};

inline const BakedTrot& bakedTrot() {
  static const BakedTrot trot = [] {
    BakedTrot b;
    const ProceduralGait gait(trotParams());
    const RigProfile profile;
    BakedShot shot;
    shot.name = "trot";
    shot.fps = kFps;
    BakedPair pair;
    pair.horse = &defaultHorse();
    pair.rider = &defaultRider();
    for (int f = 0; f < kFrames; ++f) {
      const BakedFrame baked = bakeFrame(gait, profile, f + 1, f / kFps);
      b.frames.push_back(baked.horse);
      pair.poses.push_back(poseMounted(*pair.horse, *pair.rider, baked.horse, baked.rider, profile));
      shot.seconds.push_back(float(f / kFps));
    }
    b.poses = pair.poses;
    shot.pairs.push_back(pair);
    const std::vector<unsigned char> bytes = bakedShotGlb(shot);
    b.file = std::filesystem::temp_directory_path() / ("stirrup-keyed-trot-" + std::to_string(::getpid()) + ".glb");
    std::ofstream(b.file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return b;
  }();
  return trot;
}

}  // namespace stirrup::rig::test
