// The default horse (rig/characters/horse_character.cpp): every role its header lists, each joint at
// the place its parameter gives (left legs as given, right legs mirrored in z), the stirrups hung from
// the seat by the mount, and a mesh standing on the ground. The mesh's quality (closed, outward,
// finite) is tested with the implicit bodies (implicit_body_test.cpp).
#include "rig/characters/horse_character.h"

#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "tests/rig/default_characters.h"
#include "tests/rig/tack_labels.h"

namespace stirrup::rig {
namespace {

using test::defaultHorse;

void expectAt(const Character& c, const std::string& role, glm::vec3 want) {
  const glm::vec3 p = c.skeleton.restPosition(c.role(role));
  EXPECT_NEAR(p.x, want.x, 1e-4f) << role;
  EXPECT_NEAR(p.y, want.y, 1e-4f) << role;
  EXPECT_NEAR(p.z, want.z, 1e-4f) << role;
}

TEST(HorseCharacter, HasEveryRoleItsHeaderLists) {
  const Character& h = defaultHorse();
  for (const char* role : {"root", "backMid", "chest", "withers", "neck1", "neck2", "head", "saddle", "lStirrup",
                           "rStirrup", "tail1", "tail2", "tail3", "lRein", "rRein"})
    EXPECT_NO_THROW(h.role(role)) << role;
  for (const char* leg : {"lf", "rf", "lb", "rb"})
    for (const char* part : {"Pivot", "Upper", "Middle", "Fetlock", "Hoof"})
      EXPECT_NO_THROW(h.role(std::string(leg) + part)) << leg << part;
}

// HorseParams' defaults (horse_character.h): fore scapula (40, 138), elbow (45, 94), knee (52, 54),
// fetlock (48, 20), hoof (52, 0) at z = -13; hind hip (-62, 124), stifle (-44, 96), hock (-78, 52),
// fetlock (-72, 20), hoof (-69, 0) at z = -14; the root at the hips (-60, 128, 0), backMid (-8, 128, 0).
TEST(HorseCharacter, JointsStandWhereTheParametersPutThem) {
  const Character& h = defaultHorse();
  expectAt(h, "root", {-60, 128, 0});
  expectAt(h, "backMid", {-8, 128, 0});
  expectAt(h, "lfPivot", {40, 138, -13});
  expectAt(h, "lfUpper", {45, 94, -13});
  expectAt(h, "lfMiddle", {52, 54, -13});
  expectAt(h, "lfFetlock", {48, 20, -13});
  expectAt(h, "lfHoof", {52, 0, -13});
  expectAt(h, "rfHoof", {52, 0, 13});
  expectAt(h, "lbPivot", {-62, 124, -14});
  expectAt(h, "lbUpper", {-44, 96, -14});
  expectAt(h, "lbMiddle", {-78, 52, -14});
  expectAt(h, "lbFetlock", {-72, 20, -14});
  expectAt(h, "lbHoof", {-69, 0, -14});
  expectAt(h, "rbHoof", {-69, 0, 14});
  expectAt(h, "rbMiddle", {-78, 52, 14});
}

// MountParams: the left tread 74 cm below the seat centre and 31 cm to the left; the right mirrored.
TEST(HorseCharacter, TheStirrupsHangFromTheSeatByTheMount) {
  const Character& h = defaultHorse();
  const glm::vec3 seat = h.skeleton.restPosition(h.role("saddle"));
  expectAt(h, "lStirrup", seat + glm::vec3(0, -74, -31));
  expectAt(h, "rStirrup", seat + glm::vec3(0, -74, 31));
  EXPECT_EQ(h.skeleton.joints[std::size_t(h.role("lStirrup"))].parent, h.role("saddle"));
}

// Hooves on the ground at y = 0 (a hoof's sole a little below its ground-contact joint at most), ears
// below 2 m, nose ahead of the muzzle joint at x = 140, about 240 cm nose to tail.
TEST(HorseCharacter, TheMeshStandsOnTheGround) {
  const Character& h = defaultHorse();
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : h.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  EXPECT_GT(lo.y, -2.0f);
  EXPECT_LT(lo.y, 1.0f);
  EXPECT_GT(hi.y, 174.0f);  // the poll is at 174 cm, the ears above it
  EXPECT_LT(hi.y, 200.0f);
  EXPECT_GT(hi.x, 140.0f);
  EXPECT_NEAR(hi.x - lo.x, 240.0f, 30.0f);
  EXPECT_NEAR(hi.z, -lo.z, 1.0f);  // left and right alike
}

// The tack is labelled part by part, by the piece that made each vertex's surface (the shape that gives it
// its colour, or the tube): every vertex of a tack colour is tack and no tack vertex has the coat's, each
// part has its colours and joints and the stirrups their sides; the horse built bare has no tack labels.
TEST(HorseCharacter, TheTackIsLabelledPartByPart) {
  const Character& h = defaultHorse();
  test::expectTackLabelsFit(h);
  const HorseParams p;
  std::size_t tack_coloured = 0, labelled = 0;
  for (std::size_t v = 0; v < h.mesh.vertexCount(); ++v) {
    const glm::vec3 c = h.mesh.colors[v];
    tack_coloured += c == p.leather || c == p.pad || c == p.metal;
    labelled += h.mesh.tackPart(v) != TackPart::None;
  }
  EXPECT_EQ(labelled, tack_coloured);
  // The saddle (seat, pommel, cantle) on top, the pad's flaps and girth below it down the barrel.
  float saddle_low = 1e9f, pad_low = 1e9f;
  for (std::size_t v = 0; v < h.mesh.vertexCount(); ++v) {
    if (h.mesh.tackPart(v) == TackPart::Saddle) saddle_low = std::min(saddle_low, h.mesh.positions[v].y);
    if (h.mesh.tackPart(v) == TackPart::SaddlePad) pad_low = std::min(pad_low, h.mesh.positions[v].y);
  }
  const float seat = h.skeleton.restPosition(h.role("saddle")).y;
  EXPECT_GT(saddle_low, seat - 15.0f);
  EXPECT_LT(pad_low, seat - 40.0f) << "the girth runs under the barrel";
  HorseParams bare;
  bare.tack = false;
  EXPECT_TRUE(buildHorse(bare).mesh.tack_parts.empty());
}

}  // namespace
}  // namespace stirrup::rig
