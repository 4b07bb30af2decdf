// A character's lookups (rig/character.cpp): joints by role, and the leg guard's table of the horse's
// half-width, read over a cell and its neighbours.
#include "rig/character.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// A 3 x 2 table of 2 cm cells from (0, 0): row y in [0, 2) holds 1 2 3, row y in [2, 4) holds 4 5 6.
Character::LegGuard table() {
  Character::LegGuard g;
  g.cell_cm = 2.0f;
  g.nx = 3;
  g.ny = 2;
  g.half_width = {1, 2, 3, 4, 5, 6};
  return g;
}

TEST(Character, LegGuardTakesTheWidestOfACellAndItsNeighbours) {
  const Character::LegGuard g = table();
  EXPECT_EQ(g.widthNear(0.5f, 0.5f), 5.0f);  // cell (0, 0): cells (0..1, 0..1) hold 1 2 4 5
  EXPECT_EQ(g.widthNear(5.0f, 1.0f), 6.0f);  // cell (2, 0): cells (1..2, 0..1) hold 2 3 5 6
  EXPECT_EQ(g.widthNear(-1.0f, 0.0f), 4.0f);  // cell (-1, 0), beside the table: only its neighbour column 0, 1 and 4
  Character::LegGuard far = table();
  far.x0 = 100.0f;  // the table moved 100 cm forward: (0.5, 0.5) is 50 cells behind it
  EXPECT_TRUE(std::isinf(far.widthNear(0.5f, 0.5f)));
  EXPECT_LT(far.widthNear(0.5f, 0.5f), 0.0f);
  EXPECT_EQ(far.widthNear(101.0f, 3.0f), 5.0f);  // cell (0, 1): cells (0..1, 0..1) hold 1 2 4 5
  Character::LegGuard none;
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(std::isinf(none.widthNear(0.0f, 0.0f)));
  EXPECT_FALSE(g.empty());
}

TEST(Character, RolesNameJointsAndAMissingRoleSaysWhich) {
  Character c;
  c.name = "pony";
  c.skeleton.addJoint("root", -1, glm::mat4(1.0f));
  c.skeleton.addJoint("seat", 0, glm::mat4(1.0f));
  c.roles = {{"saddle", 1}};
  EXPECT_EQ(c.role("saddle"), 1);
  try {
    c.role("lStirrup");
    FAIL() << "expected std::out_of_range";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "character pony: no role lStirrup");
  }
}

}  // namespace
}  // namespace stirrup::rig
