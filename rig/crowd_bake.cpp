#include "rig/crowd_bake.h"

#include <stdexcept>

#include <tbb/parallel_for.h>

namespace stirrup::rig {

std::vector<BakedFrame> bakeCrowdFrame(std::span<const CrowdPair> pairs, int frame, double seconds) {
  for (const CrowdPair& p : pairs)
    if (!p.clip || !p.profile) throw std::invalid_argument("bakeCrowdFrame: a pair without a clip or a profile");
  std::vector<BakedFrame> out(pairs.size());
  // Each pair reads only its own clip and profile and writes only its own slot: no order between them.
  tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t i) {
    out[i] = bakeFrame(*pairs[i].clip, *pairs[i].profile, frame, seconds + pairs[i].clip_offset_s);
    out[i].seconds = seconds;
  });
  return out;
}

}  // namespace stirrup::rig
