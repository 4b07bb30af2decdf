// Named colours for a crowd's horses and riders (issue 19: "a troop of different riders on different
// horses"): a horse's coat (with its points: legs, mane and tail), a rider's jacket, hair and skin.
// Each name sets the generators' colour parameters (linear RGB, like HorseParams::coat); the first
// name of each list is the default characters' own colour, so a pair that names none looks as before.
// The values are our choices, picked by eye under the renderer's sun and sky to read as the colour
// named (a horseman's bay, chestnut, grey ...).
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"

namespace stirrup::rig {

struct HorseCoat {
  const char* name;
  glm::vec3 coat, points;
};
struct NamedColor {
  const char* name;
  glm::vec3 color;
};

const std::vector<HorseCoat>& horseCoats();     // bay (default), chestnut, black, grey, dun, palomino, brown
const std::vector<NamedColor>& riderJackets();  // red (default), navy, black, green, tweed, blue, grey
const std::vector<NamedColor>& riderHair();     // brown (default), black, blonde, auburn, grey
const std::vector<NamedColor>& riderSkins();    // light (default), fair, olive, brown, dark

// "bay, chestnut, ..." for messages.
std::string paletteNames(const std::vector<HorseCoat>& list);
std::string paletteNames(const std::vector<NamedColor>& list);
// The entry of that name, or null.
const HorseCoat* findHorseCoat(const std::string& name);
const NamedColor* findNamedColor(const std::vector<NamedColor>& list, const std::string& name);

// Sets the named colours on generator parameters (names must exist: findHorseCoat/findNamedColor).
void applyHorseCoat(const std::string& coat, HorseParams& horse);
void applyRiderColors(const std::string& jacket, const std::string& hair, const std::string& skin, RiderParams& rider);

}  // namespace stirrup::rig
