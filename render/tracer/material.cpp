#include "render/tracer/material.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/tracer/lights.h"

namespace stirrup::render {
namespace {

const VertexColorMaterial kVertexColor;
const TexturedMaterial kTextured;

}  // namespace

glm::vec3 Brdf::diffuse(const glm::vec3& albedo) const { return (1.0f - specular) * albedo; }

glm::vec3 Brdf::reflected(const glm::vec3& albedo, const glm::vec3& n, const glm::vec3& ng, const glm::vec3& wo,
                          const glm::vec3& wi) const {
  const float cos_n = glm::dot(n, wi);
  if (cos_n <= 0.0f || glm::dot(ng, wi) <= 0.0f) return glm::vec3(0.0f);
  glm::vec3 f = diffuse(albedo);
  if (specular > 0.0f) {
    const glm::vec3 h = wi + wo;
    const float cos_h = std::max(0.0f, glm::dot(n, h * (1.0f / std::sqrt(glm::dot(h, h)))));
    f += (specular * blinn_norm) * powWhole(cos_h, shininess);
  }
  return cos_n * f;
}

void Brdf::toLanes(LaneConstants& k) const {
  k.specular = specular, k.blinn_norm = blinn_norm, k.shininess = shininess;
}

glm::vec3 Material::baseColor(const MaterialHit& hit) const {
  const ShadingMesh& mesh = *hit.mesh;
  const uint32_t* tri = &mesh.indices[std::size_t(hit.prim) * 3];
  const float b1 = hit.u, b2 = hit.v, b0 = 1.0f - b1 - b2;
  const glm::vec3 color = b0 * mesh.colors[tri[0]] + b1 * mesh.colors[tri[1]] + b2 * mesh.colors[tri[2]];
  return color * tint(hit);
}

void Material::gather(const MaterialHit& hit, SurfaceLanes& S, std::size_t m) const {
  const ShadingMesh& mesh = *hit.mesh;
  const uint32_t* tri = &mesh.indices[std::size_t(hit.prim) * 3];
  const glm::vec3 &n0 = mesh.normals[tri[0]], &n1 = mesh.normals[tri[1]], &n2 = mesh.normals[tri[2]];
  S.n0x[m] = n0.x, S.n0y[m] = n0.y, S.n0z[m] = n0.z, S.n1x[m] = n1.x, S.n1y[m] = n1.y, S.n1z[m] = n1.z;
  S.n2x[m] = n2.x, S.n2y[m] = n2.y, S.n2z[m] = n2.z;
  const glm::vec3 &c0 = mesh.colors[tri[0]], &c1 = mesh.colors[tri[1]], &c2 = mesh.colors[tri[2]];
  S.c0r[m] = c0.x, S.c0g[m] = c0.y, S.c0b[m] = c0.z, S.c1r[m] = c1.x, S.c1g[m] = c1.y, S.c1b[m] = c1.z;
  S.c2r[m] = c2.x, S.c2g[m] = c2.y, S.c2b[m] = c2.z;
  const glm::vec3 t = tint(hit);
  S.tr[m] = t.x, S.tg[m] = t.y, S.tb[m] = t.z;
}

const Material& Material::of(const ShadingMesh& mesh, uint32_t prim) {
  if (!mesh.triangle_textures.empty() && mesh.triangle_textures[std::size_t(prim)] >= 0) return kTextured;
  return kVertexColor;
}

void Material::shadeLanes(const LaneConstants& k, SurfaceLanes& S) { hitSurfaceLanes(k, S); }

glm::vec3 TexturedMaterial::tint(const MaterialHit& hit) const {
  const ShadingMesh& mesh = *hit.mesh;
  const int32_t k = mesh.triangle_textures[std::size_t(hit.prim)];
  const uint32_t* tri = &mesh.indices[std::size_t(hit.prim) * 3];
  const float b1 = hit.u, b2 = hit.v, b0 = 1.0f - b1 - b2;
  const glm::vec2 uv = b0 * mesh.uvs[tri[0]] + b1 * mesh.uvs[tri[1]] + b2 * mesh.uvs[tri[2]];
  return mesh.textures[std::size_t(k)]->sample(uv);
}

}  // namespace stirrup::render
