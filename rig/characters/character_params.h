// The character generators' parameters by name (`stirrup character make horse --withers_height 150`):
// each names a number or an x,y,z vector of HorseParams or RiderParams (cm, or linear RGB for colours).
// One table per character, so the command line and any scene or crowd that sets proportions read the
// same names.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/error.h"

namespace stirrup::rig {

template <class P>
struct CharacterParam {
  const char* name;
  std::variant<float P::*, glm::vec3 P::*> member;
};

const std::vector<CharacterParam<HorseParams>>& horseParameters();
const std::vector<CharacterParam<RiderParams>>& riderParameters();

// " --name --vector x,y,z ..." for messages.
template <class P>
std::string characterParameterList(const std::vector<CharacterParam<P>>& params) {
  std::string s;
  for (const auto& p : params) s += " --" + std::string(p.name) + (std::holds_alternative<float P::*>(p.member) ? "" : " x,y,z");
  return s;
}

// `value` as one number > 0 (scalar) or three numbers "x,y,z"; anything else is a one-line InputError
// "<context>: --key: expected ...".
std::vector<float> parseCharacterNumbers(const std::string& key, const std::string& value, bool scalar,
                                         const std::string& context);

// Sets the parameter `key` (its name) from `value`, one number > 0 or three numbers "x,y,z". Errors are
// one line: "<context>: --key: expected ...".
template <class P>
void setCharacterParameter(const std::vector<CharacterParam<P>>& table, const std::string& key, const std::string& value,
                           const std::string& context, P& out) {
  const CharacterParam<P>* found = nullptr;
  for (const auto& p : table)
    if (key == p.name) found = &p;
  if (!found)
    throw InputError(context + ": --" + key + ": unknown parameter (expected one of" + characterParameterList(table) + ")");
  const bool scalar = std::holds_alternative<float P::*>(found->member);
  const std::vector<float> numbers = parseCharacterNumbers(key, value, scalar, context);
  if (scalar) out.*std::get<float P::*>(found->member) = numbers[0];
  else out.*std::get<glm::vec3 P::*>(found->member) = glm::vec3(numbers[0], numbers[1], numbers[2]);
}

}  // namespace stirrup::rig
