// A clip sampled a fixed time later: a crowd pair's clip at its start phase (rig/motion/crowd.h,
// PairSpec::clip_offset_s), so that whatever samples a clip at the shot's time (a follow camera,
// scene/camera_motion.h) sees the pair where bakeCrowdFrame (rig/crowd_bake.h) poses it.
#pragma once

#include <string>
#include <vector>

#include "rig/clip.h"

namespace stirrup::rig {

class ShiftedClip : public Clip {
 public:
  // `clip` must outlive this.
  ShiftedClip(const Clip& clip, double offset_s) : clip_(clip), offset_s_(offset_s) {}
  std::string name() const override { return clip_.name(); }
  // The time left to play from the shot's start.
  double duration() const override { return clip_.duration() - offset_s_; }
  HorseFrame sample(double seconds) const override { return clip_.sample(seconds + offset_s_); }
  HorseFrame sampleTravel(double seconds) const override { return clip_.sampleTravel(seconds + offset_s_); }
  // Fences stand by travel distance, not by time: unchanged.
  std::vector<Obstacle> obstacles() const override { return clip_.obstacles(); }

 private:
  const Clip& clip_;
  double offset_s_;
};

}  // namespace stirrup::rig
