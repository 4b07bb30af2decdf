// Reading posed world matrices in the posing tests (tests/rig/horse_pose_test.cpp, rider_pose_test.cpp,
// tack_pose_test.cpp, pose_test.cpp): a joint's place, a role's place, whether every matrix is finite.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"

namespace stirrup::rig::test {

inline glm::vec3 pos(const std::vector<glm::mat4>& w, int j) { return glm::vec3(w[j][3]); }
inline glm::vec3 at(const Character& c, const std::vector<glm::mat4>& w, const char* role) { return pos(w, c.role(role)); }
inline bool finite(const std::vector<glm::mat4>& w) {
  for (const glm::mat4& m : w)
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 4; ++k)
        if (!std::isfinite(m[i][k])) return false;
  return true;
}

}  // namespace stirrup::rig::test
