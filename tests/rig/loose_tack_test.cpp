// rig/loose_tack.h: which of a horse's vertices are tack that hangs free or is held. Hand-built meshes:
// the expected flags follow from which triangles join which vertices and which joints bind them.
#include <gtest/gtest.h>

#include "rig/loose_tack.h"

namespace stirrup::rig {
namespace {

// Joints: 0 body, 1 saddle, 2 left stirrup, 3 left rein. Three pieces, two triangles each:
//   piece A (vertices 0-3): the body, bound to joint 0;
//   piece B (vertices 4-7): an iron, only vertex 6 bound to the stirrup joint (the rest to the saddle);
//   piece C (vertices 8-11): the rein, vertex 11 bound half to the rein joint, half to the body.
Character threePieces() {
  Character c;
  c.name = "three pieces";
  for (int v = 0; v < 12; ++v) {
    c.mesh.positions.push_back({float(v), 0.0f, 0.0f});
    c.mesh.joints.push_back({0, 0, 0, 0});
    c.mesh.weights.push_back({1.0f, 0.0f, 0.0f, 0.0f});
  }
  for (std::uint32_t p = 0; p < 3; ++p) {
    const std::uint32_t b = p * 4;
    c.mesh.indices.insert(c.mesh.indices.end(), {b, b + 1, b + 2, b + 1, b + 3, b + 2});
  }
  for (int v = 4; v < 8; ++v) c.mesh.joints[v] = {1, 0, 0, 0};
  c.mesh.joints[6] = {2, 0, 0, 0};
  c.mesh.joints[11] = {0, 3, 0, 0};
  c.mesh.weights[11] = {0.5f, 0.5f, 0.0f, 0.0f};
  c.roles = {{"saddle", 1}, {"lStirrup", 2}, {"lRein", 3}};
  return c;
}

TEST(LooseTack, APieceWithOneVertexOnAStirrupOrReinJointIsLooseWhole) {
  const std::vector<bool> loose = horseLooseTack(threePieces());
  ASSERT_EQ(loose.size(), 12u);
  for (int v = 0; v < 4; ++v) EXPECT_FALSE(loose[v]) << "body vertex " << v;
  for (int v = 4; v < 12; ++v) EXPECT_TRUE(loose[v]) << "tack vertex " << v;
}

TEST(LooseTack, AnInfluenceOfWeightZeroDoesNotCount) {
  Character c = threePieces();
  c.mesh.weights[11] = {1.0f, 0.0f, 0.0f, 0.0f};  // joint 3 listed but weighted 0
  const std::vector<bool> loose = horseLooseTack(c);
  for (int v = 8; v < 12; ++v) EXPECT_FALSE(loose[v]) << "rein vertex " << v;
  for (int v = 4; v < 8; ++v) EXPECT_TRUE(loose[v]) << "iron vertex " << v;
}

TEST(LooseTack, ATackRoleOnTheSaddlesOwnJointIsNotLoose) {
  // A horse whose file binds its stirrups to the saddle joint: the saddle is not loose tack.
  Character c = threePieces();
  c.roles["lStirrup"] = 1;
  const std::vector<bool> loose = horseLooseTack(c);
  for (int v = 4; v < 8; ++v) EXPECT_FALSE(loose[v]) << "iron vertex " << v;
  for (int v = 8; v < 12; ++v) EXPECT_TRUE(loose[v]) << "rein vertex " << v;
}

TEST(LooseTack, AHorseWithoutTackRolesHasNone) {
  Character c = threePieces();
  c.roles = {{"saddle", 1}};
  const std::vector<bool> loose = horseLooseTack(c);
  ASSERT_EQ(loose.size(), 12u);
  for (int v = 0; v < 12; ++v) EXPECT_FALSE(loose[v]) << "vertex " << v;
}

}  // namespace
}  // namespace stirrup::rig
