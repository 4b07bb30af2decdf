#include "rig/characters/palette.h"

#include <set>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// Each list's first name is the default characters' own colour, so a pair naming none looks as before.
TEST(Palette, TheFirstNamesAreTheDefaultCharactersColours) {
  const HorseParams h;
  const RiderParams r;
  EXPECT_STREQ(horseCoats().front().name, "bay");
  EXPECT_EQ(horseCoats().front().coat, h.coat);
  EXPECT_EQ(horseCoats().front().points, h.points);
  EXPECT_EQ(riderJackets().front().color, r.coat);
  EXPECT_EQ(riderHair().front().color, r.hair);
  EXPECT_EQ(riderSkins().front().color, r.skin);
}

// Names are unique within a list, colours are linear RGB in [0, 1], and no two entries of a list are
// the same colour (each name must look different).
TEST(Palette, NamesAreUniqueAndColoursDistinct) {
  const auto check = [](const std::vector<NamedColor>& list) {
    std::set<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
      EXPECT_TRUE(names.insert(list[i].name).second) << list[i].name;
      for (int c = 0; c < 3; ++c) EXPECT_TRUE(list[i].color[c] >= 0.0f && list[i].color[c] <= 1.0f) << list[i].name;
      for (std::size_t j = 0; j < i; ++j) EXPECT_NE(list[i].color, list[j].color) << list[i].name << " " << list[j].name;
    }
  };
  check(riderJackets());
  check(riderHair());
  check(riderSkins());
  std::set<std::string> coats;
  for (const HorseCoat& c : horseCoats()) EXPECT_TRUE(coats.insert(c.name).second) << c.name;
  EXPECT_GE(horseCoats().size(), 5u);
  EXPECT_GE(riderJackets().size(), 5u);
}

TEST(Palette, AppliesNamedColoursAndRefusesUnknownOnes) {
  HorseParams h;
  applyHorseCoat("grey", h);
  EXPECT_EQ(h.coat, findHorseCoat("grey")->coat);
  EXPECT_EQ(h.points, findHorseCoat("grey")->points);
  RiderParams r;
  applyRiderColors("navy", "blonde", "dark", r);
  EXPECT_EQ(r.coat, findNamedColor(riderJackets(), "navy")->color);
  EXPECT_EQ(r.hair, findNamedColor(riderHair(), "blonde")->color);
  EXPECT_EQ(r.skin, findNamedColor(riderSkins(), "dark")->color);
  EXPECT_EQ(r.thigh, RiderParams{}.thigh);  // colours only
  EXPECT_EQ(findHorseCoat("pink"), nullptr);
  EXPECT_THROW(applyHorseCoat("pink", h), std::invalid_argument);
  EXPECT_THROW(applyRiderColors("navy", "green", "dark", r), std::invalid_argument);
  EXPECT_EQ(paletteNames(riderHair()), "brown, black, blonde, auburn, grey");
}

}  // namespace
}  // namespace stirrup::rig
