// A horse clip: something that, sampled at a time, gives the horse controls of the contract plus
// what the horse's body needs to be posed. Clips are sampled, never stepped: no hidden state, so any
// frame can be evaluated alone (a farm renders frames out of order).
#pragma once

#include <string>

#include "rig/channels.h"

namespace stirrup::rig {

struct HorseFrame {
  HorseChannels controls;   // contract channels (cm, degrees), offsets from rest in the travel frame
  double travel_cm = 0.0;   // how far the travel frame has moved along world +X since t = 0
  // Body follow-through beyond the contract (degrees, + = up / to the right), for posing only.
  double neck_rz = 0.0;
  double head_rz = 0.0;
  double tail_rz = 0.0;
  double tail_ry = 0.0;
};

class Clip {
 public:
  virtual ~Clip() = default;
  virtual std::string name() const = 0;
  // Seconds; sample() accepts any t and is periodic or clamped as the clip defines.
  virtual double duration() const = 0;
  virtual HorseFrame sample(double seconds) const = 0;
};

}  // namespace stirrup::rig
