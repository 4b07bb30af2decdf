#include "scene/ridden_pair.h"

#include <utility>

#include "rig/io/gltf_character.h"

namespace stirrup::scene {

RiddenPair seatPair(rig::Character horse, rig::Character rider, const rig::RigProfile& profile) {
  RiddenPair pair;
  if (horse.source.file.empty() && rider.source.file.empty()) {
    // The generated rider is built seated in the generated horse's stirrups, hands on its reins.
    pair.horse = std::move(horse);
    pair.rider = std::move(rider);
    return pair;
  }
  rig::SeatParams params;
  params.stirrup_holes_up = static_cast<float>(profile.seat.stirrup_holes_up);
  rig::SeatedRider seated = rig::seatRider(rider, horse, params);
  pair.horse = std::move(seated.horse);
  pair.rider = std::move(seated.rider);
  pair.seat = std::move(seated.report);
  // A rider the rig seated, or fitted to a horse she was not modelled on, folds against a horse she was
  // not built for; a rider modelled seated on her own horse (the shipped rider read from its file on the
  // shipped horse among them) is left to her own proportions.
  if (pair.seat.seated_by_rig || pair.seat.fitted_to_horse) pair.rider.fold_guard = rig::foldGuard(pair.rider, pair.horse);
  return pair;
}

RiddenPair resolveRiddenPair(const std::string& horse_file, const std::string& horse_mapping,
                             const std::string& rider_file, const std::string& rider_mapping,
                             const rig::RigProfile& profile) {
  return seatPair(rig::resolveCharacter(rig::CharacterKind::Horse, horse_file, horse_mapping),
                  rig::resolveCharacter(rig::CharacterKind::Rider, rider_file, rider_mapping), profile);
}

}  // namespace stirrup::scene
