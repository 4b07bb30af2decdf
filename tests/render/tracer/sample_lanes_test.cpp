// The SIMD kernels against the scalar expressions they stand for, bit for bit, and against each other
// on every instruction set this CPU runs.
#include "render/tracer/sample_lanes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <embree3/rtcore.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/tracer/integrator.h"
#include "render/tracer/lights.h"
#include "scene/camera.h"
#include "tests/render/tracer/steep_hills.h"

namespace stirrup::render {
namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Pins the kernels to each target in turn and back to the best when it goes out of scope.
struct TargetPin {
  ~TargetPin() { pinSimdTarget("best"); }
};

TEST(SampleLanes, TheCheckerMatchesTheScalarFilterBitForBit) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-4000.0f, 4000.0f), w(0.0f, 1.4f);
  const std::size_t n = 20011;  // not a multiple of any vector: the tail is covered too
  std::vector<float> s(n), t(n), width(n), out(n);
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = coord(rng), t[i] = coord(rng);
    width[i] = i % 7 == 0 ? 0.0f : (i % 11 == 0 ? 0.25f : (i % 13 == 0 ? 1.0f : w(rng)));
  }
  filteredCheckerLanes(s.data(), t.data(), width.data(), out.data(), n);
  int differing = 0;
  for (std::size_t i = 0; i < n; ++i) differing += !sameBits(out[i], filteredChecker(s[i], t[i], width[i]));
  EXPECT_EQ(differing, 0);
}

TEST(SampleLanes, TheCheckerHasNoContrastBelowAPixel) {
  // A footprint of 1.5 squares: a box filter alone still shows a third of the contrast (0.33 to 0.67
  // along a row); the fade leaves the mean.
  for (float s = 0.0f; s < 4.0f; s += 0.01f) EXPECT_EQ(filteredChecker(s, 0.3f, 1.5f), 0.5f);
  // Between four footprints a square and one, the contrast falls smoothly: never above the box's own.
  float previous = 1.0f;
  for (int step = 0; step <= 15; ++step) {
    const float width = step == 15 ? 1.0f : 0.25f + 0.05f * float(step);
    float lo = 1.0f, hi = 0.0f;
    for (float s = 0.0f; s < 2.0f; s += 0.005f) {
      const float v = filteredChecker(s, 0.5f, width);
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    EXPECT_LE(hi - lo, previous + 1e-6f) << "width " << width;
    previous = hi - lo;
  }
  EXPECT_LT(previous, 1e-5f);
}

// The tent filter's inverse CDF (as sample_lanes.cpp states it), for the expected rays.
float tent(float u) { return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(2.0f - 2.0f * u); }

LaneConstants constantsFor(const scene::CameraFrame& frame) {
  LaneConstants k;
  frame.laneView(k.perspective, k.pixel_dx, k.pixel_dy, k.half_width, k.half_height, k.footprint_at_0,
                 k.footprint_per_cm);
  k.position = frame.positionF(), k.forward = frame.forwardF(), k.right = frame.rightF(), k.up = frame.upF();
  k.target_distance = frame.targetDistanceF();
  k.ground_extent = 100000.0f;
  k.t_visible = 60000.0f;
  k.box_lower = {-50.0f, 0.0f, -80.0f}, k.box_upper = {50.0f, 250.0f, 80.0f};
  k.box_empty = false;
  return k;
}

CameraLanes randomSamples(std::size_t n, int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 0.99999994f);
  CameraLanes lanes;
  lanes.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    lanes.ux[i] = u(rng), lanes.uy[i] = u(rng);
    lanes.cx[i] = float(int(u(rng) * float(width))) + 0.5f, lanes.cy[i] = float(int(u(rng) * float(height))) + 0.5f;
  }
  return lanes;
}

scene::Camera sideCamera(scene::Camera::Projection projection) {
  scene::Camera c;
  c.projection = projection;
  c.position = {40.0, 220.0, 900.0};
  c.target = {0.0, 110.0, 0.0};
  c.fov_deg = 27.0;
  c.ortho_height_cm = 320.0;
  return c;
}

TEST(SampleLanes, CameraRaysAreTheCameraFramesRays) {
  for (scene::Camera::Projection projection : {scene::Camera::Projection::Perspective, scene::Camera::Projection::Orthographic}) {
    const scene::CameraFrame frame(sideCamera(projection), 640, 360);
    const LaneConstants k = constantsFor(frame);
    CameraLanes lanes = randomSamples(3001, 640, 360, 9);
    cameraRayLanes(k, lanes, true);
    int differing = 0, ground = 0, may_hit = 0;
    for (std::size_t i = 0; i < lanes.size; ++i) {
      glm::vec3 o, d;
      frame.rayFromPixel(lanes.cx[i] + tent(lanes.ux[i]), lanes.cy[i] + tent(lanes.uy[i]), o, d);
      differing += !(sameBits(o.x, lanes.ox[i]) && sameBits(o.y, lanes.oy[i]) && sameBits(o.z, lanes.oz[i]) &&
                     sameBits(d.x, lanes.dx[i]) && sameBits(d.y, lanes.dy[i]) && sameBits(d.z, lanes.dz[i]));
      // The plane: where the ray meets y = 0 in front of the camera, and nowhere else.
      const float t = -o.y / d.y;
      if (d.y < 0.0f && t < k.t_visible) {
        ++ground;
        EXPECT_TRUE(sameBits(lanes.t_ground[i], t)) << i;
      } else {
        EXPECT_TRUE(std::isinf(lanes.t_ground[i])) << i;
      }
      // The box test is conservative: a ray that meets the box (in doubles, before the ground) is kept.
      const glm::dvec3 od(o), dd(d);
      double t0 = 0.0, t1 = std::isinf(lanes.t_ground[i]) ? 1e30 : double(lanes.t_ground[i]);
      for (int a = 0; a < 3; ++a) {
        double n0 = (double(k.box_lower[a]) - od[a]) / dd[a], f0 = (double(k.box_upper[a]) - od[a]) / dd[a];
        if (n0 > f0) std::swap(n0, f0);
        t0 = std::max(t0, n0), t1 = std::min(t1, f0);
      }
      if (t0 < t1 - 1e-3) {
        EXPECT_NE(lanes.may_hit[i], 0) << i;
      }
      if (t0 > t1 + 1.0) {
        EXPECT_EQ(lanes.may_hit[i], 0) << i;
      }
      may_hit += lanes.may_hit[i] != 0;
    }
    EXPECT_EQ(differing, 0);
    EXPECT_GT(ground, 100);  // the frames hold ground and the box (and sky, in perspective)
    EXPECT_GT(may_hit, 100);
    if (projection == scene::Camera::Projection::Perspective) {
      EXPECT_LT(ground, int(lanes.size));
    }
  }
}

// Open ground's light from the lanes is the scalar shading's: (albedo cos) sun + albedo sky, hazed.
TEST(SampleLanes, OpenGroundIsLitAsTheScalarShadingLightsIt) {
  const scene::CameraFrame frame(sideCamera(scene::Camera::Projection::Perspective), 640, 360);
  LaneConstants k = constantsFor(frame);
  RenderSettings settings;
  k.color_a = settings.ground_color_a, k.color_b = settings.ground_color_b;
  k.square_cm = settings.ground_square_cm;
  k.haze_visibility = settings.haze.visibility_cm;
  k.horizon = settings.sky.horizon;
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
  k.sun_y = sun.y;
  k.sun_radiance = settings.sun_color * settings.sun_strength;
  k.sky_irradiance = settings.sky.upwardIrradianceOverPi();
  k.sun_region = true;
  k.sun_lower_x = -300.0f, k.sun_upper_x = 300.0f, k.sun_lower_z = -300.0f, k.sun_upper_z = 300.0f;
  k.ao_distance = 300.0f;
  CameraLanes lanes = randomSamples(4000, 640, 360, 3);
  cameraRayLanes(k, lanes, true);
  lanes.t_shade = lanes.t_ground;
  groundLanes(k, lanes);
  int open = 0, differing = 0;
  for (std::size_t i = 0; i < lanes.size; ++i) {
    if (std::isinf(lanes.t_shade[i])) continue;
    const float t = lanes.t_shade[i];
    const glm::vec3 p(lanes.ox[i] + t * lanes.dx[i], 0.0f, lanes.oz[i] + t * lanes.dz[i]);
    const float width = frame.pixelFootprintF(t) / std::max(std::abs(lanes.dy[i]), 0.02f) / k.square_cm;
    const glm::vec3 albedo = glm::mix(k.color_a, k.color_b, filteredChecker(p.x / k.square_cm, p.z / k.square_cm, width));
    const float haze = AerialPerspective::perspective(t, k.haze_visibility);
    differing += !(sameBits(albedo.x, lanes.albedo_r[i]) && sameBits(albedo.z, lanes.albedo_b[i]) &&
                   sameBits(haze, lanes.haze[i]) && sameBits(frame.viewDepthF(p), lanes.depth[i]));
    const bool outside = p.x < -300.0f || p.x > 300.0f || p.z < -300.0f || p.z > 300.0f;
    const glm::vec3 to_box = glm::max(glm::max(k.box_lower - p, p - k.box_upper), glm::vec3(0.0f));
    const bool expect_open = outside && glm::length(to_box) > 300.5f;  // (the origin is lifted a little)
    if (expect_open) {
      EXPECT_NE(lanes.open[i], 0) << i;
    }
    if (!outside) {
      EXPECT_EQ(lanes.open[i], 0) << i;
    }
    if (!lanes.open[i]) continue;
    ++open;
    glm::vec3 radiance = albedo * sun.y * k.sun_radiance + albedo * k.sky_irradiance;
    if (haze < 1.0f) radiance = radiance * haze + k.horizon * (1.0f - haze);
    differing += !(sameBits(radiance.x, lanes.radiance_r[i]) && sameBits(radiance.y, lanes.radiance_g[i]) &&
                   sameBits(radiance.z, lanes.radiance_b[i]));
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(open, 500);
}

// The hills' horizon map as the ground kernel tests it, in floats (SunHorizon::laneView): steep hills
// under a low sun (5 m hills 15 m apart, the sun 8 degrees up), ground points found by tracing straight
// down. Wherever the lanes say the hills leave the sun open, no ray of the sun's disc (its axis and 16
// rim directions) from the point, lifted as the renderer lifts a shadow ray's origin, meets the mesh;
// the lanes agree with the map's own test (in doubles) on nearly every point, and answer much of the
// lit ground. Then the same on every SIMD target, bit for bit.
TEST(SampleLanes, HillsAreOpenToTheSunOnlyWhereNoSunRayMeetsThem) {
  const test::SteepHills hills;
  const SunHorizon& horizon = hills.horizon;
  ASSERT_FALSE(horizon.everywhereOpen());

  LaneConstants k = constantsFor(scene::CameraFrame(sideCamera(scene::Camera::Projection::Perspective), 640, 360));
  k.hills = horizon.laneView();
  ASSERT_NE(k.hills.clear, nullptr);

  // Rays straight down onto the hills (a margin past the map on two sides: those are never open).
  const std::size_t n = 4000;
  CameraLanes lanes;
  lanes.resize(n);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1700.0f, 1500.0f);
  for (std::size_t i = 0; i < n; ++i) {
    lanes.ox[i] = u(rng), lanes.oy[i] = 2000.0f, lanes.oz[i] = u(rng);
    lanes.dx[i] = 0.0f, lanes.dy[i] = -1.0f, lanes.dz[i] = 0.0f;
    RTCRayHit rh{};
    rh.ray.org_x = lanes.ox[i], rh.ray.org_y = lanes.oy[i], rh.ray.org_z = lanes.oz[i];
    rh.ray.dir_y = -1.0f, rh.ray.tfar = 1e7f, rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(hills.scene.ground(), &context, &rh);
    ASSERT_NE(rh.hit.geomID, RTC_INVALID_GEOMETRY_ID);
    lanes.t_shade[i] = rh.ray.tfar;
    lanes.gnx[i] = 0.0f, lanes.gny[i] = 1.0f, lanes.gnz[i] = 0.0f;
  }
  terrainGroundLanes(k, lanes);

  int said_open = 0, lit = 0, agree = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float t = lanes.t_shade[i];
    const glm::vec3 p(lanes.ox[i] + t * lanes.dx[i], lanes.oy[i] + t * lanes.dy[i], lanes.oz[i] + t * lanes.dz[i]);
    const float extent = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
    const float slack = 3e-3f + 4e-5f * extent;
    const bool open = lanes.hills_open[i] != 0;
    said_open += open;
    agree += open == horizon.open(p, slack, true);
    const glm::vec3 origin = p + glm::vec3(0.0f, 2e-3f + 3e-5f * extent, 0.0f);  // ShadingLanes' lift
    const std::array<bool, 17> blocked = hills.discBlocked(origin);
    lit += !blocked[0];
    for (int r = 0; r <= 16; ++r) {
      if (open) {
        ASSERT_FALSE(blocked[std::size_t(r)]) << "said open at " << p.x << " " << p.z << ", ray " << r << " meets the mesh";
      }
    }
  }
  EXPECT_GE(agree, int(n) - int(n) / 500);  // the floats' texel or height differ from the doubles' rarely
  EXPECT_GT(said_open, lit / 4);

  const std::vector<std::string> targets = simdTargets();
  TargetPin restore;
  for (const std::string& target : targets) {
    pinSimdTarget(target);
    CameraLanes again = lanes;
    std::fill(again.hills_open.begin(), again.hills_open.end(), 0);
    terrainGroundLanes(k, again);
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(again.hills_open[i] != 0, lanes.hills_open[i] != 0) << target << " " << i;
  }
}

// Under a sun open everywhere, the lanes answer every ground point open to the hills, however far from the
// origin (300 m to 1 km: the shadow rays' offset is centimetres there, past what the map's texels allow
// for); none of their sun rays meets the mesh (SunHorizon.AHighSunIsOpenEvenWhereTheRayOffsetIsCentimetres).
// The same on every SIMD target.
TEST(SampleLanes, UnderAHighSunFarGroundIsOpenToTheHills) {
  const test::HighSunHills hills;
  ASSERT_TRUE(hills.horizon.everywhereOpen());
  LaneConstants k = constantsFor(scene::CameraFrame(sideCamera(scene::Camera::Projection::Perspective), 640, 360));
  k.hills = hills.horizon.laneView();
  const std::size_t n = 2000;
  CameraLanes lanes;
  lanes.resize(n);
  std::mt19937 rng(31);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec2 at = test::farFromTheOrigin(rng);
    const glm::vec3 p = test::groundBelow(hills.scene.ground(), at.x, at.y);
    ASSERT_TRUE(std::isfinite(p.y));
    lanes.ox[i] = p.x, lanes.oy[i] = 2000.0f, lanes.oz[i] = p.z;
    lanes.dx[i] = 0.0f, lanes.dy[i] = -1.0f, lanes.dz[i] = 0.0f;
    lanes.t_shade[i] = 2000.0f - p.y;
    lanes.gnx[i] = 0.0f, lanes.gny[i] = 1.0f, lanes.gnz[i] = 0.0f;
  }
  const std::vector<std::string> targets = simdTargets();
  TargetPin restore;
  for (const std::string& target : targets) {
    pinSimdTarget(target);
    std::fill(lanes.hills_open.begin(), lanes.hills_open.end(), 0);
    terrainGroundLanes(k, lanes);
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_NE(lanes.hills_open[i], 0) << target << " " << lanes.ox[i] << " " << lanes.oz[i];
    }
  }
  for (std::size_t i = 0; i < n; i += 10) {
    const glm::vec3 p(lanes.ox[i], 2000.0f - lanes.t_shade[i], lanes.oz[i]);
    const float extent = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
    const std::array<bool, 17> blocked = hills.discBlocked(p + glm::vec3(0.0f, 2e-3f + 3e-5f * extent, 0.0f));
    for (int r = 0; r <= 16; ++r) ASSERT_FALSE(blocked[std::size_t(r)]) << p.x << " " << p.z << ", ray " << r;
  }
}

// The heightfield's hits as Embree leaves them, read in lanes: where a ray hit, t_ground is its distance
// and the normal is the mesh's vertex normals interpolated at the hit point, on the triangle the point
// lies on (found here from the point's (x, z) in the grid, not from Embree's barycentrics); where it
// missed, t_ground is infinity. Rays from above at many slants meet both triangles of many cells; some
// point up and miss. The same bits on every target.
TEST(SampleLanes, GroundHitsGiveTheMeshNormalAtTheHitPoint) {
  const test::SteepHills hills;
  const TerrainMesh& mesh = hills.mesh;
  const std::size_t n = 3001;
  CameraLanes lanes;
  lanes.resize(n);
  std::vector<unsigned> geom(lanes.padded, RTC_INVALID_GEOMETRY_ID), prim(lanes.padded, 12345u);
  std::vector<float> u(lanes.padded, 0.0f), v(lanes.padded, 0.0f), tfar(lanes.padded, 0.0f);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> across(-1400.0f, 1400.0f), slant(-0.8f, 0.8f);
  int misses = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool up = i % 10 == 3;
    const glm::vec3 d = glm::normalize(glm::vec3(slant(rng), up ? 1.0f : -1.0f, slant(rng)));
    lanes.ox[i] = across(rng), lanes.oy[i] = 900.0f, lanes.oz[i] = across(rng);
    lanes.dx[i] = d.x, lanes.dy[i] = d.y, lanes.dz[i] = d.z;
    lanes.t_leave[i] = 1e7f;
    RTCRayHit rh{};
    rh.ray.org_x = lanes.ox[i], rh.ray.org_y = lanes.oy[i], rh.ray.org_z = lanes.oz[i];
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tfar = lanes.t_leave[i], rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(hills.scene.ground(), &context, &rh);
    ASSERT_EQ(rh.hit.geomID == RTC_INVALID_GEOMETRY_ID, up) << i;
    misses += up;
    if (up) continue;
    geom[i] = rh.hit.geomID, prim[i] = rh.hit.primID, u[i] = rh.hit.u, v[i] = rh.hit.v;
    lanes.t_leave[i] = rh.ray.tfar;  // as the stream leaves it: tfar is the hit's distance
  }
  ASSERT_GT(misses, 0);
  const GroundHits hits{geom.data(), prim.data(), u.data(), v.data(), mesh.xs.size(), mesh.normals.data()};

  TargetPin restore;
  std::vector<float> first;
  int upper = 0, lower = 0;
  for (const std::string& target : simdTargets()) {
    pinSimdTarget(target);
    CameraLanes again = lanes;
    groundHitLanes(hits, again);
    std::vector<float> out;
    for (std::size_t i = 0; i < n; ++i) {
      out.insert(out.end(), {again.t_ground[i], again.gnx[i], again.gny[i], again.gnz[i]});
      if (geom[i] == RTC_INVALID_GEOMETRY_ID) {
        EXPECT_TRUE(std::isinf(again.t_ground[i])) << target << " " << i;
        continue;
      }
      ASSERT_EQ(again.t_ground[i], lanes.t_leave[i]) << target << " " << i;
      // The point's cell and triangle in the grid, and its barycentrics there.
      const float t = again.t_ground[i];
      const double x = lanes.ox[i] + t * lanes.dx[i], z = lanes.oz[i] + t * lanes.dz[i];
      const auto cell = [](const std::vector<double>& lines, double c) {
        const auto it = std::upper_bound(lines.begin(), lines.end(), c);
        return std::size_t(std::clamp<std::ptrdiff_t>(it - lines.begin() - 1, 0, std::ptrdiff_t(lines.size()) - 2));
      };
      const std::size_t ci = cell(mesh.xs, x), cj = cell(mesh.zs, z), nx = mesh.xs.size();
      const double tx = (x - mesh.xs[ci]) / (mesh.xs[ci + 1] - mesh.xs[ci]);
      const double tz = (z - mesh.zs[cj]) / (mesh.zs[cj + 1] - mesh.zs[cj]);
      const std::size_t a = cj * nx + ci, b = a + 1, c = a + nx, d = c + 1;
      glm::dvec3 expected;
      if (tz >= tx) {  // (a c d)
        expected = (1.0 - tz) * glm::dvec3(mesh.normals[a]) + (tz - tx) * glm::dvec3(mesh.normals[c]) +
                   tx * glm::dvec3(mesh.normals[d]);
        upper += target == simdTargets().front();
      } else {  // (a d b)
        expected = (1.0 - tx) * glm::dvec3(mesh.normals[a]) + (tx - tz) * glm::dvec3(mesh.normals[b]) +
                   tz * glm::dvec3(mesh.normals[d]);
        lower += target == simdTargets().front();
      }
      const glm::dvec3 got(again.gnx[i], again.gny[i], again.gnz[i]);
      ASSERT_LT(glm::length(got - expected), 2e-4) << target << " sample " << i << " at " << x << " " << z;
    }
    if (first.empty()) {
      first = out;
    } else {
      EXPECT_EQ(std::memcmp(out.data(), first.data(), out.size() * sizeof(float)), 0) << target;
    }
  }
  EXPECT_GT(upper, 500);  // both triangles of the cells were hit, many times
  EXPECT_GT(lower, 500);
}

// Every kernel, run on every target this CPU has, gives the same bits (the premise of a frame's bytes
// not depending on the instruction set).
TEST(SampleLanes, EveryDispatchTargetGivesTheSameBits) {
  const std::vector<std::string> targets = simdTargets();
  ASSERT_FALSE(targets.empty());
  if (targets.size() < 2) GTEST_SKIP() << "this CPU runs one SIMD target only: " << targets.front();
  TargetPin restore;
  for (scene::Camera::Projection projection : {scene::Camera::Projection::Perspective, scene::Camera::Projection::Orthographic}) {
    const scene::CameraFrame frame(sideCamera(projection), 640, 360);
    LaneConstants k = constantsFor(frame);
    k.sun_region = true, k.sun_y = 0.7f, k.sun_radiance = glm::vec3(1.5f), k.sky_irradiance = glm::vec3(0.4f);
    k.ao_distance = 300.0f, k.horizon = {0.6f, 0.66f, 0.74f}, k.zenith = {0.2f, 0.3f, 0.6f}, k.below = k.horizon;
    k.color_a = glm::vec3(0.3f), k.color_b = glm::vec3(0.34f);
    std::vector<std::vector<float>> first;
    for (const std::string& target : targets) {
      pinSimdTarget(target);
      ASSERT_EQ(simdTargetName(), target);
      CameraLanes lanes = randomSamples(2053, 640, 360, 11);
      cameraRayLanes(k, lanes, true);
      lanes.t_shade = lanes.t_ground;
      groundLanes(k, lanes);
      skyLanes(k, lanes);
      std::vector<std::vector<float>> all = {lanes.ox, lanes.oy, lanes.oz, lanes.dx, lanes.dy, lanes.dz,
                                             lanes.t_ground, lanes.albedo_r, lanes.haze, lanes.depth,
                                             lanes.radiance_g, lanes.sky_b};
      std::vector<float> masks;
      for (std::size_t i = 0; i < lanes.size; ++i) {
        masks.push_back(float(lanes.may_hit[i] != 0));
        masks.push_back(float(lanes.open[i] != 0));
        if (!lanes.open[i]) lanes.radiance_g[i] = 0.0f;  // left from other lanes' pass: not an output
        if (std::isinf(lanes.t_shade[i])) lanes.albedo_r[i] = lanes.haze[i] = lanes.depth[i] = 0.0f;
      }
      all[7] = lanes.albedo_r, all[8] = lanes.haze, all[9] = lanes.depth, all[10] = lanes.radiance_g;
      all.push_back(masks);
      for (auto& v : all) v.resize(lanes.size);
      if (first.empty()) {
        first = all;
        continue;
      }
      for (std::size_t a = 0; a < all.size(); ++a)
        EXPECT_EQ(std::memcmp(all[a].data(), first[a].data(), all[a].size() * sizeof(float)), 0)
            << target << " against " << targets.front() << ", array " << a;
    }
  }
}

// The stratified points of many pixels' sequences at once, for square counts (a grid), powers of two
// and others (Latin hypercubes), against Stratified2D on every target, bit for bit.
TEST(SampleLanes, StratifiedPointsAreTheSequencesPointsOnEveryTarget) {
  TargetPin restore;
  for (const std::string& target : simdTargets()) {
    pinSimdTarget(target);
    for (uint32_t count : {1u, 2u, 3u, 4u, 5u, 9u, 16u, 17u, 36u, 64u, 100u, 256u}) {
      const Stratified2D::Layout layout(count);
      const std::size_t n = 4 * 16 * 9;  // whole vectors of every width
      StratifiedLanes points;
      points.resize(n);
      std::vector<glm::vec2> expected(n);
      for (std::size_t k = 0; k < n; ++k) {
        const PixelSampler sampler(int(k % 37) - 5, int(k / 37) * 3, 7 + int(count));
        const auto dim = SampleDimension(k % 3);
        const Stratified2D sequence(sampler, layout, dim);
        const uint32_t index = uint32_t(k * 7) % count;
        points.set(k, sequence.pixelPart(), index);
        expected[k] = sequence[index];
      }
      std::vector<float> u(n), v(n);
      stratifiedLanes(layout, points, 0, n, u.data(), v.data());
      int differing = 0;
      for (std::size_t k = 0; k < n; ++k) differing += !(sameBits(u[k], expected[k].x) && sameBits(v[k], expected[k].y));
      EXPECT_EQ(differing, 0) << target << ", count " << count;
    }
  }
}

// Pixels' sequences set up in lanes are Stratified2D's, field for field, on every target: counts of one
// (no permutation) and more (the seed and its remainders), every dimension, pixels near and far (their
// coordinates fill the hash's 64 bits), frames small and large.
TEST(SampleLanes, PixelPartsAreTheSequencesOnEveryTarget) {
  TargetPin restore;
  for (const std::string& target : simdTargets()) {
    pinSimdTarget(target);
    for (uint32_t count : {1u, 2u, 4u, 5u, 9u, 64u, 1000u}) {
      const Stratified2D::Layout layout(count);
      for (const auto dim : {SampleDimension::PixelFilter, SampleDimension::SunCone, SampleDimension::SkyHemisphere}) {
        for (const int frame : {0, 1, 72, 1 << 30}) {
          const std::size_t n = 3 * 16;
          std::vector<uint32_t> xs(n), ys(n);
          for (std::size_t p = 0; p < n; ++p) {
            xs[p] = p % 2 ? uint32_t(p * 2654435761u) : uint32_t(p);
            ys[p] = p % 3 ? uint32_t(639 - p) : uint32_t(-int(p));
          }
          StratifiedLanes parts;
          parts.resize(n);
          std::fill(parts.index.begin(), parts.index.end(), 7u);
          pixelPartLanes(layout, dim, uint32_t(frame), xs.data(), ys.data(), n, parts);
          int differing = 0;
          for (std::size_t p = 0; p < n; ++p) {
            const Stratified2D::PixelPart want =
                Stratified2D(PixelSampler(int(xs[p]), int(ys[p]), frame), layout, dim).pixelPart();
            const Stratified2D::PixelPart got = parts.part(p);
            differing += want.pixel_hash != got.pixel_hash || want.seed != got.seed || want.row_seed != got.row_seed ||
                         want.offset != got.offset || want.row_offset != got.row_offset || parts.index[p] != 0;
          }
          EXPECT_EQ(differing, 0) << target << ", count " << count << ", dimension " << int(dim) << ", frame " << frame;
        }
      }
    }
  }
  const Stratified2D::Layout layout(4);
  std::vector<uint32_t> xs(20), ys(20);
  StratifiedLanes parts;
  parts.resize(32);
  EXPECT_THROW(pixelPartLanes(layout, SampleDimension::SunCone, 1, xs.data(), ys.data(), 20, parts), std::invalid_argument);
}

// The lists of samples, on every target and for every batch size (ragged tails, padding with stale
// values): ascending, and exactly the samples a scalar loop picks.
TEST(SampleLanes, TheListsHoldExactlyTheSamplesTheyName) {
  TargetPin restore;
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> coin(0, 3);
  const float inf = std::numeric_limits<float>::infinity();
  for (const std::string& target : simdTargets()) {
    pinSimdTarget(target);
    for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(15), std::size_t(16), std::size_t(17),
                                std::size_t(1000), std::size_t(1024)}) {
      CameraLanes lanes;
      lanes.resize(n);
      for (std::size_t i = 0; i < lanes.padded; ++i) {  // the padding too: it must not be listed
        lanes.may_hit[i] = coin(rng) == 0 ? -1 : 0;
        lanes.open[i] = coin(rng) == 0 ? -1 : 0;
        lanes.hit_ray[i] = coin(rng) == 0 ? int32_t(i) : -1;
        const int t = coin(rng);
        lanes.t_ground[i] = t == 0 ? inf : t == 1 ? std::numeric_limits<float>::quiet_NaN() : 100.0f + float(i);
      }
      std::vector<int32_t> may_hit(lanes.padded + 1, -7), surfaces(lanes.padded + 1, -7);
      may_hit.resize(listMayHit(lanes, may_hit.data()));
      surfaces.resize(listSurfaceSamples(lanes, surfaces.data()));
      std::vector<int32_t> want_may_hit, want_surfaces;
      for (std::size_t i = 0; i < n; ++i) {
        if (lanes.may_hit[i]) want_may_hit.push_back(int32_t(i));
        // As the scalar loop sorted them: open ground, else the sky where no character was hit and no
        // ground met (t_ground infinite), else a surface.
        if (!lanes.open[i] && (lanes.hit_ray[i] >= 0 || lanes.t_ground[i] != inf)) want_surfaces.push_back(int32_t(i));
      }
      EXPECT_EQ(may_hit, want_may_hit) << target << ", " << n << " samples";
      EXPECT_EQ(surfaces, want_surfaces) << target << ", " << n << " samples";
    }
  }
}

TEST(SampleLanes, AnUnknownTargetIsRefusedByName) {
  TargetPin restore;
  try {
    pinSimdTarget("NEON");
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"NEON\": expected one of"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stirrup::render
