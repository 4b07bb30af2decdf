// Posing the tack the rider moves: the stirrups hang where her feet put them, the reins end in her
// hands. Each moves joints of the posed horse's world matrices in place.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "rig/channels.h"
#include "rig/character.h"

namespace stirrup::rig {

// Where the ball of each foot goes, in world: the horse's stirrup rest place (hanging from the posed
// saddle) moved by lFoot/rFoot tx (forward) and tz (away from the belly). index 0 = left, 1 = right.
glm::vec3 stirrupTarget(const Character& horse, std::span<const glm::mat4> horseWorld, const RiderChannels& r,
                        double rider_unit_cm, int side);

// Moves the horse's stirrup joints to the rider's feet (call after poseHorse when a rider rides).
void placeStirrups(const Character& horse, std::span<glm::mat4> horseWorld, const RiderChannels& r,
                   double rider_unit_cm);

// Moves the hand ends of the horse's reins ("lRein", "rRein") to the rider's hands ("lHand",
// "rHand"), so the reins run from the bit to where her hands close on them (call after poseRider).
void placeReins(const Character& horse, std::span<glm::mat4> horseWorld, const Character& rider,
                std::span<const glm::mat4> riderWorld);

}  // namespace stirrup::rig
