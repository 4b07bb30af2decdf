#include "rig/character.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stirrup::rig {

float Character::LegGuard::widthNear(float x, float y) const {
  float w = -std::numeric_limits<float>::infinity();
  if (empty()) return w;
  const int cx = static_cast<int>(std::floor((x - x0) / cell_cm)), cy = static_cast<int>(std::floor((y - y0) / cell_cm));
  for (int j = std::max(cy - 1, 0); j <= std::min(cy + 1, ny - 1); ++j)
    for (int i = std::max(cx - 1, 0); i <= std::min(cx + 1, nx - 1); ++i) w = std::max(w, half_width[std::size_t(j) * nx + i]);
  return w;
}

}  // namespace stirrup::rig
