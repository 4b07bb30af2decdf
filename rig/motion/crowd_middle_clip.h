// The middle of a crowd as a clip, for cameras that frame the whole crowd (render/view.h): at each
// time its travel frame stands at the mean of the pairs' travel frames (x, z and ground height), heads
// the way of the mean of their headings' unit vectors, and holds every control at rest. Nothing rides
// it; it is only followed, so the views keep their meaning (a side view stays square to the crowd's
// direction of travel through a turn).
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
  std::vector<const Clip*> clips_;
};

}  // namespace stirrup::rig
