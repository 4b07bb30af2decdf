// The characters' materials behind their one interface: the vertex colours alone, a texture's texel
// times them, which triangle gets which, what a hit puts into the surface lanes, the lanes' albedo bit
// for bit as the scalar base colour, and the BRDF's terms.
#include "render/tracer/material.h"

#include <cmath>
#include <cstring>
#include <memory>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Two triangles of one quad; the second textured by a 2 x 2 image (nearest texels), the first not.
ShadingMesh quad() {
  ShadingMesh mesh;
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.colors = {{1.0f, 0.5f, 0.25f}, {0.5f, 1.0f, 0.5f}, {0.25f, 0.5f, 1.0f}, {0.8f, 0.8f, 0.8f}};
  mesh.normals = {{0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f}};
  mesh.uvs = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.75f, 0.75f}, {0.25f, 0.75f}};
  mesh.triangle_textures = {-1, 0};
  auto texture = std::make_shared<rig::Texture>();
  texture->width = texture->height = 2;
  texture->filter = rig::TextureFilter::Nearest;
  // Row-major from the top-left: (0, 0) leather brown, (1, 0) red, (0, 1) green, (1, 1) blue.
  texture->texels = {{0.4f, 0.25f, 0.1f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
  mesh.textures = {texture};
  return mesh;
}

TEST(Material, TheFlatMaterialIsTheVertexColours) {
  const ShadingMesh mesh = quad();
  const Material& flat = Material::of(mesh, 0);
  EXPECT_NE(dynamic_cast<const VertexColorMaterial*>(&flat), nullptr);
  EXPECT_EQ(flat.tint({&mesh, 0, 0.3f, 0.3f}), glm::vec3(1.0f));
  EXPECT_EQ(flat.baseColor({&mesh, 0, 0.0f, 0.0f}), mesh.colors[0]);
  EXPECT_EQ(flat.baseColor({&mesh, 0, 1.0f, 0.0f}), mesh.colors[1]);
  EXPECT_EQ(flat.baseColor({&mesh, 0, 0.0f, 1.0f}), mesh.colors[2]);
  const glm::vec3 middle = flat.baseColor({&mesh, 0, 0.5f, 0.5f});  // between vertices 1 and 2
  EXPECT_FLOAT_EQ(middle.x, 0.375f);
  EXPECT_FLOAT_EQ(middle.y, 0.75f);
  EXPECT_FLOAT_EQ(middle.z, 0.75f);
}

TEST(Material, ATexturedMaterialReturnsTheTexelTimesTheVertexColours) {
  const ShadingMesh mesh = quad();
  const Material& textured = Material::of(mesh, 1);
  EXPECT_NE(dynamic_cast<const TexturedMaterial*>(&textured), nullptr);
  // Triangle 1 is vertices 0, 2, 3: at each vertex its uv's texel.
  EXPECT_EQ(textured.tint({&mesh, 1, 0.0f, 0.0f}), glm::vec3(0.4f, 0.25f, 0.1f));  // uv (0.25, 0.25)
  EXPECT_EQ(textured.tint({&mesh, 1, 1.0f, 0.0f}), glm::vec3(0.0f, 0.0f, 1.0f));   // uv (0.75, 0.75)
  EXPECT_EQ(textured.tint({&mesh, 1, 0.0f, 1.0f}), glm::vec3(0.0f, 1.0f, 0.0f));   // uv (0.25, 0.75)
  EXPECT_EQ(textured.baseColor({&mesh, 1, 0.0f, 0.0f}), mesh.colors[0] * glm::vec3(0.4f, 0.25f, 0.1f));
  EXPECT_EQ(textured.baseColor({&mesh, 1, 0.0f, 1.0f}), glm::vec3(0.0f, 0.8f, 0.0f));
  // A mesh with no textures at all is flat everywhere.
  ShadingMesh plain = quad();
  plain.triangle_textures.clear();
  EXPECT_NE(dynamic_cast<const VertexColorMaterial*>(&Material::of(plain, 1)), nullptr);
}

// A hit gathered into the surface lanes, shaded there: the lanes' albedo is the scalar base colour, bit
// for bit, for both materials.
TEST(Material, TheLanesAlbedoIsTheBaseColourBitForBit) {
  const ShadingMesh mesh = quad();
  const MaterialHit hits[] = {{&mesh, 0, 0.2f, 0.3f}, {&mesh, 1, 0.1f, 0.7f}, {&mesh, 1, 0.6f, 0.3f},
                              {&mesh, 0, 0.0f, 0.0f}};
  SurfaceLanes S;
  S.reserve(4, 1, 1);
  S.setSize(4);
  for (std::size_t m = 0; m < 4; ++m) {
    const MaterialHit& hit = hits[m];
    S.character[m] = -1;
    S.ox[m] = 0.0f, S.oy[m] = 100.0f, S.oz[m] = 0.0f;
    S.dx[m] = 0.0f, S.dy[m] = -1.0f, S.dz[m] = 0.0f, S.t[m] = 100.0f;
    S.gx[m] = 0.0f, S.gy[m] = 2.0f, S.gz[m] = 0.0f;
    S.u[m] = hit.u, S.v[m] = hit.v;
    Material::of(mesh, hit.prim).gather(hit, S, m);
  }
  EXPECT_EQ(S.tr[0], 1.0f);  // untextured: the colours as they are
  EXPECT_EQ(glm::vec3(S.tr[1], S.tg[1], S.tb[1]), Material::of(mesh, 1).tint(hits[1]));
  LaneConstants k;
  Brdf::blinnPhong(0.04f, 48).toLanes(k);
  Material::shadeLanes(k, S);
  for (std::size_t m = 0; m < 4; ++m) {
    const glm::vec3 albedo(S.ar[m], S.ag[m], S.ab[m]);
    EXPECT_TRUE(sameBits(albedo, Material::of(mesh, hits[m].prim).baseColor(hits[m]))) << "hit " << m;
    EXPECT_EQ(S.specular[m], 0.04f);
    EXPECT_NEAR(glm::length(glm::vec3(S.nx[m], S.ny[m], S.nz[m])), 1.0f, 1e-5f);
  }
}

TEST(Material, TheBrdfIsDiffusePlusANormalisedLobe) {
  const Brdf brdf = Brdf::blinnPhong(0.04f, 48);
  EXPECT_EQ(brdf.blinn_norm, 7.0f);
  const glm::vec3 albedo(0.6f, 0.4f, 0.2f), up(0.0f, 1.0f, 0.0f);
  EXPECT_EQ(brdf.diffuse(albedo), (1.0f - 0.04f) * albedo);
  // Light from below the surface brings nothing.
  EXPECT_EQ(brdf.reflected(albedo, up, up, up, -up), glm::vec3(0.0f));
  // Seen along the mirror direction the lobe adds its peak, specular * (n + 8) / 8; far from it, nothing.
  const glm::vec3 wi = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)), mirror = glm::normalize(glm::vec3(-1.0f, 1.0f, 0.0f));
  const glm::vec3 glint = brdf.reflected(albedo, up, up, mirror, wi);
  const float cos_n = wi.y;
  EXPECT_NEAR(glint.x, (0.96f * albedo.x + 0.04f * 7.0f) * cos_n, 1e-5f);
  const glm::vec3 dull = brdf.reflected(albedo, up, up, glm::normalize(glm::vec3(1.0f, 0.2f, 0.0f)), wi);
  EXPECT_NEAR(dull.x, 0.96f * albedo.x * cos_n, 1e-5f);
  // Matte (the ground): albedo times cosine.
  EXPECT_NEAR(Brdf{}.reflected(albedo, up, up, mirror, wi).y, albedo.y * cos_n, 1e-6f);
}

}  // namespace
}  // namespace stirrup::render
