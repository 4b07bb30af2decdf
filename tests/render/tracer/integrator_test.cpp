// The integrator traces a tile as ray streams in batches of pixels. A pixel's result must not depend
// on which tile or batch it falls in, or on how many other pixels share its streams.
#include "render/tracer/integrator.h"

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "tests/render/test_meshes.h"

namespace stirrup::render {
namespace {

// A sphere resting near the ground, seen from above and in front, so tiles hold sky, ground, the
// sphere's edge and its shadow.
struct StreamScene {
  RenderSettings settings;
  Camera camera;
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
    const CameraFrame frame(camera, settings.width, settings.height);
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

}  // namespace
}  // namespace stirrup::render
