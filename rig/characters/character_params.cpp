#include "rig/characters/character_params.h"

#include <cmath>
#include <cstdlib>

namespace stirrup::rig {

const std::vector<CharacterParam<HorseParams>>& horseParameters() {
  using H = HorseParams;
  static const std::vector<CharacterParam<H>> p = {
      {"withers_height", &H::withers_height}, {"withers_x", &H::withers_x},
      {"hips", &H::hips},                     {"back_mid", &H::back_mid},
      {"barrel_center", &H::barrel_center},   {"barrel_radii", &H::barrel_radii},
      {"buttock_center", &H::buttock_center}, {"buttock_radii", &H::buttock_radii},
      {"quarter_center", &H::quarter_center}, {"quarter_radii", &H::quarter_radii},
      {"chest_center", &H::chest_center},     {"chest_radii", &H::chest_radii},
      {"neck_base", &H::neck_base},           {"neck_mid", &H::neck_mid},
      {"poll", &H::poll},                     {"muzzle", &H::muzzle},
      {"neck_base_radius", &H::neck_base_radius}, {"neck_mid_radius", &H::neck_mid_radius},
      {"head_radius", &H::head_radius},       {"muzzle_radius", &H::muzzle_radius},
      {"ear_length", &H::ear_length},         {"mane_radius", &H::mane_radius},
      {"forearm_radius", &H::forearm_radius}, {"cannon_radius", &H::cannon_radius},
      {"gaskin_radius", &H::gaskin_radius},   {"hoof_radius", &H::hoof_radius},
      {"tail_root", &H::tail_root},           {"tail_length", &H::tail_length},
      {"saddle_x", &H::saddle_x},             {"saddle_seat_height", &H::saddle_seat_height},
      {"rein_radius", &H::rein_radius},       {"strap_radius", &H::strap_radius},
      {"coat", &H::coat},                     {"points", &H::points},
      {"leather", &H::leather},               {"pad", &H::pad},
      {"cell", &H::cell}};
  return p;
}

const std::vector<CharacterParam<RiderParams>>& riderParameters() {
  using R = RiderParams;
  static const std::vector<CharacterParam<R>> p = {
      {"pelvis", &R::pelvis},           {"lower_back", &R::lower_back},   {"waist", &R::waist},
      {"chest", &R::chest},             {"upper_chest", &R::upper_chest}, {"neck", &R::neck},
      {"head", &R::head},               {"head_height", &R::head_height}, {"shoulder", &R::shoulder},
      {"upper_arm", &R::upper_arm},     {"forearm", &R::forearm},         {"hip", &R::hip},
      {"thigh", &R::thigh},             {"shin", &R::shin},               {"knee_pole_dir", &R::knee_pole_dir},
      {"hips_radii", &R::hips_radii},
      {"chest_radii", &R::chest_radii}, {"waist_radius", &R::waist_radius},
      {"thigh_radius", &R::thigh_radius}, {"calf_radius", &R::calf_radius},
      {"braid_radius", &R::braid_radius}, {"braid_length", &R::braid_length},
      {"coat_tail_length", &R::coat_tail_length},
      {"skin", &R::skin},               {"coat", &R::coat},               {"breeches", &R::breeches},
      {"boots", &R::boots},             {"hair", &R::hair},               {"cell", &R::cell}};
  return p;
}

std::vector<float> parseCharacterNumbers(const std::string& key, const std::string& value, bool scalar,
                                         const std::string& context) {
  const std::string where = context + ": --" + key + ": ";
  std::vector<float> numbers;
  std::size_t start = 0;
  while (start <= value.size()) {
    const std::size_t comma = value.find(',', start);
    const std::string part = value.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || !end || *end != '\0' || !std::isfinite(v))
      throw InputError(where + "expected a number" + (scalar ? "" : "s x,y,z") + ", got \"" + value + "\"");
    numbers.push_back(static_cast<float>(v));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (scalar && numbers.size() != 1) throw InputError(where + "expected one number, got \"" + value + "\"");
  if (scalar && !(numbers[0] > 0.0f)) throw InputError(where + "expected a number > 0, got \"" + value + "\"");
  if (!scalar && numbers.size() != 3) throw InputError(where + "expected three numbers x,y,z, got \"" + value + "\"");
  return numbers;
}

}  // namespace stirrup::rig
