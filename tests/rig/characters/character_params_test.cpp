#include "rig/characters/character_params.h"

#include <functional>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

using test::errorOf;

template <class P>
void expectEachNameReachesItsOwnField(const std::vector<CharacterParam<P>>& table) {
  std::set<std::string> names;
  for (const auto& param : table) {
    EXPECT_TRUE(names.insert(param.name).second) << "duplicate " << param.name;
    // Setting this parameter to a value no default has changes it and nothing else.
    P p;
    const bool scalar = std::holds_alternative<float P::*>(param.member);
    setCharacterParameter(table, param.name, scalar ? "123.5" : "123.5,-7,9", "test", p);
    const P defaults;
    for (const auto& other : table) {
      if (const auto* f = std::get_if<float P::*>(&other.member)) {
        if (std::string(other.name) == param.name) EXPECT_EQ(p.*(*f), 123.5f) << param.name;
        else EXPECT_EQ(p.*(*f), defaults.*(*f)) << param.name << " changed " << other.name;
      } else {
        const auto v = std::get<glm::vec3 P::*>(other.member);
        if (std::string(other.name) == param.name) EXPECT_EQ(p.*v, glm::vec3(123.5f, -7, 9)) << param.name;
        else EXPECT_EQ(p.*v, defaults.*v) << param.name << " changed " << other.name;
      }
    }
  }
}

TEST(CharacterParams, EveryHorseNameSetsItsOwnField) { expectEachNameReachesItsOwnField(horseParameters()); }
TEST(CharacterParams, EveryRiderNameSetsItsOwnField) { expectEachNameReachesItsOwnField(riderParameters()); }

TEST(CharacterParams, BadValuesAreOneLineErrorsNamingTheParameter) {
  HorseParams h;
  EXPECT_EQ(errorOf([&] { setCharacterParameter(horseParameters(), "withers_height", "0", "make", h); }),
            "make: --withers_height: expected a number > 0, got \"0\"");
  EXPECT_EQ(errorOf([&] { setCharacterParameter(horseParameters(), "hips", "1,2", "make", h); }),
            "make: --hips: expected three numbers x,y,z, got \"1,2\"");
  EXPECT_EQ(errorOf([&] { setCharacterParameter(horseParameters(), "withers_height", "tall", "make", h); }),
            "make: --withers_height: expected a number, got \"tall\"");
  const std::string unknown = errorOf([&] { setCharacterParameter(horseParameters(), "wings", "1", "make", h); });
  EXPECT_EQ(unknown.rfind("make: --wings: unknown parameter (expected one of --withers_height", 0), 0u) << unknown;
}

}  // namespace
}  // namespace stirrup::rig
