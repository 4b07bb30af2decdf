// The bake job for a crowd (issue 19): every pair's frame baked from its own clip and its own rig
// profile, in parallel. A pair's rider channels come from its own horse only, so each equals the
// single-pair bake of her horse (tests/rig/crowd_bake_test.cpp) and no two riders move alike.
#pragma once

#include <span>
#include <vector>

#include "rig/bake.h"

namespace stirrup::rig {

struct CrowdPair {
  const Clip* clip = nullptr;
  const RigProfile* profile = nullptr;
  double clip_offset_s = 0;  // its clip is sampled at the shot's time plus this (its start phase)
};

// One BakedFrame per pair, in order: bakeFrame(pair clip, pair profile, frame, seconds + offset), with
// `seconds` (the shot's time) as its time.
std::vector<BakedFrame> bakeCrowdFrame(std::span<const CrowdPair> pairs, int frame, double seconds);

}  // namespace stirrup::rig
