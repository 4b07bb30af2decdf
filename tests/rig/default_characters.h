// The default horse and rider (rig/characters/), built once per test executable: building them
// polygonises the implicit bodies, which takes a moment, and every test poses the same ones.
#pragma once

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"

namespace stirrup::rig::test {

inline const Character& defaultHorse() {
  static const Character c = buildDefaultHorse();
  return c;
}
inline const Character& defaultRider() {
  static const Character c = buildDefaultRider();
  return c;
}

}  // namespace stirrup::rig::test
