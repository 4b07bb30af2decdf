// A scene's horse and rider as the rig rides them, made the one way every command makes them (render,
// bake, rig, clip): each character resolved from the scene's entry (rig::resolveCharacter), then the
// rider seated on this horse (rig/characters/seating.h). A rider standing in her file's rest pose is
// seated by the rig and the horse's stirrup leathers are set to her legs (the profile's
// seat.stirrup_holes_up); a rider already seated (the generated rider, or one modelled sitting) keeps
// her rest and only gains the points the rig needs that her file does not name.
#pragma once

#include <string>

#include "rig/character.h"
#include "rig/characters/seating.h"
#include "rig/rig_profile.h"

namespace stirrup::scene {

struct RiddenPair {
  rig::Character horse, rider;
  rig::SeatReport seat;
};

// `*_file` is "default" (the built-in generator) or a glTF path; `*_mapping` a mapping file or empty.
RiddenPair resolveRiddenPair(const std::string& horse_file, const std::string& horse_mapping,
                             const std::string& rider_file, const std::string& rider_mapping,
                             const rig::RigProfile& profile);

// Seats an already resolved rider on an already resolved horse as resolveRiddenPair does.
RiddenPair seatPair(rig::Character horse, rig::Character rider, const rig::RigProfile& profile);

}  // namespace stirrup::scene
