// The characters' surface model behind one interface. A Material says a hit's base colour (the
// triangle's vertex colours interpolated, times whatever the material adds: a texture's colour at the
// hit's uv) and puts a hit's inputs into the surface lanes; the BRDF is the review look's (diffuse plus
// a small normalised Blinn-Phong lobe, Brdf). The lanes stay lanes behind it: the integrator gathers each
// hit through its triangle's material (Material::of), then Material::shadeLanes turns a batch's hits
// into surfaces (hitSurfaceLanes) and the BRDF is evaluated for a batch in shadingLanes
// (render/tracer/shading_lanes.h), operation for operation as the scalar members here.
//
// Two materials today: VertexColorMaterial (the colours alone) and TexturedMaterial (times the base
// colour texture, rig/texture.h). Adding one (leather, a metal bit) is a subclass here and, where it
// needs new BRDF terms, their lanes in shading_lanes.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/tracer/renderer.h"  // ObjectId
#include "render/tracer/shading_lanes.h"
#include "rig/texture.h"

namespace stirrup::render {

// What the integrator needs of a mesh: its id for the passes, and the per-vertex data Embree does
// not keep (Embree has the positions and the triangles).
struct ShadingMesh {
  ObjectId id = ObjectId::Horse;
  std::vector<uint32_t> indices;
  std::vector<glm::vec3> colors;
  std::vector<glm::vec3> normals;
  // Base colour textures, as MeshDesc's (all empty: untextured).
  std::vector<glm::vec2> uvs;
  std::vector<int32_t> triangle_textures;
  std::vector<std::shared_ptr<const rig::Texture>> textures;
};

// The BRDF of the review look: diffuse (1 - specular) albedo plus a Blinn-Phong lobe of weight
// `specular`, normalised for energy by (shininess + 8) / 8. The ground is matte (specular 0).
struct Brdf {
  float specular = 0.0f;
  int shininess = 1;
  float blinn_norm = 1.0f;  // (shininess + 8) / 8

  static Brdf blinnPhong(float specular, int shininess) {
    return {specular, shininess, float(shininess + 8) / 8.0f};
  }
  // What scales the diffuse light (the sky rays' sum): (1 - specular) albedo.
  glm::vec3 diffuse(const glm::vec3& albedo) const;
  // BRDF times cosine for light from wi (unit) seen from wo (unit), at shading normal n and geometric
  // normal ng; 0 from below either. As shadingLanes, operation for operation.
  glm::vec3 reflected(const glm::vec3& albedo, const glm::vec3& n, const glm::vec3& ng, const glm::vec3& wo,
                      const glm::vec3& wi) const;
  void toLanes(LaneConstants& k) const;
};

// A hit on a character's triangle: the mesh, the triangle and Embree's barycentrics.
struct MaterialHit {
  const ShadingMesh* mesh = nullptr;
  uint32_t prim = 0;
  float u = 0.0f, v = 0.0f;
};

class Material {
 public:
  virtual ~Material() = default;
  // The colour the material multiplies the interpolated vertex colours by at the hit (1: none).
  virtual glm::vec3 tint(const MaterialHit& hit) const = 0;

  // The hit's base colour: its triangle's vertex colours interpolated, times tint (as hitSurfaceLanes).
  glm::vec3 baseColor(const MaterialHit& hit) const;
  // The hit's inputs into the surface lanes at m: the triangle's vertex normals and colours, and tint.
  void gather(const MaterialHit& hit, SurfaceLanes& S, std::size_t m) const;

  // The material of a mesh's triangle: textured where the mesh gives the triangle a texture.
  static const Material& of(const ShadingMesh& mesh, uint32_t prim);
  // A batch's gathered hits (where `character` is set) into surfaces: point, normals, albedo,
  // specular weight, view depth (hitSurfaceLanes).
  static void shadeLanes(const LaneConstants& k, SurfaceLanes& S);
};

// The vertex (part) colours alone.
class VertexColorMaterial final : public Material {
 public:
  glm::vec3 tint(const MaterialHit&) const override { return glm::vec3(1.0f); }
};

// The vertex colours times the triangle's base colour texture at the hit's uv (interpolated as Embree's
// barycentrics say; a scalar lookup: the same bits on every SIMD target and thread).
class TexturedMaterial final : public Material {
 public:
  glm::vec3 tint(const MaterialHit& hit) const override;
};

}  // namespace stirrup::render
