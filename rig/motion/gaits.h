// Gait timelines: one or more steady gaits played one after another, blended phase-continuously.
// Speed and stride frequency ramp linearly across each blend window and the stride phase is their
// exact integral, so the trunk oscillation never jumps; footfalls are found where each hoof's phase
// (stride phase minus its blended touchdown phase) crosses a whole stride, so every stance hoof stays
// put in the world however the parameters change.
#pragma once

#include <vector>

#include "rig/motion/movement.h"
#include "rig/motion/procedural_gait.h"

namespace stirrup::rig {

struct GaitSegment {
  GaitParams gait;
  double duration_s = 3.0;
};

struct GaitTimeline {
  std::vector<GaitSegment> segments;
  double blend_s = 1.0;      // each blend window is centred on the boundary between two segments
  double variation = 0.0;    // 0..1: seeded jitter of hoof lift and landing place
  unsigned seed = 0;
};

// Writes the timeline's speed, stride frequency and trunk oscillation into `m` (replacing them) and
// returns the time its last segment ends.
double applyGaitTimeline(const GaitTimeline& timeline, Movement& m);

// The footfalls of hoof `hoof` under the gait state already in `m` (applyGaitTimeline), touching down
// in [from_s, to_s). Touchdowns whose lift-off would come after `lift_by_s` are dropped, so a scripted
// movement can take over the hoof.
HoofSchedule scanFootfalls(const Movement& m, const GaitTimeline& timeline, int hoof, double from_s,
                           double to_s, double lift_by_s);

}  // namespace stirrup::rig
