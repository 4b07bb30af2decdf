#include "rig/skeleton.h"

#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

glm::mat4 translate(glm::vec3 t) { return glm::translate(glm::mat4(1.0f), t); }

void expectNear(glm::vec3 a, glm::vec3 b, float tol = 1e-4f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Skeleton, InverseBindIsInverseOfRestWorld) {
  Skeleton s;
  const int a = s.addJoint("a", -1, translate({1, 2, 3}));
  const int b = s.addJoint("b", a, translate({0, 10, 0}) * glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0, 0, 1)));
  const int c = s.addJoint("c", b, translate({5, 0, 0}));
  const std::vector<glm::mat4> world = restWorlds(s);
  for (int j : {a, b, c}) {
    const glm::mat4 id = world[j] * s.joints[j].inverse_bind;
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row) EXPECT_NEAR(id[col][row], col == row ? 1.0f : 0.0f, 1e-5f);
  }
  expectNear(s.restPosition(b), {1, 12, 3});
  // c is 5 along b's rotated x axis.
  expectNear(s.restPosition(c), glm::vec3(1, 12, 3) + 5.0f * glm::vec3(std::cos(0.5f), std::sin(0.5f), 0));
}

TEST(Skeleton, LocalToWorldPropagatesParentMotion) {
  Skeleton s;
  const int a = s.addJoint("a", -1, glm::mat4(1.0f));
  const int b = s.addJoint("b", a, translate({10, 0, 0}));
  std::vector<glm::mat4> local = restLocals(s);
  local[a] = glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 1, 0));
  std::vector<glm::mat4> world(s.size());
  localToWorld(s, local, world);
  // Rotating the root 90 degrees about +Y takes +X to -Z.
  expectNear(glm::vec3(world[b][3]), {0, 0, -10});
}

TEST(Skeleton, FindRequireAndErrors) {
  Skeleton s;
  s.addJoint("root", -1, glm::mat4(1.0f));
  EXPECT_EQ(s.find("root"), 0);
  EXPECT_EQ(s.find("nope"), -1);
  EXPECT_THROW(s.require("nope"), std::out_of_range);
  EXPECT_THROW(s.addJoint("root", -1, glm::mat4(1.0f)), std::invalid_argument);
  EXPECT_THROW(s.addJoint("x", 5, glm::mat4(1.0f)), std::invalid_argument);
  std::vector<glm::mat4> local(1), world(2);
  EXPECT_THROW(localToWorld(s, local, world), std::invalid_argument);
}

}  // namespace
}  // namespace stirrup::rig
