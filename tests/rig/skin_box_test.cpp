#include "rig/skin_box.h"

#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/skin.h"

namespace stirrup::rig {
namespace {

// The box as every vertex gives it: the min and max of skinPositions at stride 1.
void everyVertexBox(const Character& c, const std::vector<glm::mat4>& world, glm::vec3& lo, glm::vec3& hi) {
  std::vector<glm::vec3> all;
  skinPositions(c.mesh, c.skeleton, world, 1, all);
  lo = glm::vec3(std::numeric_limits<float>::infinity());
  hi = glm::vec3(-std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : all) lo = glm::min(lo, p), hi = glm::max(hi, p);
}

// Poses of a character: the bind pose; every third joint bent 20 degrees (vertices blend across the
// bends); the same far out in the world and turned (a crowd's pair 90 m along its path, where a
// float's step is 1/128 cm); and every joint turned and moved at random (the mesh torn apart).
std::vector<std::vector<glm::mat4>> poses(const Skeleton& skeleton) {
  std::vector<std::vector<glm::mat4>> out;
  std::vector<glm::mat4> world = restWorlds(skeleton);
  out.push_back(world);
  for (std::size_t j = 1; j < world.size(); j += 3)
    world[j] = world[j] * glm::rotate(glm::mat4(1.0f), glm::radians(20.0f), glm::normalize(glm::vec3(1, 2, 3)));
  out.push_back(world);
  const glm::mat4 far = glm::translate(glm::mat4(1.0f), glm::vec3(9137.25f, -213.5f, -4711.0f)) *
                        glm::rotate(glm::mat4(1.0f), glm::radians(-37.0f), glm::vec3(0, 1, 0));
  for (glm::mat4& m : world) m = far * m;
  out.push_back(world);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> angle(-180.0f, 180.0f), move(-50.0f, 50.0f);
  for (glm::mat4& m : world)
    m = glm::translate(glm::mat4(1.0f), glm::vec3(move(random), move(random), move(random))) * m *
        glm::rotate(glm::mat4(1.0f), glm::radians(angle(random)), glm::normalize(glm::vec3(move(random), 1.0f, 2.0f)));
  out.push_back(world);
  return out;
}

// The box is every vertex's, to the bit, for the generated horse and rider at full detail and at a
// crowd's coarsest cell, in every pose; in the pose of a rider (not torn apart) far fewer vertices are
// skinned than the mesh has.
TEST(SkinBox, IsEveryVertexsBoxToTheBitSkinningFewOfThem) {
  for (float cell : {1.0f, 4.0f}) {  // full detail and a crowd's coarsest level (4 times the cell)
    HorseParams hp;
    hp.cell *= cell;
    RiderParams rp;
    rp.cell *= cell;
    const Character horse = buildHorse(hp);
    const Character rider = buildRider(rp, hp.mount);
    for (const Character* c : {&horse, &rider}) {
      const SkinBoxIndex index(c->mesh);
      EXPECT_GT(index.clusterCount(), 1u);
      const std::vector<std::vector<glm::mat4>> all = poses(c->skeleton);
      for (std::size_t k = 0; k < all.size(); ++k) {
        glm::vec3 lo, hi;
        everyVertexBox(*c, all[k], lo, hi);
        const SkinnedBox box = index.box(c->mesh, c->skeleton, all[k]);
        EXPECT_EQ(box.lo, lo) << "cell " << cell << " pose " << k;
        EXPECT_EQ(box.hi, hi) << "cell " << cell << " pose " << k;
        EXPECT_LE(box.skinned, c->mesh.vertexCount());
        if (k < 3) {
          EXPECT_LT(box.skinned, c->mesh.vertexCount() / 3) << "cell " << cell << " pose " << k;
        }
      }
    }
  }
}

TEST(SkinBox, RejectsAnotherMeshAndAWrongPose) {
  HorseParams hp;
  hp.cell = 6.4f;
  const Character horse = buildHorse(hp);
  const SkinBoxIndex index(horse.mesh);
  std::vector<glm::mat4> world = restWorlds(horse.skeleton);
  SkinnedMesh other = horse.mesh;
  other.positions.pop_back();
  EXPECT_THROW(index.box(other, horse.skeleton, world), std::logic_error);
  world.pop_back();
  EXPECT_THROW(index.box(horse.mesh, horse.skeleton, world), std::invalid_argument);
}

}  // namespace
}  // namespace stirrup::rig
