// Images for the layering tests: a solid image, and a pixel's colour checked channel by channel.
#pragma once

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "render/tracer/image.h"

namespace stirrup::render {

inline Image solid(int w, int h, glm::vec4 c) {
  Image img(w, h);
  for (glm::vec4& p : img.rgba) p = c;
  return img;
}

inline void expectRgb(const Image& img, int x, int y, glm::vec3 want, float tol = 1e-5f) {
  const glm::vec4 p = img.at(x, y);
  EXPECT_NEAR(p.x, want.x, tol) << "R at " << x << "," << y;
  EXPECT_NEAR(p.y, want.y, tol) << "G at " << x << "," << y;
  EXPECT_NEAR(p.z, want.z, tol) << "B at " << x << "," << y;
}

}  // namespace stirrup::render
