// The horse's loose tack: the pieces of its mesh that hang free or are held (the irons, the leathers
// hanging from the saddle, the reins and bit). A rider's legs and hands touch these on purpose, so the
// surfaces a rider must keep clear of leave them out: seating (rig/characters/seating.h) when it fits her
// legs, and the contact measure of a posed frame (rig/contact_depth.h, rig/frame_check.h).
#pragma once

#include <vector>

#include "rig/character.h"

namespace stirrup::rig {

// One flag a vertex of horse.mesh: true for every separate piece of the mesh (vertices joined by
// triangles) with a vertex bound to a stirrup or rein joint of its own ("lStirrup", "rStirrup", "lRein",
// "rRein" roles other than the saddle's joint). A horse without those roles has no loose tack.
std::vector<bool> horseLooseTack(const Character& horse);

}  // namespace stirrup::rig
