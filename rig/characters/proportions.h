// A horse or a rider of other proportions, made from the default generators' parameters (issue 19: a
// crowd of different riders on different horses, no new hand-made meshes).
//
// Horse: every length and radius of HorseParams scaled by withers_height / the default's 160 cm
// (a uniform scale: a smaller horse is the default made smaller, as the Shetland to Shire range is
// not, but 145-175 cm spans riding horses of one build). Colours and the mesh cell stay.
// Rider: every length and radius of RiderParams scaled by height / the default's 170 cm; then her
// build multiplies her girths only: the soft-tissue radii of hips, waist, chest, thigh, knee and calf
// (their depth x and breadth z; not their height y), so a stout rider is wider, not taller.
// Mount: the stirrup's drop and the rein grip follow the rider (leathers and reins are let out for a
// taller rider); the stirrup's distance out from the horse's midline follows the horse's barrel.
#pragma once

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"

namespace stirrup::rig {

// The default characters' sizes the scales are taken against (horse_character.h: "about 160 cm at
// the withers"; rider_character.h: "about 170 cm").
inline constexpr double kDefaultWithersHeightCm = 160.0;
inline constexpr double kDefaultRiderHeightCm = 170.0;

// HorseParams for a horse of this height at the withers carrying a rider of this height. Valid for
// any sizes > 0; the crowd (rig/motion/crowd.h) keeps them to its stated ranges.
HorseParams scaledHorse(double withers_height_cm, double rider_height_cm);
// RiderParams for a rider of this height and build (1 the default's girths).
RiderParams scaledRider(double height_cm, double build);

}  // namespace stirrup::rig
