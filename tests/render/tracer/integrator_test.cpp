// The integrator traces a tile as ray streams in batches of pixels. A pixel's result must not depend
// on which tile or batch it falls in, or on how many other pixels share its streams.
#include "render/tracer/integrator.h"

#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "render/tracer/renderer.h"
#include "rig/motion/terrain_mesh.h"
#include "tests/render/test_meshes.h"

namespace stirrup::render {
namespace {

// A sphere resting near the ground, seen from above and in front, so tiles hold sky, ground, the
// sphere's edge and its shadow.
struct StreamScene {
  RenderSettings settings;
  scene::Camera camera;
  testing::TestMesh sphere = testing::makeSphere({0.0f, 35.0f, 0.0f}, 30.0f, 16, 32, {0.6f, 0.35f, 0.2f});
  EmbreeScene scene;
  ShadingMesh mesh;
  std::vector<const ShadingMesh*> by_geometry;

  explicit StreamScene(int spp) {
    settings.width = 40;
    settings.height = 24;
    settings.samples_per_pixel = spp;
    settings.light_samples = 2;
    settings.ao_samples = 3;
    settings.sun_direction = {0.3, 0.8, 0.5};
    camera.position = {0.0, 120.0, 260.0};
    camera.target = {0.0, 60.0, 0.0};
    camera.fov_deg = 40.0;
    scene.setGround(settings.ground_half_extent_cm);
    const unsigned geometry = scene.addTriangleMesh(sphere.positions.size(), sphere.indices);
    scene.setVertices(geometry, sphere.positions);
    scene.commit();
    mesh.id = ObjectId::Rider;
    mesh.indices = sphere.indices;
    mesh.colors = sphere.colors;
    mesh.normals = sphere.normals;
    by_geometry.assign(geometry + 1, nullptr);
    by_geometry[geometry] = &mesh;
  }

  // The whole frame, tiled `tile` x `tile` pixels, through one integrator and one scratch.
  std::vector<PixelResult> render(int tile, uint64_t& rays) {
    const Integrator integrator(settings, scene, by_geometry);
    const scene::CameraFrame frame(camera, settings.width, settings.height);
    std::vector<PixelResult> image(size_t(settings.width * settings.height));
    std::vector<PixelResult> results;
    TileScratch scratch;
    RayTally tally;
    for (int y0 = 0; y0 < settings.height; y0 += tile) {
      for (int x0 = 0; x0 < settings.width; x0 += tile) {
        const int x1 = std::min(x0 + tile, settings.width), y1 = std::min(y0 + tile, settings.height);
        results.assign(size_t((x1 - x0) * (y1 - y0)), PixelResult{});
        integrator.renderTile(frame, x0, x1, y0, y1, 7, scratch, tally, results.data());
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) image[size_t(y * settings.width + x)] = results[size_t((y - y0) * (x1 - x0) + x - x0)];
      }
    }
    rays = tally.rays;
    return image;
  }
};

bool same(const PixelResult& a, const PixelResult& b) {
  return std::memcmp(&a.rgba, &b.rgba, sizeof a.rgba) == 0 && std::memcmp(&a.depth, &b.depth, sizeof a.depth) == 0 &&
         std::memcmp(&a.matte, &b.matte, sizeof a.matte) == 0 && std::memcmp(&a.normal, &b.normal, sizeof a.normal) == 0 &&
         a.object_id == b.object_id;
}

void expectSameImages(const std::vector<PixelResult>& a, const std::vector<PixelResult>& b) {
  ASSERT_EQ(a.size(), b.size());
  int differing = 0;
  for (size_t i = 0; i < a.size(); ++i) differing += !same(a[i], b[i]);
  EXPECT_EQ(differing, 0);
}

TEST(Integrator, APixelIsTheSameInAnyTileAndBatch) {
  // 4 samples: a 16 x 16 tile is one batch of 1024 samples. 64 samples: batches of 16 pixels that
  // straddle the rows of a tile. 1 x 1 tiles: streams of a single pixel's rays.
  for (int spp : {4, 64}) {
    StreamScene scene(spp);
    uint64_t rays_16 = 0, rays_5 = 0, rays_1 = 0;
    const std::vector<PixelResult> tiles_16 = scene.render(16, rays_16);
    const std::vector<PixelResult> tiles_5 = scene.render(5, rays_5);
    const std::vector<PixelResult> tiles_1 = scene.render(1, rays_1);
    SCOPED_TRACE(spp);
    expectSameImages(tiles_16, tiles_5);
    expectSameImages(tiles_16, tiles_1);
    EXPECT_EQ(rays_16, rays_5);
    EXPECT_EQ(rays_16, rays_1);
  }
}

TEST(Integrator, TheSceneHoldsEveryKindOfPixel) {
  // Guards the test above: it only means something if the tiles mix sky, ground, sphere and shadow.
  StreamScene scene(4);
  uint64_t rays = 0;
  const std::vector<PixelResult> image = scene.render(16, rays);
  int sky = 0, ground = 0, sphere = 0;
  for (const PixelResult& p : image) {
    sky += p.object_id == kNoObject;
    ground += p.object_id == uint32_t(ObjectId::Ground);
    sphere += p.object_id == uint32_t(ObjectId::Rider);
  }
  EXPECT_GT(sky, 0);
  EXPECT_GT(ground, 0);
  EXPECT_GT(sphere, 20);
  const uint64_t camera_rays = uint64_t(scene.settings.width * scene.settings.height * 4);
  EXPECT_GT(rays, camera_rays);  // shadow and sky rays were cast too
}

TEST(Integrator, TheGroundSunShortcutAgreesWithTheFullTest) {
  // The rectangle must be exact where it answers: on random ground points, over suns high and low,
  // narrow and wide, both tests give the same answer. It must also answer for most of the open ground,
  // or it is no use.
  StreamScene scene(1);
  uint32_t state = 12345u;
  auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) * 0x1p-24f;
  };
  int blocked = 0, open = 0, excluded = 0;
  for (const glm::dvec3 sun : {glm::dvec3(0.3, 0.8, 0.5), glm::dvec3(-0.7, 0.35, 0.1), glm::dvec3(0.0, 1.0, 0.0),
                               glm::dvec3(0.2, 0.05, -0.9)}) {
    for (double radius : {0.0, 2.0, 12.0}) {
      scene.settings.sun_direction = sun;
      scene.settings.sun_angular_radius_deg = radius;
      const Integrator integrator(scene.settings, scene.scene, scene.by_geometry);
      for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p(1200.0f * uniform() - 600.0f, 0.004f * uniform(), 1200.0f * uniform() - 600.0f);
        const bool full = integrator.sunMayBeBlocked(p);
        ASSERT_EQ(integrator.groundSunMayBeBlocked(p), full) << "sun " << sun.x << " " << sun.y << " " << sun.z
                                                             << " radius " << radius << " at " << p.x << " " << p.z;
        (full ? blocked : open) += 1;
        excluded += integrator.groundSunRegionExcludes(p);
      }
    }
  }
  EXPECT_GT(blocked, 1000);
  EXPECT_GT(open, 100000);
  EXPECT_GT(excluded, open / 2);  // the rectangle answers most open ground without the full test
}

// On uneven ground the points lie anywhere between the lowest ground and the hill tops; the rectangle,
// measured from the lowest ground, must still agree with the full test everywhere it answers.
TEST(Integrator, TheGroundSunShortcutHoldsOverHills) {
  StreamScene scene(1);
  rig::HillsParams hills;
  hills.amplitude_cm = 80.0;
  const rig::Terrain terrain = rig::Terrain::hills(hills, "test");
  constexpr float kFloorCm = -80.0f;  // the hills' lowest possible point
  uint32_t state = 777u;
  auto uniform = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) * 0x1p-24f;
  };
  int blocked = 0, excluded = 0;
  for (const glm::dvec3 sun : {glm::dvec3(0.3, 0.8, 0.5), glm::dvec3(-0.7, 0.35, 0.1), glm::dvec3(0.2, 0.05, -0.9)}) {
    scene.settings.sun_direction = sun;
    const Integrator integrator(scene.settings, scene.scene, scene.by_geometry, &terrain, kFloorCm);
    for (int i = 0; i < 20000; ++i) {
      const glm::vec3 p(1200.0f * uniform() - 600.0f, kFloorCm + 160.0f * uniform(), 1200.0f * uniform() - 600.0f);
      const bool full = integrator.sunMayBeBlocked(p);
      ASSERT_EQ(integrator.groundSunMayBeBlocked(p), full) << "at " << p.x << " " << p.y << " " << p.z;
      blocked += full;
      excluded += integrator.groundSunRegionExcludes(p);
    }
  }
  EXPECT_GT(blocked, 300);      // both answers are exercised
  EXPECT_GT(excluded, 20000);
}


// A ridge across the sun (issue 35, terrain you can see): a prism along z, 200 cm high at x = 0 with
// 45-degree faces down to the flat ground at x = -200 and x = 200, and flat ground out to 50 m. The
// sun shines from +x. Seen straight down through the renderer, a few pixels around one ground point.
struct RidgeScene {
  static constexpr double kCrestCm = 200.0, kHalfWidthCm = 200.0, kExtentCm = 5000.0;
  RenderSettings settings;
  std::unique_ptr<Renderer> renderer;

  explicit RidgeScene(double sun_elevation_deg) {
    settings.width = settings.height = 4;
    settings.samples_per_pixel = 4;
    settings.light_samples = 4;
    settings.ao_samples = 4;
    settings.threads = 1;
    settings.passes = false;
    const double e = sun_elevation_deg * std::numbers::pi / 180.0;
    settings.sun_direction = {std::cos(e), std::sin(e), 0.0};
    settings.ground_color_a = settings.ground_color_b = glm::vec3(0.3f);  // no checker: one albedo
    renderer = std::make_unique<Renderer>(settings);
    const double x[5] = {-kExtentCm, -kHalfWidthCm, 0.0, kHalfWidthCm, kExtentCm};
    const double y[5] = {0.0, 0.0, kCrestCm, 0.0, 0.0};
    std::vector<glm::dvec3> vertices;
    for (int i = 0; i < 5; ++i) vertices.push_back({x[i], y[i], -kExtentCm}), vertices.push_back({x[i], y[i], kExtentCm});
    std::vector<uint32_t> indices;
    for (uint32_t i = 0; i < 4; ++i) {  // counter-clockwise seen from above
      const uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
      indices.insert(indices.end(), {a, b, d, a, d, c});
    }
    auto mesh = std::make_shared<const rig::TerrainMesh>(vertices, indices, "ridge");
    renderer->setTerrain(std::make_shared<const rig::Terrain>(rig::Terrain::mesh(mesh)),
                         GroundRegion{-3000.0, -500.0, 3000.0, 500.0});
  }
  // The ridge's height at x.
  static double height(double x) { return std::max(0.0, kCrestCm - std::abs(x) * kCrestCm / kHalfWidthCm); }

  void addSphere(glm::vec3 center, float radius) {
    const testing::TestMesh sphere = testing::makeSphere(center, radius, 16, 32, {0.6f, 0.6f, 0.6f});
    MeshDesc desc;
    desc.indices = sphere.indices;
    desc.colors = sphere.colors;
    desc.vertex_count = sphere.positions.size();
    desc.rest_positions = sphere.positions;
    renderer->updateMesh(renderer->addMesh(desc), sphere.positions, sphere.normals);
  }

  // Mean red radiance of a 4 x 4 pixel, 2 cm square view straight down onto (x, y, z).
  float redAt(double x, double y, double z) {
    scene::Camera camera;
    camera.projection = scene::Camera::Projection::Orthographic;
    camera.position = {x, y + 1000.0, z};
    camera.target = {x, y, z};
    camera.up = {0.0, 0.0, -1.0};
    camera.ortho_height_cm = 2.0;
    const Image image = renderer->render(camera, 1);
    float sum = 0.0f;
    for (const glm::vec4& p : image.rgba) sum += p.x;
    return sum / float(image.rgba.size());
  }
};

// Hand-worked light (RenderSettings' defaults): the sun's red radiance 1.8 (strength 1.8, colour 1.0), the
// sky's red irradiance / pi on an upward surface horizon + 0.8 (zenith - horizon) = 0.6 + 0.8 (0.22 - 0.6)
// = 0.296 (SkyGradient::upwardIrradianceOverPi), the ground's albedo 0.3 and matte.
constexpr float kSunRed = 1.8f, kSkyRed = 0.296f, kGroundAlbedo = 0.3f;

TEST(Integrator, TheSunnyFaceOfAHillIsBrighterThanItsShadedFace) {
  // Sun 30 degrees up from +x: the face toward it (normal (1, 1, 0) / sqrt 2) takes cos = (cos 30 + sin
  // 30) / sqrt 2 = 0.966 of the sun, the face away (-1, 1, 0) / sqrt 2 none (cos < 0), flat ground sin 30
  // = 0.5. The faces see the same sky (the sky is not tilted with the ground): the difference is the sun's.
  RidgeScene ridge(30.0);
  const float sunny = ridge.redAt(100.0, RidgeScene::height(100.0), 0.0);
  const float shaded = ridge.redAt(-100.0, RidgeScene::height(-100.0), 0.0);
  const float flat = ridge.redAt(-2500.0, 0.0, 0.0);
  EXPECT_NEAR(sunny - shaded, kGroundAlbedo * kSunRed * 0.9659f, 0.02f);
  EXPECT_NEAR(flat, kGroundAlbedo * (kSunRed * 0.5f + kSkyRed), 0.01f);
}

TEST(Integrator, GroundInAHillsShadowGetsNoDirectSun) {
  // Sun 20 degrees up from +x (tan 20 = 0.364; the disc's highest ray, 22 degrees, tan 0.404). From the
  // ground at x = -400 a ray reaches the crest's x = 0 at most 400 * 0.404 = 162 cm up, under the 200 cm
  // crest: the whole disc is behind the ridge and only the sky lights it, 0.3 * 0.296. From x = -2500 the
  // lowest ray (18 degrees, tan 0.325) passes the crest 812 cm up: the full sun, 0.3 (1.8 sin 20 + 0.296).
  RidgeScene ridge(20.0);
  EXPECT_NEAR(ridge.redAt(-400.0, 0.0, 0.0), kGroundAlbedo * kSkyRed, 0.005f);
  EXPECT_NEAR(ridge.redAt(-2500.0, 0.0, 0.0), kGroundAlbedo * (kSunRed * 0.3420f + kSkyRed), 0.01f);
}

TEST(Integrator, ACharacterInAHillsShadowIsDarker) {
  // Two grey spheres (radius 10, albedo 0.6, specular 0.04) resting on the flat ground, one at x = -400
  // behind the ridge, one at x = -2500 in the open. The shaded one's top, 20 cm up, sees the crest's
  // x = 0 under the disc's highest ray (20 + 400 * 0.404 = 182 cm < 200): no sun, the sky alone. The open
  // top takes 0.96 * 0.6 * 1.8 sin 20 of the sun on top of its sky.
  RidgeScene ridge(20.0);
  ridge.addSphere({-400.0f, 10.0f, 0.0f}, 10.0f);
  ridge.addSphere({-2500.0f, 10.0f, 0.0f}, 10.0f);
  const float diffuse = 0.96f * 0.6f;
  const float shaded = ridge.redAt(-400.0, 20.0, 0.0), open = ridge.redAt(-2500.0, 20.0, 0.0);
  EXPECT_LT(shaded, diffuse * kSkyRed * 1.15f);  // the sky alone (sampled: a margin for its noise)
  EXPECT_GT(open - shaded, 0.8f * diffuse * kSunRed * 0.3420f);
}

}  // namespace
}  // namespace stirrup::render
