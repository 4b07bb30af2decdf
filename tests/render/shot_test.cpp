#include "render/shot.h"

#include <cmath>

#include <gtest/gtest.h>

#include "render/scene.h"
#include "rig/motion/clip_factory.h"

namespace stirrup::render {
namespace {

// A path over rolling hills (issue 15), as a scene file gives it.
SceneSpec pathOverHills() {
  return parseScene(nlohmann::json::parse(R"({
    "name": "path1",
    "clip": {"generator": "path", "points": [[0,0],[2000,0],[3500,1000],[3500,3000]],
             "speed": [[0,380],[40,380]]},
    "terrain": {"hills": {"seed": 3, "amplitude_cm": 80, "wavelength_cm": 3000, "octaves": 2}},
    "fps": 24, "frames": "1-240", "resolution": [32, 32], "quality": {"samples": 1}})"),
                    "path1.json");
}

// The shot renders its scene's terrain, finely meshed along the horse's track: looking straight down
// on the track where the horse is at a later frame (so no character is in the way), the ground in
// the depth pass lies on Terrain::height to half a centimetre, plus the slope times the sample's jitter.
TEST(Shot, StandsTheHorseOnTheSceneTerrain) {
  const SceneSpec scene = pathOverHills();
  ASSERT_TRUE(scene.terrain && !scene.terrain->flat());
  const auto clip = rig::makeClip(scene.clip);
  constexpr double kViewCm = 16.0, kTopCm = 1000.0, kOnSurfaceCm = 0.5;
  const double jitter_cm = 2.0 * kViewCm / scene.height;  // the tent filter reaches a pixel either side
  for (int later : {120, 200}) {
    const rig::HorseFrame h = clip->sample(frameTime(scene, later));
    // Off the plane y = 0 by more than the tolerance, so the flat ground would fail here.
    ASSERT_GT(std::abs(scene.terrain->height(h.travel_cm, h.travel_z_cm)), 5.0) << "frame " << later;
    CameraSpec down;
    down.motion = "fixed";
    down.follow = false;
    down.orthographic = true;
    down.ortho_height_cm = kViewCm;
    down.position = {h.travel_cm, kTopCm, h.travel_z_cm};
    down.target = {h.travel_cm, 0.0, h.travel_z_cm};
    down.up = {0.0, 0.0, -1.0};
    Shot shot(scene, resolveProfile(scene), down, 1);
    const Image img = shot.renderFrame(1);  // the horse is still at the start
    const double cm_per_px = kViewCm / scene.height;
    for (int py = 0; py < img.height; ++py) {
      for (int px = 0; px < img.width; ++px) {
        const std::size_t i = std::size_t(py) * img.width + px;
        ASSERT_EQ(img.object_id[i], uint32_t(ObjectId::Ground));
        const double x = h.travel_cm + (px + 0.5 - 0.5 * img.width) * cm_per_px;
        const double z = h.travel_z_cm + (py + 0.5 - 0.5 * img.height) * cm_per_px;
        double dx = 0.0, dz = 0.0;
        scene.terrain->gradient(x, z, dx, dz);
        EXPECT_NEAR(kTopCm - img.depth[i], scene.terrain->height(x, z), kOnSurfaceCm + std::hypot(dx, dz) * jitter_cm)
            << "frame " << later << " at " << x << ", " << z;
      }
    }
  }
}

// Columns whose bottom row is brighter than the row four above it (by 0.06, a tenth of the sky): a
// light band along the bottom edge shows in most columns, the checker's and the horse's own shading
// in a few (up to 8% of them in these frames).
int bandColumns(const Image& img) {
  auto luminance = [&](int x, int y) {
    const glm::vec4& c = img.at(x, y);
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
  };
  int band = 0;
  for (int x = 0; x < img.width; ++x) band += luminance(x, img.height - 1) > luminance(x, img.height - 5) + 0.06f;
  return band;
}

// Issue 18: the close view of the rear showed a light band at its bottom edge. Through the whole rear,
// the bottom rows are the ground and the horse as the rows above them are, never a band; and the
// check itself sees a band when there is one.
TEST(Shot, TheRearsCloseViewHasNoLightBandAtTheBottom) {
  SceneSpec scene = loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/rear.json");
  scene.width = 192, scene.height = 108, scene.samples = 4, scene.light_samples = 1, scene.ao_samples = 1;
  Shot shot(scene, resolveProfile(scene), findCamera(scene, "close"), 0);
  for (int frame : {1, 30, 45, 58, 70, 85, 96}) {
    Image img = shot.renderFrame(frame);
    EXPECT_LT(bandColumns(img), img.width / 4) << "frame " << frame;
    if (frame == 58) {  // the rear at its height: a band painted in is found
      for (int x = 0; x < img.width; ++x) img.at(x, img.height - 1) += glm::vec4(0.3f, 0.3f, 0.3f, 0.0f);
      EXPECT_GT(bandColumns(img), img.width / 2);
    }
  }
}

}  // namespace
}  // namespace stirrup::render
