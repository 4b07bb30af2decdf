// Comparing vectors in tests, component by component, so a failure says which one is off.
#pragma once

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

namespace stirrup::test {

inline void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tol = 1e-6) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace stirrup::test
