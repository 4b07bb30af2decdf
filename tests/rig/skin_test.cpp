#include "rig/skin.h"

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"

namespace stirrup::rig {
namespace {

Skeleton twoJoints() {
  Skeleton s;
  const int a = s.addJoint("a", -1, glm::translate(glm::mat4(1.0f), glm::vec3(0, 10, 0)));
  s.addJoint("b", a, glm::translate(glm::mat4(1.0f), glm::vec3(20, 0, 0)));
  return s;
}

SkinnedMesh oneVertex(glm::vec3 p, glm::vec3 n, glm::u16vec4 joints, glm::vec4 weights) {
  SkinnedMesh m;
  m.positions = {p};
  m.normals = {n};
  m.colors = {glm::vec3(1)};
  m.joints = {joints};
  m.weights = {weights};
  return m;
}

TEST(Skin, VertexBoundToOneJointFollowsItExactly) {
  const Skeleton s = twoJoints();
  const SkinnedMesh m = oneVertex({25, 12, 3}, glm::normalize(glm::vec3(0, 1, 1)), {1, 0, 0, 0}, {1, 0, 0, 0});
  std::vector<glm::mat4> world = restWorlds(s);
  world[1] = glm::translate(glm::mat4(1.0f), glm::vec3(5, -7, 40)) *
             glm::rotate(glm::mat4(1.0f), glm::radians(70.0f), glm::normalize(glm::vec3(1, 2, 3)));
  std::vector<glm::vec3> p, n;
  skinMesh(m, s, world, p, n);
  const glm::mat4 motion = world[1] * s.joints[1].inverse_bind;
  const glm::vec3 expected = glm::vec3(motion * glm::vec4(m.positions[0], 1.0f));
  const glm::vec3 expected_n = glm::normalize(glm::mat3(motion) * m.normals[0]);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NEAR(glm::length(p[0] - expected), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::length(n[0] - expected_n), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(n[0]), 1.0f, 1e-5f);
}

TEST(Skin, RestPoseLeavesTheMeshUnchangedAndBlendsAreLinear) {
  const Skeleton s = twoJoints();
  const SkinnedMesh m = oneVertex({10, 10, 0}, {0, 1, 0}, {0, 1, 0, 0}, {0.25f, 0.75f, 0, 0});
  std::vector<glm::mat4> world = restWorlds(s);
  std::vector<glm::vec3> p, n;
  skinMesh(m, s, world, p, n);
  EXPECT_NEAR(glm::length(p[0] - m.positions[0]), 0.0f, 1e-4f);
  // Translating only joint b by 8 moves a 75 % b vertex by 6.
  world[1] = glm::translate(glm::mat4(1.0f), glm::vec3(0, 8, 0)) * world[1];
  skinMesh(m, s, world, p, n);
  EXPECT_NEAR(p[0].y - m.positions[0].y, 6.0f, 1e-4f);
}

TEST(Skin, RejectsWrongJointCount) {
  const Skeleton s = twoJoints();
  const SkinnedMesh m = oneVertex({0, 0, 0}, {0, 1, 0}, {0, 0, 0, 0}, {1, 0, 0, 0});
  std::vector<glm::mat4> world(1);
  std::vector<glm::vec3> p, n;
  EXPECT_THROW(skinMesh(m, s, world, p, n), std::invalid_argument);
}

void expectValidWeights(const Character& c) {
  const SkinnedMesh& m = c.mesh;
  ASSERT_EQ(m.joints.size(), m.vertexCount());
  ASSERT_EQ(m.weights.size(), m.vertexCount());
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    float sum = 0.0f;
    int influences = 0;
    for (int i = 0; i < 4; ++i) {
      ASSERT_GE(m.weights[v][i], 0.0f);
      ASSERT_LT(m.joints[v][i], c.skeleton.size());
      sum += m.weights[v][i];
      influences += m.weights[v][i] > 0.0f;
    }
    ASSERT_NEAR(sum, 1.0f, 1e-4f) << c.name << " vertex " << v;
    ASSERT_GE(influences, 1);
    ASSERT_LE(influences, kMaxInfluences);
  }
}

TEST(Skin, DefaultCharactersHaveNormalisedWeightsOfAtMostFourJoints) {
  expectValidWeights(buildDefaultHorse());
  expectValidWeights(buildDefaultRider());
}

// skinPositions places every stride-th vertex where skinMesh does, to the bit (framing a view reads
// them instead of the whole skin): the built horse, posed with a bent joint so vertices blend.
TEST(Skin, PositionsAloneAreSkinMeshsEveryStrideThVertex) {
  const Character horse = buildHorse(HorseParams{});
  std::vector<glm::mat4> world = restWorlds(horse.skeleton);
  for (std::size_t j = 1; j < world.size(); j += 3)
    world[j] = world[j] * glm::rotate(glm::mat4(1.0f), glm::radians(20.0f), glm::normalize(glm::vec3(1, 2, 3)));
  std::vector<glm::vec3> all, normals;
  skinMesh(horse.mesh, horse.skeleton, world, all, normals);
  for (int stride : {1, 3, 7}) {
    std::vector<glm::vec3> some;
    skinPositions(horse.mesh, horse.skeleton, world, stride, some);
    ASSERT_EQ(some.size(), (all.size() + std::size_t(stride) - 1) / std::size_t(stride)) << stride;
    for (std::size_t k = 0; k < some.size(); ++k) ASSERT_EQ(some[k], all[k * std::size_t(stride)]) << stride << " " << k;
  }
  std::vector<glm::vec3> none;
  EXPECT_THROW(skinPositions(horse.mesh, horse.skeleton, world, 0, none), std::invalid_argument);
  world.pop_back();
  EXPECT_THROW(skinPositions(horse.mesh, horse.skeleton, world, 3, none), std::invalid_argument);
}

// skinMesh runs vertices a SIMD vector at a time (Highway, the best target of this CPU): every vertex
// must come out to the bit as skinVertex, glm's scalar reference, makes it, or frames would differ
// between machines and from the goldens. The built horse and rider posed with bent joints (so vertices
// blend), and a mesh of odd cases: weights of zero and below (skipped), a degenerate blend (the normal
// kept), a vertex count that is no multiple of any vector's lanes.
TEST(Skin, EveryVertexIsTheScalarReferencesToTheBit) {
  auto expectReference = [](const SkinnedMesh& mesh, const Skeleton& skeleton, const std::vector<glm::mat4>& world,
                            const char* what) {
    std::vector<glm::vec3> p, n;
    skinMesh(mesh, skeleton, world, p, n);
    const std::vector<glm::mat4> m = skinningMatrices(skeleton, world);
    ASSERT_EQ(p.size(), mesh.positions.size()) << what;
    std::size_t blended = 0;
    for (std::size_t v = 0; v < p.size(); ++v) {
      glm::vec3 rp, rn;
      skinVertex(mesh, m.data(), v, rp, rn);
      ASSERT_EQ(std::memcmp(&rp, &p[v], sizeof rp), 0) << what << " vertex " << v << " position";
      ASSERT_EQ(std::memcmp(&rn, &n[v], sizeof rn), 0) << what << " vertex " << v << " normal";
      blended += mesh.weights[v][1] > 0.0f;
    }
    EXPECT_GT(blended, 0u) << what << ": no vertex blends two joints";
  };
  // Every SIMD target this CPU runs (Highway's dispatch, pinned one at a time), then the best again.
  struct Unpin {
    ~Unpin() { hwy::SetSupportedTargetsForTest(0); }
  } unpin;
  const std::vector<Character> characters = {buildHorse(HorseParams{}), buildDefaultRider()};
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    for (std::size_t k = 0; k < characters.size(); ++k) {
      const Character& c = characters[k];
      std::vector<glm::mat4> world = restWorlds(c.skeleton);
      for (std::size_t j = 1; j < world.size(); j += 2)
        world[j] = world[j] * glm::rotate(glm::mat4(1.0f), glm::radians(17.0f + float(j)), glm::normalize(glm::vec3(1, 2, 3)));
      world[0] = glm::scale(world[0], glm::vec3(1.0f, 1.3f, 0.9f));  // non-uniform: the inverse transpose matters
      expectReference(c.mesh, c.skeleton, world, k == 0 ? "horse" : "rider");
    }
  }
  hwy::SetSupportedTargetsForTest(0);
  const Skeleton s = twoJoints();
  SkinnedMesh odd;
  for (int v = 0; v < 37; ++v) {
    const float a = float(v);
    odd.positions.push_back({a, 2.0f * a - 5.0f, 0.5f * a});
    odd.normals.push_back(glm::normalize(glm::vec3(1.0f, a, 2.0f)));
    odd.colors.push_back(glm::vec3(1));
    odd.joints.push_back(glm::u16vec4(v % 2, 1 - v % 2, 0, 1));
    const float w = float(v % 5) / 4.0f;
    odd.weights.push_back(v % 7 == 3 ? glm::vec4(1.0f, 0.0f, -0.5f, 0.0f) : glm::vec4(w, 1.0f - w, 0.0f, 0.0f));
  }
  std::vector<glm::mat4> world = restWorlds(s);
  world[1] = world[1] * glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0, 0, 1));
  expectReference(odd, s, world, "odd cases");
  world[1] = glm::scale(world[1], glm::vec3(0.0f));  // joint b flattened to a point: degenerate blends
  expectReference(odd, s, world, "odd cases, a joint scaled to nothing");
}

}  // namespace
}  // namespace stirrup::rig
