// The rider rig: Kuhnel 2003's Equations 1-18 with Appendix B's limits, plus the knee lift, hair and
// cloth drives, evaluated from one frame of horse controls. A pure function of its inputs (no state,
// no allocation), so frames can be evaluated in any order, on any thread.
//
// Horse translations arrive in cm and are divided by profile.horse_unit_cm (thesis units) before the
// expressions; rider translations leave in rider units and rotations in degrees, as the channel
// contract (docs/channels.md) says. Every constant is a named RigProfile parameter; the
// decisions where the thesis contradicts itself are in docs/rider-rig.md.
#pragma once

#include "rig/channels.h"
#include "rig/rig_profile.h"

namespace stirrup::rig {

RiderChannels evaluateRider(const HorseChannels& horse, const RigProfile& profile);

}  // namespace stirrup::rig
