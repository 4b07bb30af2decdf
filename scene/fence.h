// The fence a jump clip clears (rig::Obstacle), as a mesh the renderer can stand in the scene: a
// show-jumping vertical — two white wing posts and three poles painted in red and white bands — so the
// take-off, the bascule and the landing read against something solid, as in the thesis's jump movies.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/clip.h"

namespace stirrup::scene {

// A rigid mesh in world centimetres: positions, unit normals and linear base colours per vertex,
// three indices per triangle, counter-clockwise seen from outside.
struct PropMesh {
  std::vector<glm::vec3> positions, normals, colors;
  std::vector<uint32_t> indices;
};

struct FenceStyle {
  double pole_radius_cm = 5.0;
  double band_cm = 40.0;           // length of each painted band on the poles
  double post_half_cm = 6.0;       // half the width of a square wing post
  double post_above_cm = 35.0;     // how far the posts stand above the top pole
  int pole_sides = 16;
  glm::vec3 white{0.78f, 0.78f, 0.75f};
  glm::vec3 red{0.55f, 0.06f, 0.05f};
};

// The fence standing at world x = `x_cm` (its centre line), across the travel direction (along Z,
// centred on z = 0), its top pole's top at obstacle.height_cm. Poles at the top, two thirds and one
// third of the height. Throws std::invalid_argument for a height or width <= 0.
PropMesh makeFence(const rig::Obstacle& obstacle, double x_cm, const FenceStyle& style = {});

}  // namespace stirrup::scene
