// A clip moved rigidly on the ground: its travel frame turned by `turn_deg` about a point of the ground
// and carried from that point to another. A crowd pair that plays its horse's own keyed animation
// (rig/motion/crowd.h PairCharacters::own_clip, issue 60) plays it from its place in the formation, facing
// the lead's way: the animation as keyed, the whole of it moved there. A keyed horse is posed in its
// travel frame (HorseFrame::keyed_pose), so moving the frame moves every joint with it; the controls,
// relative to that frame, are the clip's own.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "rig/clip.h"

namespace stirrup::rig {

class PlacedClip final : public Clip {
 public:
  // The clip's ground point `from` (x, z cm) is carried to `to`, its travel turned `turn_deg` about it
  // (+ from +X toward +Z, the sense of HorseFrame::heading_deg).
  PlacedClip(std::shared_ptr<const Clip> clip, glm::dvec2 from, glm::dvec2 to, double turn_deg);
  std::string name() const override { return clip_->name(); }
  double duration() const override { return clip_->duration(); }
  HorseFrame sample(double seconds) const override { return placed(clip_->sample(seconds)); }
  HorseFrame sampleTravel(double seconds) const override { return placed(clip_->sampleTravel(seconds)); }
  // Fences stand along the travel, which the clip keeps: unchanged.
  std::vector<Obstacle> obstacles() const override { return clip_->obstacles(); }

 private:
  HorseFrame placed(HorseFrame f) const;
  std::shared_ptr<const Clip> clip_;
  glm::dvec2 from_, to_;
  double turn_deg_, cos_, sin_;
};

}  // namespace stirrup::rig
