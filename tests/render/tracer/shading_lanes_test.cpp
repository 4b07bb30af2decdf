// The shading kernels: the characters' hit surface, the sun test, the BRDF and the shadow and sky
// rays, against the scalar definitions they stand for (the integrator's full sun test, the sampling
// functions of render/tracer/lights.h bit for bit, the BRDF with the C library's pow), and against each other
// on every instruction set this CPU runs.
#include "render/tracer/shading_lanes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/tracer/integrator.h"
#include "render/tracer/lights.h"
#include "scene/camera.h"
#include "tests/render/test_meshes.h"

namespace stirrup::render {
namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct TargetPin {
  ~TargetPin() { pinSimdTarget("best"); }
};

// A sphere on the ground lit by a sun of 3 degrees: the integrator's constants for the kernels.
struct Lit {
  RenderSettings settings;
  testing::TestMesh sphere = testing::makeSphere({0.0f, 35.0f, 0.0f}, 30.0f, 16, 32, {0.6f, 0.35f, 0.2f});
  EmbreeScene scene;
  ShadingMesh mesh;
  std::vector<const ShadingMesh*> by_geometry;
  LaneConstants k;

  Lit() {
    settings.light_samples = 3;
    settings.ao_samples = 5;
    settings.sun_direction = {0.3, 0.8, 0.5};
    settings.sun_angular_radius_deg = 3.0;
    scene.setGround(settings.ground_half_extent_cm);
    const unsigned geometry = scene.addTriangleMesh(sphere.positions.size(), sphere.indices);
    scene.setVertices(geometry, sphere.positions);
    scene.commit();
    mesh.indices = sphere.indices, mesh.colors = sphere.colors, mesh.normals = sphere.normals;
    by_geometry.assign(geometry + 1, nullptr);
    by_geometry[geometry] = &mesh;
    scene::Camera camera;
    camera.position = {0.0, 120.0, 260.0};
    camera.target = {0.0, 60.0, 0.0};
    k = integrator().laneConstants(scene::CameraFrame(camera, 64, 36));
  }
  Integrator integrator() const { return Integrator(settings, scene, by_geometry); }
};

// Random surfaces: ground points (up normal, matte) and glossy points with random normals, with
// random sun and sky points.
SurfaceLanes randomSurfaces(const LaneConstants& k, std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-150.0f, 150.0f), far(-600.0f, 600.0f), height(0.0f, 90.0f), unit(-1.0f, 1.0f),
      u(0.0f, 0.99999994f), colour(0.02f, 0.9f);
  SurfaceLanes S;
  S.reserve(n, k.light_samples, k.ao_samples);
  for (std::size_t i = 0; i < n; ++i) {
    const bool ground = i % 3 == 0;
    glm::vec3 normal(0.0f, 1.0f, 0.0f);
    if (!ground) {
      do normal = {unit(rng), unit(rng), unit(rng)};
      while (glm::length(normal) < 0.2f || glm::length(normal) > 1.0f);
      normal = glm::normalize(normal);
    }
    glm::vec3 d = glm::normalize(glm::vec3(unit(rng), -0.5f + 0.4f * unit(rng), unit(rng)));
    if (glm::dot(d, normal) > 0.0f) d = glm::reflect(d, normal);  // seen from the normal's side
    S.character[i] = 0;
    S.on_ground[i] = ground ? -1 : 0;
    // Half the ground far from the sphere (open sky), the rest near it (in and out of its shadow).
    const bool distant = ground && i % 2 == 0;
    S.px[i] = distant ? far(rng) : coord(rng), S.py[i] = ground ? 0.0f : height(rng);
    S.pz[i] = distant ? far(rng) : coord(rng);
    S.ngx[i] = S.nx[i] = normal.x, S.ngy[i] = S.ny[i] = normal.y, S.ngz[i] = S.nz[i] = normal.z;
    S.dx[i] = d.x, S.dy[i] = d.y, S.dz[i] = d.z;
    S.ar[i] = colour(rng), S.ag[i] = colour(rng), S.ab[i] = colour(rng);
    S.specular[i] = ground ? 0.0f : k.specular;
    S.ground_y[i] = 0.0f;
    for (int s = 0; s < k.light_samples; ++s) S.sun_u[s * S.stride + i] = u(rng), S.sun_v[s * S.stride + i] = u(rng);
    for (int s = 0; s < k.ao_samples; ++s) S.sky_u[s * S.stride + i] = u(rng), S.sky_v[s * S.stride + i] = u(rng);
  }
  S.setSize(n);
  return S;
}

glm::vec3 at3(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z, std::size_t i) {
  return {x[i], y[i], z[i]};
}

TEST(ShadingLanes, TheSunTestIsTheIntegratorsFullTest) {
  Lit lit;
  const Integrator integrator = lit.integrator();
  SurfaceLanes S = randomSurfaces(lit.k, 3001, 3);
  shadingLanes(lit.k, S);
  int traced = 0, open = 0;
  for (std::size_t i = 0; i < S.size; ++i) {
    const glm::vec3 origin = at3(S.rox, S.roy, S.roz, i);
    const bool expected = S.on_ground[i] ? integrator.groundSunMayBeBlocked(origin) : integrator.sunMayBeBlocked(origin);
    ASSERT_EQ(S.sun_traced[i] != 0, expected) << i;
    (expected ? traced : open) += 1;
    // The origin is off the surface along the geometric normal, by more than the hit's rounding.
    const glm::vec3 p = at3(S.px, S.py, S.pz, i), ng = at3(S.ngx, S.ngy, S.ngz, i);
    EXPECT_NEAR(glm::dot(origin - p, ng), 2e-3f + 3e-5f * std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1e-4f);
  }
  EXPECT_GT(traced, 100);
  EXPECT_GT(open, 100);
}

TEST(ShadingLanes, SunRaysSampleTheDiscAndCarryTheBrdf) {
  Lit lit;
  const LaneConstants& k = lit.k;
  SurfaceLanes S = randomSurfaces(k, 2003, 5);
  shadingLanes(k, S);
  const Frame sun{k.sun_frame_x, k.sun_frame_y, k.sun_axis};
  int valid = 0, glossy = 0;
  for (std::size_t i = 0; i < S.size; ++i) {
    const glm::vec3 n = at3(S.nx, S.ny, S.nz, i), wo = -at3(S.dx, S.dy, S.dz, i), albedo = at3(S.ar, S.ag, S.ab, i);
    const float specular = S.specular[i];
    // The BRDF times cosine, from its definition with the C library's pow.
    auto brdf = [&](const glm::vec3& wi) {
      const float cos_n = glm::dot(n, wi);
      if (cos_n <= 0.0f) return glm::vec3(0.0f);
      const double lobe = specular > 0.0f ? specular * k.blinn_norm *
                                                std::pow(std::max(0.0, double(glm::dot(n, glm::normalize(wi + wo)))), 48.0)
                                          : 0.0;
      return glm::vec3((glm::dvec3(albedo) * (1.0 - specular) + lobe) * double(cos_n));
    };
    const glm::vec3 axis_light = brdf(k.sun_axis) * k.sun_radiance;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(at3(S.sun_r, S.sun_g, S.sun_b, i)[c], axis_light[c], 1e-5f * (1 + axis_light[c]));
    if (!S.sun_traced[i]) continue;
    for (int s = 0; s < k.light_samples; ++s) {
      const std::size_t at = s * S.stride + i;
      const glm::vec3 wi = at3(S.sun_wx, S.sun_wy, S.sun_wz, at);
      ASSERT_TRUE(sameBits(wi, sampleCone(sun, k.sun_cos_max, {S.sun_u[at], S.sun_v[at]}))) << i;
      const glm::vec3 f = at3(S.sun_fr, S.sun_fg, S.sun_fb, at), expected = brdf(wi);
      EXPECT_EQ(S.sun_valid[at] != 0, expected != glm::vec3(0.0f)) << i;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 1e-5f * (1 + expected[c])) << i;
      valid += S.sun_valid[at] != 0;
      glossy += S.sun_valid[at] != 0 && specular > 0.0f;
    }
  }
  EXPECT_GT(valid, 200);
  EXPECT_GT(glossy, 100);
}

TEST(ShadingLanes, SkyRaysAreCosineWeightedAndStopAboveTheGround) {
  Lit lit;
  const LaneConstants& k = lit.k;
  SurfaceLanes S = randomSurfaces(k, 2003, 7);
  shadingLanes(k, S);
  const SkyGradient sky{k.horizon, k.zenith, k.below};
  int down = 0, open_ground = 0;
  for (std::size_t i = 0; i < S.size; ++i) {
    const glm::vec3 origin = at3(S.rox, S.roy, S.roz, i), ng = at3(S.ngx, S.ngy, S.ngz, i);
    if (!S.sky_traced[i]) {  // only open ground far from the sphere's box sees the whole sky
      ASSERT_TRUE(S.on_ground[i]);
      const glm::vec3 e = glm::max(glm::max(k.box_lower - origin, origin - k.box_upper), glm::vec3(0.0f));
      EXPECT_GT(glm::length(e), k.ao_distance);
      ++open_ground;
      continue;
    }
    const Frame around = Frame::around(at3(S.nx, S.ny, S.nz, i));
    for (int s = 0; s < k.ao_samples; ++s) {
      const std::size_t at = s * S.stride + i;
      const glm::vec3 wi = at3(S.sky_wx, S.sky_wy, S.sky_wz, at);
      ASSERT_TRUE(sameBits(wi, sampleCosineHemisphere(around, {S.sky_u[at], S.sky_v[at]}))) << i;
      EXPECT_EQ(S.sky_valid[at] != 0, glm::dot(ng, wi) > 0.0f);
      const glm::vec3 light = at3(S.sky_lr, S.sky_lg, S.sky_lb, at);
      if (!S.on_ground[i] && wi.y < 0.0f) {
        // A character's downward ray: the lit ground's bounce, ending just short of the ground.
        EXPECT_EQ(light, k.ground_bounce);
        const float end = origin.y + S.sky_t_far[at] * wi.y;
        EXPECT_NEAR(end, 0.999f * origin.y < k.ao_distance * -wi.y ? 0.001f * origin.y : origin.y + k.ao_distance * wi.y,
                    1e-3f + 1e-5f * origin.y);
        ++down;
      } else {
        EXPECT_EQ(S.sky_t_far[at], k.ao_distance);
        const glm::vec3 expected = sky.radiance(wi);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(light[c], expected[c], 1e-6f);
      }
    }
  }
  EXPECT_GT(down, 100);
  EXPECT_GT(open_ground, 100);
}

TEST(ShadingLanes, AHitSurfaceIsItsTrianglesInterpolation) {
  LaneConstants k;
  k.specular = 0.04f;
  k.forward = {0.0f, 0.0f, -1.0f};
  SurfaceLanes S;
  const std::size_t n = 37;
  S.reserve(n, 1, 1);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> b(0.0f, 0.5f), unit(-1.0f, 1.0f);
  for (std::size_t i = 0; i < n; ++i) {
    S.character[i] = -1;
    S.ox[i] = 1.0f, S.oy[i] = 50.0f, S.oz[i] = 300.0f, S.t[i] = 250.0f + float(i);
    const glm::vec3 d = glm::normalize(glm::vec3(0.1f * unit(rng), -0.1f, -1.0f));
    S.dx[i] = d.x, S.dy[i] = d.y, S.dz[i] = d.z;
    // Embree's normal, unnormalised and on the far side half the time.
    const float side = i % 2 ? 3.0f : -2.0f;
    S.gx[i] = 0.0f, S.gy[i] = 0.0f, S.gz[i] = side;
    S.u[i] = b(rng), S.v[i] = b(rng);
    const glm::vec3 n0 = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)), n1 = glm::normalize(glm::vec3(-0.3f, 0.2f, 1.0f)),
                    n2 = glm::normalize(glm::vec3(0.0f, -0.3f, 1.0f));
    S.n0x[i] = n0.x, S.n0y[i] = n0.y, S.n0z[i] = n0.z, S.n1x[i] = n1.x, S.n1y[i] = n1.y, S.n1z[i] = n1.z;
    S.n2x[i] = n2.x, S.n2y[i] = n2.y, S.n2z[i] = n2.z;
    S.c0r[i] = 1.0f, S.c0g[i] = 0.0f, S.c0b[i] = 0.0f, S.c1r[i] = 0.0f, S.c1g[i] = 1.0f, S.c1b[i] = 0.0f;
    S.c2r[i] = 0.0f, S.c2g[i] = 0.0f, S.c2b[i] = 1.0f;
    // Every third hit is on a textured triangle: its colour is scaled by the texture's there.
    if (i % 3 == 0) S.tr[i] = 0.5f, S.tg[i] = 0.25f, S.tb[i] = 2.0f;
  }
  // The last one is a silhouette: its interpolated normal faces away from the camera.
  S.n0x[n - 1] = S.n1x[n - 1] = S.n2x[n - 1] = 1.0f;
  S.n0z[n - 1] = S.n1z[n - 1] = S.n2z[n - 1] = 0.0f;
  S.n0y[n - 1] = S.n1y[n - 1] = S.n2y[n - 1] = 0.0f;
  S.dx[n - 1] = 0.5f, S.dy[n - 1] = 0.0f, S.dz[n - 1] = -std::sqrt(0.75f);
  S.setSize(n);
  hitSurfaceLanes(k, S);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 d(S.dx[i], S.dy[i], S.dz[i]);
    const glm::vec3 p = glm::vec3(S.ox[i], S.oy[i], S.oz[i]) + S.t[i] * d;
    EXPECT_TRUE(sameBits(at3(S.px, S.py, S.pz, i), p)) << i;
    // The geometric normal: unit, facing the camera whichever side Embree gave.
    EXPECT_EQ(at3(S.ngx, S.ngy, S.ngz, i), glm::vec3(0.0f, 0.0f, 1.0f)) << i;
    const float b1 = S.u[i], b2 = S.v[i], b0 = 1.0f - b1 - b2;
    const glm::vec3 albedo = at3(S.ar, S.ag, S.ab, i);
    const glm::vec3 texture = i % 3 == 0 ? glm::vec3(0.5f, 0.25f, 2.0f) : glm::vec3(1.0f);
    EXPECT_NEAR(albedo.x, b0 * texture.x, 1e-6f);
    EXPECT_NEAR(albedo.y, b1 * texture.y, 1e-6f);
    EXPECT_NEAR(albedo.z, b2 * texture.z, 1e-6f);
    EXPECT_EQ(S.specular[i], 0.04f);
    EXPECT_NEAR(S.depth[i], glm::dot(p, k.forward), 1e-4f);
    const glm::vec3 shading = at3(S.nx, S.ny, S.nz, i);
    EXPECT_NEAR(glm::length(shading), 1.0f, 1e-6f);
    if (i + 1 < n) {
      const glm::vec3 expected = glm::normalize(b0 * glm::vec3(S.n0x[i], S.n0y[i], S.n0z[i]) +
                                                b1 * glm::vec3(S.n1x[i], S.n1y[i], S.n1z[i]) +
                                                b2 * glm::vec3(S.n2x[i], S.n2y[i], S.n2z[i]));
      EXPECT_NEAR(glm::length(shading - expected), 0.0f, 1e-6f) << i;
    } else {
      // Tilted toward the camera by just enough to face it (0.01, then made unit).
      EXPECT_GT(glm::dot(shading, -d), 0.0099f);
      EXPECT_LT(glm::dot(shading, -d), 0.02f);
    }
  }
}

// Every shadow and sky ray Embree finds blocked by the sphere is listed for Embree (the box test
// only ever leaves out rays that miss), the lists ascend, and each surface's light from the rays left
// open is the scalar sum the integrator made ray by ray, to the bit, on every target.
TEST(ShadingLanes, TheListedRaysHoldEveryBlockedOneAndTheLightSumsTheOpenOnes) {
  TargetPin restore;
  Lit lit;
  std::vector<float> first_radiance;
  std::vector<int32_t> first_lists;
  for (const std::string& target : simdTargets()) {
    pinSimdTarget(target);
    SurfaceLanes S = randomSurfaces(lit.k, 1999, 29);
    for (std::size_t i = 0; i < S.size; ++i) S.haze[i] = i % 4 == 0 ? 0.25f + 0.001f * float(i % 500) : 1.0f;
    shadingLanes(lit.k, S);
    std::vector<int32_t> sun_list(S.sun_valid.size() + CameraLanes::kPad), sky_list(S.sky_valid.size() + CameraLanes::kPad);
    const OccluderCounts counts = occluderLanes(lit.k, S, sun_list.data(), sky_list.data());
    sun_list.resize(counts.sun), sky_list.resize(counts.sky);
    EXPECT_TRUE(std::is_sorted(sun_list.begin(), sun_list.end()) && std::is_sorted(sky_list.begin(), sky_list.end()));
    std::size_t made = 0, blocked_rays = 0;
    auto check = [&](bool sky, const std::vector<int32_t>& list, std::vector<int32_t>& open, std::size_t rays_a_surface) {
      for (std::size_t i = 0; i < S.size; ++i) {
        const bool traced = sky ? S.sky_traced[i] != 0 : S.sun_traced[i] != 0;
        for (std::size_t r = 0, at = i; r < rays_a_surface; ++r, at += S.stride) {
          const bool valid = traced && (sky ? S.sky_valid[at] : S.sun_valid[at]) != 0;
          ASSERT_EQ(open[at] != 0, valid) << "ray " << at;
          const float t_far = sky ? S.sky_t_far[at] : std::numeric_limits<float>::infinity();
          if (!valid || !(t_far > 0.0f)) continue;
          ++made;
          RTCRay ray{};
          ray.org_x = S.rox[i], ray.org_y = S.roy[i], ray.org_z = S.roz[i];
          ray.dir_x = sky ? S.sky_wx[at] : S.sun_wx[at], ray.dir_y = sky ? S.sky_wy[at] : S.sun_wy[at];
          ray.dir_z = sky ? S.sky_wz[at] : S.sun_wz[at];
          ray.tfar = t_far, ray.mask = 0xffffffffu;
          RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          rtcOccluded1(lit.scene.characters(), &context, &ray);
          if (!(ray.tfar < 0.0f)) continue;
          ++blocked_rays;
          EXPECT_TRUE(std::binary_search(list.begin(), list.end(), int32_t(at))) << target << ": blocked ray " << at;
          open[at] = 0;  // as the integrator clears it
        }
      }
    };
    check(false, sun_list, S.sun_open, std::size_t(lit.k.light_samples));
    check(true, sky_list, S.sky_open, std::size_t(lit.k.ao_samples));
    EXPECT_EQ(counts.made, made);
    EXPECT_GT(blocked_rays, 100u);  // the sphere shades a good part of the surfaces
    EXPECT_LT(counts.sun + counts.sky, made);  // and the box leaves out rays that pass beside it
    surfaceRadianceLanes(lit.k, S);
    const glm::vec3 sun_scale = lit.k.sun_radiance / float(lit.k.light_samples);
    for (std::size_t i = 0; i < S.size; ++i) {
      glm::vec3 sun = at3(S.sun_r, S.sun_g, S.sun_b, i), sky = at3(S.sky_r, S.sky_g, S.sky_b, i);
      if (S.sun_traced[i]) {
        sun = glm::vec3(0.0f);
        for (std::size_t r = 0, at = i; r < std::size_t(lit.k.light_samples); ++r, at += S.stride)
          if (S.sun_valid[at] && S.sun_open[at]) sun += at3(S.sun_fr, S.sun_fg, S.sun_fb, at);
        sun *= sun_scale;
      }
      if (S.sky_traced[i]) {
        sky = glm::vec3(0.0f);
        for (std::size_t r = 0, at = i; r < std::size_t(lit.k.ao_samples); ++r, at += S.stride)
          if (S.sky_valid[at] && S.sky_open[at]) sky += at3(S.sky_lr, S.sky_lg, S.sky_lb, at);
        sky *= at3(S.diffuse_r, S.diffuse_g, S.diffuse_b, i) / float(lit.k.ao_samples);
      }
      glm::vec3 radiance = sun + sky;
      if (S.haze[i] < 1.0f) radiance = radiance * S.haze[i] + lit.k.horizon * (1.0f - S.haze[i]);
      ASSERT_TRUE(sameBits(at3(S.radiance_r, S.radiance_g, S.radiance_b, i), radiance)) << target << ", surface " << i;
    }
    std::vector<float> radiance(S.radiance_r.begin(), S.radiance_r.begin() + std::ptrdiff_t(S.size));
    std::vector<int32_t> lists = sun_list;
    lists.insert(lists.end(), sky_list.begin(), sky_list.end());
    if (first_radiance.empty()) {
      first_radiance = radiance, first_lists = lists;
      continue;
    }
    EXPECT_EQ(lists, first_lists) << target;
    EXPECT_EQ(std::memcmp(radiance.data(), first_radiance.data(), radiance.size() * sizeof(float)), 0) << target;
  }
}

TEST(ShadingLanes, EveryDispatchTargetGivesTheSameBits) {
  const std::vector<std::string> targets = simdTargets();
  ASSERT_FALSE(targets.empty());
  if (targets.size() < 2) GTEST_SKIP() << "this CPU runs one SIMD target only: " << targets.front();
  TargetPin restore;
  Lit lit;
  std::vector<std::vector<float>> first;
  for (const std::string& target : targets) {
    pinSimdTarget(target);
    SurfaceLanes S = randomSurfaces(lit.k, 1999, 13);
    shadingLanes(lit.k, S);
    std::vector<std::vector<float>> all = {S.rox, S.roz, S.diffuse_g, S.sun_r, S.sky_b, S.sun_wx, S.sun_wz, S.sun_fr,
                                           S.sun_fb, S.sky_wx, S.sky_wy, S.sky_t_far, S.sky_lg};
    // The outputs: per surface, and per ray where its surface traces it (a kernel skips a vector of
    // surfaces none of which trace, and a vector's width differs by target).
    for (auto& v : all) v.resize(v.size() == S.stride ? S.size : v.size());
    std::vector<float> masks;
    for (std::size_t i = 0; i < S.size; ++i) masks.push_back(float(S.sun_traced[i]) + 2.0f * float(S.sky_traced[i]));
    for (std::size_t at = 0; at < S.sun_valid.size(); ++at) {
      const std::size_t i = at % S.stride;
      const bool traced = i < S.size && S.sun_traced[i];
      masks.push_back(traced ? float(S.sun_valid[at]) : 0.0f);
      for (std::vector<float>* v : {&all[5], &all[6], &all[7], &all[8]}) (*v)[at] = traced ? (*v)[at] : 0.0f;
    }
    for (std::size_t at = 0; at < S.sky_valid.size(); ++at) {
      const std::size_t i = at % S.stride;
      const bool traced = i < S.size && S.sky_traced[i];
      masks.push_back(traced ? float(S.sky_valid[at]) : 0.0f);
      for (std::vector<float>* v : {&all[9], &all[10], &all[11], &all[12]}) (*v)[at] = traced ? (*v)[at] : 0.0f;
    }
    all.push_back(masks);
    if (first.empty()) {
      first = all;
      continue;
    }
    for (std::size_t a = 0; a < all.size(); ++a) {
      ASSERT_EQ(all[a].size(), first[a].size());
      EXPECT_EQ(std::memcmp(all[a].data(), first[a].data(), all[a].size() * sizeof(float)), 0)
          << target << " against " << targets.front() << ", array " << a;
    }
  }
}

}  // namespace
}  // namespace stirrup::render
