// Organic bodies as a signed distance field: a smooth union (polynomial smooth-min) of tapered
// capsules and ellipsoids, each attached to a joint and carrying a colour. Polygonised with naive
// Surface Nets (no tables: one vertex per surface cell, one quad per sign-changing grid edge), with
// normals from the field's gradient, colour from the nearest primitive and skin weights from the
// distance to each joint's primitives.
#pragma once

#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "rig/mesh.h"

namespace stirrup::rig {

struct ImplicitPrimitive {
  enum class Shape { TaperedCapsule, Ellipsoid };
  Shape shape = Shape::TaperedCapsule;
  // Tapered capsule: segment a -> b, radius ra at a and rb at b (a round cone).
  glm::vec3 a{0.0f}, b{0.0f};
  float ra = 1.0f, rb = 1.0f;
  // Ellipsoid: centre, semi-axes along the columns of axes (orthonormal).
  glm::vec3 center{0.0f};
  glm::vec3 radii{1.0f};
  glm::mat3 axes{1.0f};
  // Optional axis-aligned clip box (bind-pose world): the shape is intersected with it, for flat
  // hoof soles and for saddle flaps cut from a shell around the barrel.
  glm::vec3 clip_min{-std::numeric_limits<float>::infinity()};
  glm::vec3 clip_max{std::numeric_limits<float>::infinity()};
  float clip_round = 0.0f;  // cm: rounds the cut edges (smooth intersection) so they don't alias on the grid
  // How softly this primitive merges into what was added before it (cm); ~0 keeps a crisp seam.
  float blend = 2.0f;
  int joint = 0;
  glm::vec3 color{0.5f};
  // Primitives that only shape the surface (a fillet) but should not colour it or pull weights.
  bool paints = true;
  // The part of a horse's tack it makes (None: the body). Each vertex takes the part of the primitive
  // that gives it its colour (SkinnedMesh::tack_parts), so the part's surface is the one painted so.
  TackPart tack_part = TackPart::None;
};

ImplicitPrimitive taperedCapsule(glm::vec3 a, glm::vec3 b, float ra, float rb, int joint,
                                 glm::vec3 color, float blend = 2.0f);
// An ellipsoid whose first axis points along `forward` (second axis kept near world up).
ImplicitPrimitive ellipsoid(glm::vec3 center, glm::vec3 radii, int joint, glm::vec3 color,
                            float blend = 2.0f, glm::vec3 forward = {1.0f, 0.0f, 0.0f});

struct ImplicitBody {
  std::vector<ImplicitPrimitive> primitives;  // unioned in order

  void add(const ImplicitPrimitive& p) { primitives.push_back(p); }
  // Signed distance (cm, negative inside), approximately Euclidean near the surface.
  float distance(glm::vec3 p) const;
  glm::vec3 gradient(glm::vec3 p, float h = 0.05f) const;
  // Bounds of the primitives (conservative), bind pose.
  void bounds(glm::vec3& lo, glm::vec3& hi) const;
};

struct PolygonizeParams {
  float cell = 1.5f;          // grid spacing, cm: sets the triangle count (about area / cell^2 * 2.6)
  float skin_falloff = 2.5f;  // cm: how far past the nearest joint's primitives a weight fades by 1/e
  int project_steps = 1;      // Newton steps pulling each vertex onto the zero set
};

SkinnedMesh polygonize(const ImplicitBody& body, const PolygonizeParams& params);

// Distance from p to one primitive (negative inside), clip box included.
float primitiveDistance(const ImplicitPrimitive& prim, glm::vec3 p);
// Polynomial smooth minimum: equals min(a, b) when |a - b| >= k, rounds the crease otherwise.
float smoothMin(float a, float b, float k);

}  // namespace stirrup::rig
