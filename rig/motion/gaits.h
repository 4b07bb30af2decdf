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
//
// With m.paced_blends a blend moves no hoof faster than the steady gaits do (in a steady gait these
// rules give the gait's own footfalls). Touchdowns stay where the phase puts them; what is paced is
// where each stance ends and how high the swing after it goes:
//   - the stance ends when the hoof has covered the duty factor the blend has reached by then, not the
//     one at touchdown: speeding up, the duty factor falls while the stride frequency rises, and a
//     stance timed at touchdown leaves a swing too short for its stride;
//   - a stance lasts at most its duty factor of a stride: a hoof whose touchdown phase the blend moves
//     later (a lead change, the fore pair from walk to trot) takes the delay in the air, where it
//     lengthens the swing, not on the ground, where it would stretch the stance past both gaits' reach
//     and leave the next swing a longer stride to cover;
//   - and at most its duty factor of the time to the hoof's next touchdown, less when the cycle after
//     is longer: a hoof whose touchdown the blend moves earlier shortens its stance as much as its
//     swing, and the swing's ground (half of each stance on either side and the body's travel in the
//     air) stays in the steady gait's proportion to its time;
//   - a swing's lift is its duration times the gaits' blended lift per second of swing (each gait's lift
//     over its steady swing time), so a quicker swing is a lower one and the hoof rises and falls no
//     faster than in either gait; a longer one goes no higher than the higher of the two gaits.
HoofSchedule scanFootfalls(const Movement& m, const GaitTimeline& timeline, int hoof, double from_s,
                           double to_s, double lift_by_s);

}  // namespace stirrup::rig
