// The middle of a crowd as a clip, for cameras that frame the whole crowd (scene/view.h): at each
// time its travel frame stands at the mean of the pairs' travel frames (x, z and ground height), heads
// the way of the mean of their headings' unit vectors, and holds every control at rest. Nothing rides
// it; it is only followed, so the views keep their meaning (a side view stays square to the crowd's
// direction of travel through a turn).
// Cameras sample it often (a damped follow camera's filter takes 600 samples a frame, and a view frames
// every frame of the shot three times), and each sample samples every pair: so it is tabulated once,
// every kTableStepS over the crowd's ride, and sampled between table points by linear interpolation
// (of the mean travel and height, and of the mean heading's unit vector). At a gallop a step is 4 cm of
// travel; on a 50 m turn the chord is within 0.001 cm of the arc. Beyond the table it samples the pairs.
#pragma once

#include <string>
#include <vector>

#include "rig/clip.h"

namespace stirrup::rig {

class CrowdMiddleClip : public Clip {
 public:
  // The pairs' clips, each as the shot samples it (a ShiftedClip at its start phase); they must
  // outlive this. At least one.
  explicit CrowdMiddleClip(std::vector<const Clip*> clips);
  std::string name() const override { return "crowd middle"; }
  // While any pair still rides.
  double duration() const override;
  // Headings that cancel (pairs riding exactly opposite ways) give heading 0.
  HorseFrame sample(double seconds) const override;

 private:
  // Every pair's frames averaged at `seconds`.
  HorseFrame average(double seconds) const;

  std::vector<const Clip*> clips_;
  double duration_ = 0;
  std::vector<HorseFrame> table_;  // average(i * kTableStepS), from 0 to past the duration
};

// The table's step (our choice): a tenth of a frame at 24 fps.
inline constexpr double kCrowdMiddleTableStepS = 1.0 / 240.0;

}  // namespace stirrup::rig
