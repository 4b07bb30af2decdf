#include "scene/crowd_characters.h"

#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/error.h"
#include "rig/io/gltf_character.h"
#include "rig/io/keyed_horse_clip.h"
#include "rig/motion/placed_clip.h"
#include "rig/parallel_first_error.h"
#include "scene/profile_resolver.h"
#include "scene/ridden_pair.h"
#include "scene/scene.h"

namespace stirrup::scene {
namespace {

using CharacterKey = std::tuple<rig::CharacterKind, std::string, std::string>;  // kind, file, mapping

// The files the pairs name, each read once.
std::map<CharacterKey, std::shared_ptr<const rig::Character>> readFiles(const std::vector<rig::PairSpec>& pairs) {
  std::map<CharacterKey, std::shared_ptr<const rig::Character>> files;
  for (const rig::PairSpec& p : pairs) {
    if (p.horse_file != "default") files[{rig::CharacterKind::Horse, p.horse_file, p.horse_mapping}];
    if (p.rider_file != "default") files[{rig::CharacterKind::Rider, p.rider_file, p.rider_mapping}];
  }
  std::vector<CharacterKey> keys;
  for (const auto& [key, c] : files) keys.push_back(key);
  std::vector<std::shared_ptr<const rig::Character>> read(keys.size());
  rig::parallelForFirstError(keys.size(), [&](std::size_t i) {
    const auto& [kind, file, mapping] = keys[i];
    read[i] = std::make_shared<const rig::Character>(rig::resolveCharacter(kind, file, mapping));
  });
  for (std::size_t i = 0; i < keys.size(); ++i) files[keys[i]] = read[i];
  return files;
}

// The horse's own animation, keyed on `horse`, moved to the pair's slot as it stands at the pair's start
// phase (the shot's time 0 plays the clip at clip_offset_s).
std::shared_ptr<const rig::Clip> placedAnimation(const rig::PairSpec& p, const rig::Character& horse) {
  auto keyed = std::make_shared<const rig::KeyedHorseClip>(p.horse_file, *p.animation, rig::keyedHorseMapping(horse), &horse);
  const rig::HorseFrame start = keyed->sampleTravel(p.clip_offset_s);
  return std::make_shared<const rig::PlacedClip>(keyed, glm::dvec2(start.travel_cm, start.travel_z_cm), p.slot_cm,
                                                 p.slot_heading_deg - start.heading_deg);
}

}  // namespace

void resolvePairCharacters(std::vector<rig::PairSpec>& pairs, const SceneSpec& scene, const std::string& field) {
  const std::string source = scene.file.string();
  for (std::size_t i = 0; i < pairs.size(); ++i)
    if (pairs[i].animation && scene.terrain && !scene.terrain->flat())
      throw rig::InputError(source + ": " + field + ": pair " + std::to_string(i) + " plays its horse's own animation \"" + *pairs[i].animation +
                       "\", keyed on flat ground (expected a crowd on flat ground, or the generated gait over the terrain)");
  const auto files = readFiles(pairs);
  // Each profile name resolved once, as the shot's evaluator resolves a crowd's (the scene's overrides applied).
  std::map<std::string, rig::RigProfile> profiles;
  for (const rig::PairSpec& p : pairs)
    if (p.ownCharacters() && !profiles.count(p.profile)) {
      SceneSpec named = scene;
      named.profile = p.profile;
      profiles.emplace(p.profile, resolveProfile(named));
    }
  rig::parallelForFirstError(pairs.size(), [&](std::size_t i) {
    rig::PairSpec& p = pairs[i];
    if (!p.ownCharacters()) return;
    rig::Character horse = p.horse_file == "default" ? rig::buildHorse(p.horse())
                                                      : *files.at({rig::CharacterKind::Horse, p.horse_file, p.horse_mapping});
    rig::Character rider = p.rider_file == "default" ? rig::buildRider(p.rider(), p.horse().mount)
                                                      : *files.at({rig::CharacterKind::Rider, p.rider_file, p.rider_mapping});
    scene::RiddenPair seated = scene::seatPair(std::move(horse), std::move(rider), profiles.at(p.profile));
    auto c = std::make_shared<rig::PairCharacters>();
    c->extent = rig::pairExtent(seated.horse, seated.rider);
    c->seat = seated.seat;
    c->horse = std::make_shared<const rig::Character>(std::move(seated.horse));
    c->rider = std::make_shared<const rig::Character>(std::move(seated.rider));
    if (p.animation) c->own_clip = placedAnimation(p, *c->horse);
    p.characters = std::move(c);
  });
}

}  // namespace stirrup::scene
