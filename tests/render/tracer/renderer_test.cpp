#include "render/tracer/renderer.h"

#include <chrono>
#include <memory>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <vector>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/tracer/integrator.h"
#include "render/tracer/sample_lanes.h"
#include "rig/texture.h"
#include "tests/render/tracer/steep_hills.h"
#include "tests/render/test_meshes.h"

namespace stirrup::render {
namespace {

using testing::makeSphere;
using testing::TestMesh;

// A 30 cm sphere floating 45 cm above the ground, seen from the front-right and above.
struct SmallScene {
  RenderSettings settings;
  scene::Camera camera;
  TestMesh sphere = makeSphere({0.0f, 45.0f, 0.0f}, 30.0f, 24, 48, {0.6f, 0.35f, 0.2f});

  SmallScene() {
    settings.width = 64;
    settings.height = 36;
    settings.samples_per_pixel = 4;
    settings.light_samples = 2;
    settings.ao_samples = 2;
    settings.sun_direction = {0.3, 0.8, 0.5};
    camera.position = {0.0, 300.0, 500.0};
    camera.target = {0.0, 20.0, 0.0};
    camera.fov_deg = 40.0;
  }

  Image render(int threads, int frame = 1) {
    RenderSettings s = settings;
    s.threads = threads;
    Renderer r(s);
    const int mesh = r.addMesh({ObjectId::Horse, sphere.indices, sphere.colors, sphere.positions.size()});
    r.updateMesh(mesh, sphere.positions, sphere.normals);
    return r.render(camera, frame);
  }

  // The pixel a world point projects to.
  glm::ivec2 pixelOf(glm::dvec3 p) const {
    const scene::CameraFrame f(camera, settings.width, settings.height);
    const glm::dvec3 d = p - camera.position;
    const double z = glm::dot(d, f.forward());
    const double half_h = std::tan(camera.fov_deg * std::numbers::pi / 360.0);
    const double half_w = half_h * settings.width / settings.height;
    const double u = 0.5 + 0.5 * glm::dot(d, f.right()) / z / half_w;
    const double v = 0.5 - 0.5 * glm::dot(d, f.upward()) / z / half_h;
    return {int(u * settings.width), int(v * settings.height)};
  }

  // Where the sun shadow of the sphere's centre falls on the ground.
  glm::dvec3 shadowCentre() const {
    const glm::dvec3 sun = glm::normalize(settings.sun_direction);
    const glm::dvec3 c(0.0, 45.0, 0.0);
    return c - sun * (c.y / sun.y);
  }
};

float luminance(const glm::vec4& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Mean luminance of a 3 x 3 block, to be robust to the checker and the noise.
float blockLuminance(const Image& img, glm::ivec2 p) {
  float sum = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) sum += luminance(img.at(p.x + dx, p.y + dy));
  return sum / 9.0f;
}

bool sameBytes(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.rgba.size() == b.rgba.size() &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(glm::vec4)) == 0 &&
         std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) == 0 &&
         std::memcmp(a.matte.data(), b.matte.data(), a.matte.size() * sizeof(float)) == 0 &&
         a.normal.size() == b.normal.size() &&
         std::memcmp(a.normal.data(), b.normal.data(), a.normal.size() * sizeof(glm::vec3)) == 0 &&
         a.object_id == b.object_id;
}

// Uneven ground (issue 15): the rolling hills of a path scene, meshed fine around the origin.
rig::Terrain testHills() { return test::rollingHillsTerrain(); }
const GroundRegion kHillsRegion{-2000.0, -2000.0, 2000.0, 2000.0};

// The sphere of `scene` over `terrain` in kHillsRegion, rendered with `settings` at `frame`.
template <class Scene>
Image renderOverHills(const Scene& scene, const std::shared_ptr<const rig::Terrain>& terrain,
                      const RenderSettings& settings, int frame) {
  Renderer r(settings);
  r.setTerrain(terrain, kHillsRegion);
  const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  return r.render(scene.camera, frame);
}

// A top-down orthographic camera over (x, z), `size` cm across.
scene::Camera lookingDownAt(double x, double z, double size) {
  scene::Camera c;
  c.projection = scene::Camera::Projection::Orthographic;
  c.position = {x, 1000.0, z};
  c.target = {x, 0.0, z};
  c.up = {0.0, 0.0, -1.0};
  c.ortho_height_cm = size;
  return c;
}

// Where the ground is in the depth pass is where the heightfield is: straight down at hill tops and
// hollows the ground pixels lie within half a centimetre (plus the slope times the sample's jitter
// inside its pixel) of Terrain::height, and not on the plane y = 0.
TEST(Renderer, UnevenGroundPixelsLieOnTheHeightfield) {
  auto terrain = std::make_shared<const rig::Terrain>(testHills());
  RenderSettings s;
  s.width = s.height = 32;
  s.samples_per_pixel = 1;
  s.light_samples = s.ao_samples = 1;
  constexpr double kViewCm = 16.0;                       // 0.5 cm pixels
  constexpr double kJitterCm = 2.0 * kViewCm / 32.0;     // the tent filter reaches a pixel either side
  constexpr double kOnSurfaceCm = 0.5;
  Renderer r(s);
  r.setTerrain(terrain, kHillsRegion);
  int spots = 0;
  for (double x = -1800.0; x <= 1800.0 && spots < 4; x += 97.0) {
    for (double z = -1800.0; z <= 1800.0 && spots < 4; z += 101.0) {
      if (std::abs(terrain->height(x, z)) < 30.0) continue;  // well off the plane, so the plane would fail
      ++spots;
      const Image img = r.render(lookingDownAt(x, z, kViewCm), 1);
      const double cm_per_px = kViewCm / s.height;
      for (int py = 0; py < s.height; ++py) {
        for (int px = 0; px < s.width; ++px) {
          const std::size_t i = std::size_t(py) * s.width + px;
          ASSERT_EQ(img.object_id[i], uint32_t(ObjectId::Ground));
          // Image right is +X, image down is +Z.
          const double wx = x + (px + 0.5 - 0.5 * s.width) * cm_per_px, wz = z + (py + 0.5 - 0.5 * s.height) * cm_per_px;
          double dx = 0.0, dz = 0.0;
          terrain->gradient(wx, wz, dx, dz);
          const double tolerance = kOnSurfaceCm + std::hypot(dx, dz) * kJitterCm;
          EXPECT_NEAR(1000.0 - img.depth[i], terrain->height(wx, wz), tolerance) << "at " << wx << ", " << wz;
        }
      }
    }
  }
  EXPECT_EQ(spots, 4);
}

// A sphere over the hills casts its shadow on them: where the sun ray through its centre meets the
// heightfield the ground is darker than beside it.
TEST(Renderer, ACharacterShadowsUnevenGround) {
  const rig::Terrain terrain = testHills();
  SmallScene scene;
  const glm::dvec3 centre(0.0, terrain.height(0.0, 0.0) + 45.0, 0.0);
  scene.sphere = makeSphere(glm::vec3(centre), 30.0f, 24, 48, {0.6f, 0.35f, 0.2f});
  scene.camera.target = {0.0, centre.y - 25.0, 0.0};
  scene.camera.position = {0.0, centre.y + 280.0, 500.0};
  // The shadow of the centre: march down the sun's ray to the ground (bisection on the height above it).
  const glm::dvec3 sun = glm::normalize(scene.settings.sun_direction);
  auto above = [&](double t) { const glm::dvec3 p = centre - sun * t; return p.y - terrain.height(p.x, p.z); };
  double lo = 0.0, hi = 1000.0;
  for (int i = 0; i < 60; ++i) (above(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const glm::dvec3 shadow = centre - sun * lo;
  const glm::dvec3 beside(-shadow.x - 100.0, terrain.height(-shadow.x - 100.0, shadow.z), shadow.z);
  RenderSettings s = scene.settings;
  Renderer r(s);
  r.setTerrain(std::make_shared<const rig::Terrain>(terrain), kHillsRegion);
  const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  const Image img = r.render(scene.camera, 1);
  const glm::ivec2 in_shadow = scene.pixelOf(shadow), in_sun = scene.pixelOf(beside);
  ASSERT_EQ(img.object_id[in_shadow.y * 64 + in_shadow.x], uint32_t(ObjectId::Ground));
  ASSERT_EQ(img.object_id[in_sun.y * 64 + in_sun.x], uint32_t(ObjectId::Ground));
  EXPECT_LT(blockLuminance(img, in_shadow), 0.5f * blockLuminance(img, in_sun));
}

TEST(Renderer, UnevenGroundBytesDoNotDependOnTheThreadCount) {
  SmallScene scene;
  auto terrain = std::make_shared<const rig::Terrain>(testHills());
  auto renderWith = [&](int threads) {
    RenderSettings s = scene.settings;
    s.threads = threads;
    return renderOverHills(scene, terrain, s, 3);
  };
  EXPECT_TRUE(sameBytes(renderWith(1), renderWith(2)));
}

// Under a sun lower than the hills' slopes the frame takes the hills' horizon map and their shadow rays
// (issue 35): still the same bytes at any thread count and on every SIMD target.
TEST(Renderer, HillShadowBytesDoNotDependOnTheThreadCountOrTarget) {
  SmallScene scene;
  const double e = 5.0 * std::numbers::pi / 180.0;
  scene.settings.sun_direction = {std::cos(e) * 0.8, std::sin(e), std::cos(e) * 0.6};
  auto terrain = std::make_shared<const rig::Terrain>(testHills());
  {  // the hills do hide this sun somewhere: the map is built and not open everywhere
    const TerrainMesh mesh = makeTerrainMesh(*terrain, kHillsRegion);
    const SunHorizon horizon(mesh, scene.settings.sun_direction,
                             scene.settings.sun_angular_radius_deg * std::numbers::pi / 180.0, kHillsRegion);
    ASSERT_FALSE(horizon.everywhereOpen());
    ASSERT_GT(horizon.width(), 0u);
  }
  auto renderWith = [&](int threads) {
    RenderSettings s = scene.settings;
    s.threads = threads;
    return renderOverHills(scene, terrain, s, 5);
  };
  const Image one = renderWith(1);
  EXPECT_TRUE(sameBytes(one, renderWith(2)));
  EXPECT_TRUE(sameBytes(one, renderWith(3)));
  const std::vector<std::string> targets = simdTargets();
  struct Restore {
    ~Restore() { pinSimdTarget("best"); }
  } restore;
  for (const std::string& target : targets) {
    pinSimdTarget(target);
    EXPECT_TRUE(sameBytes(one, renderWith(2))) << target;
  }
}

// Open ground over hills is lit in the camera lanes without a ray (terrainGroundLanes): the sun's
// cosine on the slope's own normal. With the shortcuts off every ground point traces its sun rays over
// the disc instead; lit by the sun alone (a black sky), the two agree pixel by pixel to the noise of
// sampling the disc (its cosine spreads by up to 3.5% across the default 2-degree disc, seen through 16 rays a
// pixel), and over the whole ground to a fraction of a percent, on the sunny and the shaded faces alike.
TEST(Renderer, OpenHillsTakeTheLightTheirSunRaysWouldGive) {
  SmallScene scene;
  scene.settings.sky.horizon = scene.settings.sky.zenith = scene.settings.sky.below = glm::vec3(0.0f);
  scene.settings.sun_direction = {0.8, 0.45, 0.2};
  scene.settings.light_samples = 4;
  auto terrain = std::make_shared<const rig::Terrain>(testHills());
  auto renderWith = [&](bool shortcuts) {
    RenderSettings s = scene.settings;
    s.open_ground_shortcuts = shortcuts;
    return renderOverHills(scene, terrain, s, 2);
  };
  const Image lanes = renderWith(true), traced = renderWith(false);
  int ground = 0;
  float darkest = 1.0f, brightest = 0.0f;
  double sum_lanes = 0.0, sum_traced = 0.0;
  for (std::size_t i = 0; i < lanes.pixelCount(); ++i) {
    if (lanes.object_id[i] != uint32_t(ObjectId::Ground) || traced.object_id[i] != uint32_t(ObjectId::Ground)) continue;
    ++ground;
    const float a = luminance(lanes.rgba[i]), b = luminance(traced.rgba[i]);
    darkest = std::min(darkest, a), brightest = std::max(brightest, a);
    sum_lanes += a, sum_traced += b;
    EXPECT_NEAR(a, b, 0.04f * std::max(a, b) + 1e-4f) << "pixel " << i % 64 << ", " << i / 64;
  }
  ASSERT_GT(ground, 64 * 36 / 2);
  EXPECT_NEAR(sum_lanes / ground, sum_traced / ground, 0.003 * sum_traced / ground);
  EXPECT_GT(brightest, 1.1f * darkest);  // the slopes do turn to and from the sun
}

// Flat terrain keeps the analytic plane: the same bytes as no terrain at all.
TEST(Renderer, FlatTerrainIsThePlaneOfBefore) {
  SmallScene scene;
  RenderSettings s = scene.settings;
  Renderer r(s);
  r.setTerrain(std::make_shared<const rig::Terrain>(), kHillsRegion);
  const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  EXPECT_TRUE(sameBytes(r.render(scene.camera, 1), scene.render(0)));
}

TEST(Renderer, TheSphereCoversTheExpectedPixels) {
  SmallScene scene;
  const Image img = scene.render(0);
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 36);
  ASSERT_EQ(img.object_id.size(), img.pixelCount());
  const glm::ivec2 centre = scene.pixelOf({0.0, 45.0, 0.0});
  EXPECT_EQ(img.object_id[centre.y * 64 + centre.x], uint32_t(ObjectId::Horse));
  EXPECT_EQ(img.matte[centre.y * 64 + centre.x], 1.0f);
  EXPECT_EQ(img.at(centre.x, centre.y).w, 1.0f);
  // A ground point beside the sphere.
  const glm::ivec2 beside = scene.pixelOf({-120.0, 0.0, 60.0});
  EXPECT_EQ(img.object_id[beside.y * 64 + beside.x], uint32_t(ObjectId::Ground));
  EXPECT_EQ(img.matte[beside.y * 64 + beside.x], 0.0f);
  EXPECT_EQ(img.at(beside.x, beside.y).w, 1.0f);
  // Count the character pixels: the sphere's silhouette is a disc of about pi r^2 pixels.
  const double r_px = 30.0 / (glm::length(scene.camera.position - glm::dvec3(0, 45, 0)) *
                              std::tan(scene.camera.fov_deg * std::numbers::pi / 360.0)) * 18.0;
  double covered = 0;
  for (float m : img.matte) covered += m;
  EXPECT_NEAR(covered, std::numbers::pi * r_px * r_px, 0.15 * std::numbers::pi * r_px * r_px);
}

TEST(Renderer, SkyIsAGradientWithZeroAlpha) {
  SmallScene scene;
  scene.camera.position = {0.0, 100.0, 500.0};
  scene.camera.target = {0.0, 140.0, 0.0};  // looking up a little: the top rows are sky
  const Image img = scene.render(0);
  EXPECT_EQ(img.at(10, 0).w, 0.0f);
  EXPECT_EQ(img.object_id[10], kNoObject);
  EXPECT_TRUE(std::isinf(img.depth[10]));
  // Bluer toward the zenith: the top row has a larger blue/red ratio than the row at the horizon.
  const glm::vec4 top = img.at(10, 0);
  EXPECT_GT(top.z / top.x, 1.2f);
}

// Every view has a horizon (issue 18): looking level from a rider's eye height, the rows above the
// horizon are sky (no alpha, bluer upward), the ground below it fades into the horizon's colour, and
// the near ground keeps its own.
TEST(Renderer, TheGroundFadesIntoTheSkyAtTheHorizon) {
  SmallScene scene;
  scene.settings.width = 96;
  scene.settings.height = 64;
  scene.camera.position = {0.0, 170.0, 800.0};
  scene.camera.target = {0.0, 170.0, 0.0};  // level: the horizon is the middle row
  scene.camera.fov_deg = 30.0;
  const Image img = scene.render(0);
  const glm::vec3 horizon = scene.settings.sky.horizon;
  auto row = [&](int y) {  // mean colour and alpha of a row, away from the sphere
    glm::vec4 sum(0.0f);
    for (int x = 0; x < 20; ++x) sum += img.at(x, y);
    return sum / 20.0f;
  };
  for (int y = 0; y < 31; ++y) EXPECT_EQ(row(y).w, 0.0f) << "row " << y;  // sky above
  for (int y = 33; y < 64; ++y) EXPECT_EQ(row(y).w, 1.0f) << "row " << y;  // ground below
  EXPECT_GT(row(0).z / row(0).x, row(30).z / row(30).x + 0.2f);            // bluer toward the zenith
  // The ground meets the sky in the horizon's colour (no seam), and keeps more of its own the nearer
  // it is: row 32 is half a degree below the horizon (hundreds of metres), row 63 a few metres off.
  auto haze = [&](int y) { return glm::length(glm::vec3(row(y)) - horizon); };
  EXPECT_LT(haze(32), 0.05f);
  EXPECT_LT(haze(32), haze(34));
  EXPECT_LT(haze(34), haze(40));
  EXPECT_LT(haze(40), haze(63));
  EXPECT_GT(haze(63), 0.15f);
}

// An orthographic side view has no eye to measure distance from: its ground fades from the camera's
// target to haze.ortho_depth_cm behind it, and the sky above that line is graded by height.
TEST(Renderer, AnOrthographicViewHasAHorizonToo) {
  SmallScene scene;
  scene.settings.width = 64;
  scene.settings.height = 48;
  scene.camera.projection = scene::Camera::Projection::Orthographic;
  scene.camera.position = {0.0, 200.0, 900.0};
  scene.camera.target = {0.0, 100.0, 0.0};  // looking down 6 degrees, as the side view does
  scene.camera.ortho_height_cm = 300.0;
  const Image img = scene.render(0);
  EXPECT_EQ(img.at(5, 0).w, 0.0f);   // the top is sky
  EXPECT_EQ(img.at(5, 47).w, 1.0f);  // the bottom is ground
  int line = 0;                       // the first ground row from the top
  while (line < 48 && img.at(5, line).w == 0.0f) ++line;
  ASSERT_GT(line, 2);
  ASSERT_LT(line, 40);
  const glm::vec4 top = img.at(5, 0), low_sky = img.at(5, line - 1);
  EXPECT_GT(top.z / top.x, low_sky.z / low_sky.x + 0.1f);  // graded: bluer higher up
  // Where the ground ends it is all haze: the horizon's colour, no seam.
  EXPECT_LT(glm::length(glm::vec3(img.at(5, line)) - scene.settings.sky.horizon), 0.04f);
}

// The checker far away is calm: in a slow pan (a tenth of a degree a frame) each pixel of the distant
// ground, where a square is a pixel wide or less (36 to 18 m away here), keeps its value from frame to
// frame to within a level of an 8-bit image (measured: 0.00016, 1/25 of a level). A box filter alone
// left bands there that crawled, 2.3 levels (0.0089): its side lobes keep a third of the contrast where a
// square is 1.5 footprints wide.
TEST(Renderer, DistantGroundIsCalmInASlowPan) {
  SmallScene scene;
  scene.settings.width = 160;
  scene.settings.height = 90;
  scene.settings.samples_per_pixel = 4;
  scene.camera.position = {0.0, 400.0, 800.0};
  scene.camera.fov_deg = 30.0;
  constexpr int kFrames = 12;
  std::vector<Image> frames;
  for (int f = 0; f < kFrames; ++f) {
    const double yaw = (30.0 + 0.1 * f) * std::numbers::pi / 180.0;  // away from the sphere
    scene.camera.target = scene.camera.position + glm::dvec3(-std::sin(yaw), -0.18, -std::cos(yaw)) * 100.0;
    frames.push_back(scene.render(0, f + 1));
  }
  const scene::CameraFrame cf(scene.camera, 160, 90);
  double worst = 0.0, sum = 0.0;
  int pixels = 0;
  for (int y = 0; y < 90; ++y) {
    const scene::Ray ray = cf.ray(0.5, (y + 0.5) / 90.0);
    if (!(ray.direction.y < 0.0)) continue;
    const double t = 400.0 / -ray.direction.y;
    const double squares = cf.pixelFootprint(t) / -ray.direction.y / scene.settings.ground_square_cm;
    if (squares < 1.0 || squares > 4.0) continue;  // a square spans a pixel to a quarter of one
    for (int x = 0; x < 160; ++x) {
      double mean = 0.0, square = 0.0;
      for (const Image& img : frames) {
        const double l = luminance(img.at(x, y));
        mean += l, square += l * l;
      }
      mean /= kFrames;
      const double sd = std::sqrt(std::max(0.0, square / kFrames - mean * mean));
      worst = std::max(worst, sd), sum += sd;
      ++pixels;
    }
  }
  ASSERT_GT(pixels, 160 * 10);
  std::printf("distant ground over the pan: %d pixels, standard deviation mean %.5f, largest %.5f\n", pixels,
              sum / pixels, worst);
  EXPECT_LT(worst, 1.0 / 255.0) << "the largest standard deviation of a distant ground pixel over the pan";
}

// The SIMD kernels give the same bytes on every instruction set (SSE4, AVX2, AVX-512), whole frames
// included: a flat-ground perspective frame, an orthographic one and one over hills.
TEST(Renderer, SameBytesOnEveryDispatchTarget) {
  const std::vector<std::string> targets = simdTargets();
  if (targets.size() < 2) GTEST_SKIP() << "this CPU runs one SIMD target only";
  struct Restore {
    ~Restore() { pinSimdTarget("best"); }
  } restore;
  SmallScene scene;
  SmallScene side = scene;
  side.camera.projection = scene::Camera::Projection::Orthographic;
  side.camera.position = {0.0, 200.0, 900.0};
  side.camera.target = {0.0, 100.0, 0.0};
  side.camera.ortho_height_cm = 300.0;
  auto terrain = std::make_shared<const rig::Terrain>(testHills());
  auto hills = [&] {
    Renderer r(scene.settings);
    r.setTerrain(terrain, kHillsRegion);
    const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
    r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
    return r.render(scene.camera, 3);
  };
  std::vector<Image> first;
  for (const std::string& target : targets) {
    pinSimdTarget(target);
    std::vector<Image> images = {scene.render(0), side.render(0), hills()};
    if (first.empty()) {
      first = std::move(images);
      continue;
    }
    for (std::size_t i = 0; i < images.size(); ++i) EXPECT_TRUE(sameBytes(images[i], first[i])) << target << ", image " << i;
  }
}

TEST(Renderer, TheSunShadowIsDarkerThanLitGround) {
  SmallScene scene;
  const Image img = scene.render(0);
  const glm::dvec3 shadow = scene.shadowCentre();
  const glm::ivec2 in_shadow = scene.pixelOf(shadow);
  const glm::ivec2 in_sun = scene.pixelOf({-shadow.x - 100.0, 0.0, shadow.z});  // same depth, other side
  ASSERT_EQ(img.object_id[in_shadow.y * 64 + in_shadow.x], uint32_t(ObjectId::Ground));
  ASSERT_EQ(img.object_id[in_sun.y * 64 + in_sun.x], uint32_t(ObjectId::Ground));
  EXPECT_LT(blockLuminance(img, in_shadow), 0.5f * blockLuminance(img, in_sun));
}

TEST(Renderer, SkyOcclusionDarkensTheGroundUnderTheObject) {
  SmallScene scene;
  scene.settings.sun_strength = 0.0f;  // sky light only
  scene.settings.ao_samples = 8;
  const Image img = scene.render(0);
  const float under = blockLuminance(img, scene.pixelOf({0.0, 0.0, 32.0}));  // just in front of the contact point
  const float open = blockLuminance(img, scene.pixelOf({-150.0, 0.0, 32.0}));
  EXPECT_LT(under, 0.85f * open);
  EXPECT_GT(under, 0.0f);
}

TEST(Renderer, TheSunlitSideIsBrighterThanTheShadedSide) {
  SmallScene scene;
  scene.settings.sun_direction = {1.0, 0.3, 0.0};  // from the right of the picture
  scene.camera.position = {0.0, 45.0, 500.0};
  scene.camera.target = {0.0, 45.0, 0.0};
  const Image img = scene.render(0);
  const glm::ivec2 right = scene.pixelOf({20.0, 45.0, 22.0}), left = scene.pixelOf({-20.0, 45.0, 22.0});
  EXPECT_GT(luminance(img.at(right.x, right.y)), 2.0f * luminance(img.at(left.x, left.y)));
}

TEST(Renderer, BytesDoNotDependOnTheThreadCount) {
  SmallScene scene;
  const Image one = scene.render(1), all = scene.render(0), two = scene.render(2), three = scene.render(3);
  EXPECT_TRUE(sameBytes(one, all));
  EXPECT_TRUE(sameBytes(one, two));
  EXPECT_TRUE(sameBytes(one, three));
}

// A task run beside the frame (frames overlapped: the shot's next frame) runs to its end before render
// returns, on one thread or several, leaves the frame's bytes as they are, and its error comes out of render.
TEST(Renderer, ATaskBesideTheFrameRunsToItsEndAndChangesNoByte) {
  SmallScene scene;
  for (const int threads : {1, 2}) {
    RenderSettings s = scene.settings;
    s.threads = threads;
    Renderer r(s);
    const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
    r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
    std::vector<double> work(200000);
    bool done = false;
    const Image beside = r.render(scene.camera, 1, nullptr, [&] {
      for (std::size_t i = 0; i < work.size(); ++i) work[i] = std::sqrt(double(i));
      done = true;
    });
    EXPECT_TRUE(done) << threads << " threads";
    EXPECT_EQ(work.back(), std::sqrt(double(work.size() - 1)));
    EXPECT_TRUE(sameBytes(beside, scene.render(threads))) << threads << " threads";
    EXPECT_THROW(r.render(scene.camera, 1, nullptr, [] { throw std::runtime_error("beside"); }), std::runtime_error);
  }
}

TEST(Renderer, RenderingTwiceGivesTheSameBytes) {
  SmallScene scene;
  RenderSettings s = scene.settings;
  Renderer r(s);
  const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  const Image a = r.render(scene.camera, 3);
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);  // a new commit of the same vertices
  const Image b = r.render(scene.camera, 3);
  EXPECT_TRUE(sameBytes(a, b));
  EXPECT_TRUE(sameBytes(a, scene.render(0, 3)));  // and a fresh renderer agrees
}

// A hidden mesh is not drawn (the frame is the empty scene's), and shown again, after frames of other
// poses while hidden, it gives the bytes of a fresh renderer (a crowd's levels of detail, under Refit:
// a mesh put back is built over its rest pose again).
TEST(Renderer, AHiddenMeshIsNotDrawnAndComesBackTheSame) {
  SmallScene scene;
  Renderer empty(scene.settings);
  const Image nothing = empty.render(scene.camera, 3);
  Renderer r(scene.settings);
  const TestMesh rest = makeSphere({0.0f, 60.0f, 0.0f}, 25.0f, 24, 48, {0.6f, 0.35f, 0.2f});
  const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size(),
                              rest.positions});
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  const Image shown = r.render(scene.camera, 3);
  r.setMeshEnabled(mesh, false);
  EXPECT_TRUE(sameBytes(r.render(scene.camera, 3), nothing));
  const TestMesh moved = makeSphere({40.0f, 45.0f, 0.0f}, 30.0f, 24, 48, {0.6f, 0.35f, 0.2f});
  r.updateMesh(mesh, moved.positions, moved.normals);
  EXPECT_TRUE(sameBytes(r.render(scene.camera, 3), nothing));
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  r.setMeshEnabled(mesh, true);
  EXPECT_TRUE(sameBytes(r.render(scene.camera, 3), shown));
  EXPECT_EQ(r.lastStats().triangles, scene.sphere.indices.size() / 3);
  EXPECT_THROW(r.setMeshEnabled(mesh + 1, false), std::invalid_argument);
}

TEST(Renderer, AnotherFrameMovesOnlyTheNoise) {
  SmallScene scene;
  const Image a = scene.render(0, 1), b = scene.render(0, 2);
  double mean_a = 0, mean_b = 0;
  int differing = 0;
  for (size_t i = 0; i < a.pixelCount(); ++i) {
    mean_a += luminance(a.rgba[i]);
    mean_b += luminance(b.rgba[i]);
    differing += a.rgba[i] != b.rgba[i];
  }
  EXPECT_GT(differing, 0);  // the sampling pattern changed...
  EXPECT_NEAR(mean_a / a.pixelCount(), mean_b / b.pixelCount(), 0.01);  // ...the picture did not
  // Only edge pixels can change their majority object between frames.
  int ids_changed = 0;
  for (size_t i = 0; i < a.pixelCount(); ++i) ids_changed += a.object_id[i] != b.object_id[i];
  EXPECT_LT(ids_changed, int(a.pixelCount() / 50));
}

TEST(Renderer, MovingAMeshMovesItsPixels) {
  SmallScene scene;
  Renderer r(scene.settings);
  const int mesh = r.addMesh({ObjectId::Rider, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  const glm::ivec2 centre = scene.pixelOf({0.0, 45.0, 0.0});
  EXPECT_EQ(r.render(scene.camera, 1).object_id[centre.y * 64 + centre.x], uint32_t(ObjectId::Rider));
  std::vector<glm::vec3> moved = scene.sphere.positions;
  for (glm::vec3& p : moved) p.x += 150.0f;
  r.updateMesh(mesh, moved, scene.sphere.normals);
  const Image img = r.render(scene.camera, 1);
  EXPECT_EQ(img.object_id[centre.y * 64 + centre.x], uint32_t(ObjectId::Ground));
  const glm::ivec2 now = scene.pixelOf({150.0, 45.0, 0.0});
  EXPECT_EQ(img.object_id[now.y * 64 + now.x], uint32_t(ObjectId::Rider));
}

TEST(Renderer, AllBvhUpdateModesSeeTheSameScene) {
  SmallScene scene;
  const Image reference = scene.render(0);
  for (BvhUpdate mode : {BvhUpdate::RebuildPerMesh, BvhUpdate::RebuildPerMeshLow, BvhUpdate::Refit}) {
    scene.settings.bvh_update = mode;
    const Image img = scene.render(0);
    EXPECT_EQ(img.object_id, reference.object_id);
    double diff = 0;
    for (size_t i = 0; i < img.pixelCount(); ++i) diff += std::abs(luminance(img.rgba[i]) - luminance(reference.rgba[i]));
    EXPECT_LT(diff / img.pixelCount(), 1e-3);
  }
}

TEST(Renderer, TheNormalPassIsUnitOnSurfacesAndZeroOnSky) {
  SmallScene scene;
  const Image img = scene.render(0);
  ASSERT_EQ(img.normal.size(), img.pixelCount());
  for (size_t i = 0; i < img.pixelCount(); ++i) {
    if (img.rgba[i].w == 0.0f) {  // no sample hit anything
      EXPECT_EQ(img.normal[i], glm::vec3(0.0f));
    } else {
      EXPECT_NEAR(glm::length(img.normal[i]), 1.0f, 1e-4f);
    }
  }
  // The sphere's point nearest the camera faces it; the open ground faces up.
  const glm::dvec3 centre(0.0, 45.0, 0.0);
  const glm::dvec3 toward = glm::normalize(scene.camera.position - centre);
  const glm::ivec2 front = scene.pixelOf(centre + 30.0 * toward);
  const glm::vec3 n = img.normal[size_t(front.y) * 64 + size_t(front.x)];
  EXPECT_GT(glm::dot(glm::dvec3(n), toward), 0.95);
  const glm::ivec2 ground = scene.pixelOf({-150.0, 0.0, 100.0});
  EXPECT_EQ(img.object_id[size_t(ground.y) * 64 + size_t(ground.x)], uint32_t(ObjectId::Ground));
  EXPECT_EQ(img.normal[size_t(ground.y) * 64 + size_t(ground.x)], glm::vec3(0.0f, 1.0f, 0.0f));
}

// With Refit the BVH is built over the rest pose and only refitted, so a frame's bytes must not
// depend on which poses were committed before it (a farm renders frames alone, in any order).
TEST(Renderer, RefitFromTheRestPoseDoesNotDependOnEarlierFrames) {
  SmallScene scene;
  scene.settings.bvh_update = BvhUpdate::Refit;
  auto posed = [&](float dx, float squash) {
    std::vector<glm::vec3> p = scene.sphere.positions;
    for (glm::vec3& v : p) v = {v.x * (1.0f + squash) + dx, 45.0f + (v.y - 45.0f) * (1.0f - squash), v.z};
    return p;
  };
  auto renderAfter = [&](const std::vector<std::vector<glm::vec3>>& poses, int threads) {
    RenderSettings s = scene.settings;
    s.threads = threads;
    Renderer r(s);
    MeshDesc desc{ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size(),
                  scene.sphere.positions};
    const int mesh = r.addMesh(desc);
    Image last;
    for (const auto& p : poses) {
      r.updateMesh(mesh, p, scene.sphere.normals);
      last = r.render(scene.camera, 5);
    }
    return last;
  };
  const auto a = posed(-40.0f, 0.3f), b = posed(25.0f, -0.2f);
  const Image alone = renderAfter({b}, 1);
  EXPECT_TRUE(sameBytes(alone, renderAfter({a, b}, 1)));
  EXPECT_TRUE(sameBytes(alone, renderAfter({b, a, b}, 0)));
  EXPECT_TRUE(sameBytes(alone, renderAfter({a, a, b}, 2)));
  // And it sees the same picture as a rebuild of pose b.
  scene.settings.bvh_update = BvhUpdate::Rebuild;
  const Image rebuilt = renderAfter({b}, 0);
  EXPECT_EQ(rebuilt.object_id, alone.object_id);
}

TEST(Renderer, CountsItsRaysAndKeepsThemForReplay) {
  SmallScene scene;
  Renderer r(scene.settings);
  const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, scene.sphere.colors, scene.sphere.positions.size()});
  r.updateMesh(mesh, scene.sphere.positions, scene.sphere.normals);
  const Image plain = r.render(scene.camera, 2);
  const uint64_t rays = r.lastStats().rays;
  const uint64_t camera_rays = uint64_t(64 * 36 * scene.settings.samples_per_pixel);
  EXPECT_GT(rays, camera_rays);  // camera rays plus shadow and sky rays near the sphere
  EXPECT_LE(rays, camera_rays * uint64_t(1 + scene.settings.light_samples + scene.settings.ao_samples));

  RayLog log;
  const Image logged = r.render(scene.camera, 2, &log);
  EXPECT_TRUE(sameBytes(plain, logged));  // keeping the rays changes nothing
  EXPECT_EQ(log.camera.size(), camera_rays);
  EXPECT_EQ(log.rays, rays);
  EXPECT_EQ(log.rays, log.camera.size() + log.occlusion.size());
  EXPECT_GT(r.replay(log), 0.0);

  RayLog half;
  half.pixel_stride = 2;
  r.render(scene.camera, 2, &half);
  EXPECT_EQ(half.camera.size(), camera_rays / 2);
  EXPECT_LT(half.rays, log.rays);
}

// A lit flat panel must shade evenly: self-intersection of shadow rays ("acne") would speckle it.
TEST(Renderer, AFlatLitPanelHasNoShadowAcne) {
  RenderSettings settings;
  settings.width = 48;
  settings.height = 48;
  settings.samples_per_pixel = 4;
  settings.sun_direction = {0.2, 1.0, 0.1};
  settings.sky.horizon = settings.sky.zenith = settings.sky.below = glm::vec3(0.0f);  // sun only: no sky noise
  // A 400 cm square at y = 80, far from the origin so float error in hit points is realistic.
  const float x0 = 3000.0f, y = 80.0f;
  const std::vector<glm::vec3> positions = {{x0 - 200, y, -200}, {x0 - 200, y, 200}, {x0 + 200, y, 200}, {x0 + 200, y, -200}};
  const std::vector<glm::vec3> normals(4, glm::vec3(0, 1, 0));
  Renderer r(settings);
  const int mesh = r.addMesh({ObjectId::Horse, {0, 1, 2, 0, 2, 3}, std::vector<glm::vec3>(4, glm::vec3(0.5f)), 4});
  r.updateMesh(mesh, positions, normals);
  scene::Camera camera;
  camera.projection = scene::Camera::Projection::Orthographic;
  camera.position = {x0, 500.0, 300.0};
  camera.target = {x0, y, 0.0};
  camera.ortho_height_cm = 150.0;  // only the middle of the panel: no edges, no sky
  const Image img = r.render(camera, 1);
  float lo = 1e9f, hi = 0.0f;
  for (const glm::vec4& c : img.rgba) lo = std::min(lo, luminance(c)), hi = std::max(hi, luminance(c));
  // One blocked sun ray of the 4 x 4 per pixel would cost 1/16 of the light; the spread allowed is the
  // small specular variation across the view.
  EXPECT_GT(lo, 0.5f);
  EXPECT_LT(hi - lo, 0.01f * hi);
}

TEST(Renderer, RejectsInconsistentInput) {
  SmallScene scene;
  Renderer r(scene.settings);
  const size_t n = scene.sphere.positions.size();
  EXPECT_THROW(r.addMesh({ObjectId::Horse, {0, 1}, {}, 3}), std::invalid_argument);         // partial triangle
  EXPECT_THROW(r.addMesh({ObjectId::Horse, {0, 1, 3}, {}, 3}), std::invalid_argument);      // index out of range
  EXPECT_THROW(r.addMesh({ObjectId::Horse, {0, 1, 2}, {{1, 1, 1}}, 3}), std::invalid_argument);  // colour count
  const int mesh = r.addMesh({ObjectId::Horse, scene.sphere.indices, {}, n});
  EXPECT_THROW(r.updateMesh(mesh, std::span(scene.sphere.positions).first(n - 1), scene.sphere.normals),
               std::invalid_argument);
  EXPECT_THROW(r.updateMesh(mesh, scene.sphere.positions, std::span(scene.sphere.normals).first(n - 1)),
               std::invalid_argument);
  EXPECT_THROW(r.updateMesh(mesh + 1, scene.sphere.positions, scene.sphere.normals), std::invalid_argument);
  RenderSettings bad;
  bad.samples_per_pixel = 0;
  EXPECT_THROW(Renderer{bad}, std::invalid_argument);
  bad = {};
  bad.sun_direction = {0, 0, 0};
  EXPECT_THROW(Renderer{bad}, std::invalid_argument);
}

TEST(Renderer, GroundCheckerIsFilteredToItsMean) {
  EXPECT_EQ(filteredChecker(0.5f, 0.5f, 0.0f), 0.0f);
  EXPECT_EQ(filteredChecker(1.5f, 0.5f, 0.0f), 1.0f);
  EXPECT_EQ(filteredChecker(1.5f, 1.5f, 0.0f), 0.0f);
  EXPECT_NEAR(filteredChecker(1.5f, 0.5f, 0.2f), 1.0f, 1e-6f);  // the box stays inside one square
  EXPECT_NEAR(filteredChecker(1.0f, 0.5f, 1.0f), 0.5f, 1e-6f);  // straddles an edge evenly
  EXPECT_EQ(filteredChecker(12.3f, 45.6f, 3.0f), 0.5f);          // far away: the mean
  EXPECT_EQ(filteredChecker(1999.5f, 0.5f, 0.0f), 1.0f);   // far from the origin, still sharp
  EXPECT_EQ(filteredChecker(-0.5f, 0.5f, 0.0f), 1.0f);
}

// A 200 cm square panel standing in the plane z = 0 and facing +z, seen square on through an
// orthographic camera that sees only its middle (no edges, sky or ground). Its texture is a 2 x 1
// stripe: sRGB (200, 60, 20) on the left, (20, 60, 200) on the right, nearest.
struct TexturedPanel {
  RenderSettings settings;
  scene::Camera camera;
  std::vector<glm::vec3> positions = {{-100, 0, 0}, {100, 0, 0}, {100, 200, 0}, {-100, 200, 0}};
  std::vector<glm::vec3> normals = std::vector<glm::vec3>(4, glm::vec3(0, 0, 1));
  std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
  std::vector<glm::vec2> uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};  // the image's top at the panel's top
  std::shared_ptr<const rig::Texture> stripe;

  // The sRGB transfer undone (IEC 61966-2-1) for an 8-bit code.
  static float linear(int code) {
    const double c = code / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
  }

  TexturedPanel() {
    settings.width = settings.height = 32;
    settings.samples_per_pixel = 4;
    settings.specular = 0.0f;  // matte: the light reflected is the albedo times the same irradiance
    settings.sun_direction = {0.3, 0.5, 1.0};
    camera.projection = scene::Camera::Projection::Orthographic;
    camera.position = {0.0, 100.0, 500.0};
    camera.target = {0.0, 100.0, 0.0};
    camera.ortho_height_cm = 150.0;
    auto t = std::make_shared<rig::Texture>();
    t->width = 2;
    t->height = 1;
    t->texels = {{linear(200), linear(60), linear(20)}, {linear(20), linear(60), linear(200)}};
    t->filter = rig::TextureFilter::Nearest;
    stripe = t;
  }

  Image render(bool textured, glm::vec3 colour, int threads = 0) const {
    RenderSettings s = settings;
    s.threads = threads;
    Renderer r(s);
    MeshDesc desc{ObjectId::Horse, indices, std::vector<glm::vec3>(4, colour), 4};
    if (textured) {
      desc.uvs = uvs;
      desc.triangle_textures = {0, 0};
      desc.textures = {stripe};
    }
    r.updateMesh(r.addMesh(desc), positions, normals);
    return r.render(camera, 1);
  }
};

// Textured, each pixel is its vertex colour times the texel under it times the light a white panel
// gets there (the panel is matte, so the light is the same); untextured, the panel is its colour.
TEST(Renderer, ATexturedTriangleShowsItsTexture) {
  const TexturedPanel panel;
  const glm::vec3 tint(0.5f, 1.0f, 1.0f);
  const Image white = panel.render(false, glm::vec3(1.0f)), plain = panel.render(false, tint),
              textured = panel.render(true, tint);
  const glm::vec3 left(TexturedPanel::linear(200), TexturedPanel::linear(60), TexturedPanel::linear(20));
  const glm::vec3 right(left.z, left.y, left.x);
  int checked = 0;
  for (int y = 0; y < textured.height; ++y)
    for (int x = 0; x < textured.width; ++x) {
      if (std::abs(2 * x + 1 - textured.width) < 6) continue;  // the seam's pixels see both texels
      const glm::vec3 expected = tint * (2 * x < textured.width ? left : right);
      const glm::vec3 light(white.at(x, y)), got(textured.at(x, y));
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(got[k], expected[k] * light[k], 1e-5f * light[k] + 1e-7f) << x << ", " << y;
      // Left red over blue, right blue over red; untextured, the panel is the tint everywhere.
      if (2 * x < textured.width) EXPECT_GT(got.x, 4.0f * got.z) << x << ", " << y;
      else EXPECT_GT(got.z, 2.0f * got.x) << x << ", " << y;
      const glm::vec3 p(plain.at(x, y));
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], tint[k] * light[k], 1e-5f * light[k] + 1e-7f) << x << ", " << y;
      ++checked;
    }
  EXPECT_GT(checked, 600);
}

// A textured frame is the same bytes at any thread count and on every SIMD target.
TEST(Renderer, TexturedBytesDoNotDependOnThreadsOrTarget) {
  const TexturedPanel panel;
  TexturedPanel seen = panel;
  seen.camera.projection = scene::Camera::Projection::Perspective;  // the panel's edges, the ground and the sky too
  seen.camera.position = {150.0, 180.0, 420.0};
  const Image one = seen.render(true, glm::vec3(1.0f), 1);
  EXPECT_TRUE(sameBytes(one, seen.render(true, glm::vec3(1.0f), 2)));
  const std::vector<std::string> targets = simdTargets();
  if (targets.size() < 2) GTEST_SKIP() << "this CPU runs one SIMD target only (the thread counts were compared)";
  struct Restore {
    ~Restore() { pinSimdTarget("best"); }
  } restore;
  for (const std::string& target : targets) {
    pinSimdTarget(target);
    EXPECT_TRUE(sameBytes(seen.render(true, glm::vec3(1.0f), 2), one)) << target;
  }
}

TEST(Renderer, RejectsInconsistentTextures) {
  const TexturedPanel panel;
  Renderer r(panel.settings);
  MeshDesc desc{ObjectId::Horse, panel.indices, {}, 4};
  desc.uvs = panel.uvs;
  desc.triangle_textures = {0, 0};
  desc.textures = {panel.stripe};
  MeshDesc bad = desc;
  bad.uvs.pop_back();
  EXPECT_THROW(r.addMesh(bad), std::invalid_argument);  // one uv short
  bad = desc;
  bad.triangle_textures = {0};
  EXPECT_THROW(r.addMesh(bad), std::invalid_argument);  // one triangle without its texture index
  bad = desc;
  bad.triangle_textures = {0, 1};
  EXPECT_THROW(r.addMesh(bad), std::invalid_argument);  // texture 1 of one
  EXPECT_NO_THROW(r.addMesh(desc));
}

}  // namespace
}  // namespace stirrup::render
