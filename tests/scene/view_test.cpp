// Each view frames the horse and rider fully on every default scene: rendered small and fast, no pixel
// of the character matte may touch the image border on any frame shown, and the horse and the rider
// both show, at a stated fraction of the frame's height (kMinPairHeight; the close view's rider,
// kMinCloseRiderHeight).
#include "scene/view.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include "render/shot.h"
#include "render/tracer/renderer.h"
#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;

struct BorderCount {
  int matte = 0;      // border pixels with any horse or rider coverage
  int rider_top = 0;  // top-row pixels that show the rider
  int rider = 0;      // rider pixels anywhere
  int horse = 0;      // horse pixels anywhere
  // The bounds of the pixels showing the horse or the rider (both), and of the rider's alone, as
  // fractions of the frame's width and height (0 when none shows).
  double width = 0, height = 0, rider_width = 0, rider_height = 0;
};

BorderCount countBorder(const render::Image& im) {
  BorderCount c;
  EXPECT_EQ(im.matte.size(), im.pixelCount());
  int x0 = im.width, x1 = -1, y0 = im.height, y1 = -1, rx0 = im.width, rx1 = -1, ry0 = im.height, ry1 = -1;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const std::size_t i = std::size_t(y) * im.width + x;
      const bool rider = im.object_id[i] == static_cast<uint32_t>(render::ObjectId::Rider);
      const bool horse = im.object_id[i] == static_cast<uint32_t>(render::ObjectId::Horse);
      c.rider += rider;
      c.horse += horse;
      if (y == 0 && rider) ++c.rider_top;
      if ((x == 0 || y == 0 || x == im.width - 1 || y == im.height - 1) && im.matte[i] > 0.0f) ++c.matte;
      if (rider || horse) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      if (rider) rx0 = std::min(rx0, x), rx1 = std::max(rx1, x), ry0 = std::min(ry0, y), ry1 = std::max(ry1, y);
    }
  if (x1 >= 0) c.width = double(x1 - x0 + 1) / im.width, c.height = double(y1 - y0 + 1) / im.height;
  if (rx1 >= 0) c.rider_width = double(rx1 - rx0 + 1) / im.width, c.rider_height = double(ry1 - ry0 + 1) / im.height;
  return c;
}

// How large the framing shows the pair, stated. A view keeps every framed point frame_margin (12%)
// inside each border over all the frames it shows, so the pair's extents over the whole clip span 76%
// of the frame in their limiting direction; one frame's pair spans less by what the clip adds to its
// height, the jump's flight and the rear's rise at most about 150 cm on a pair 250 cm tall: at least
// 0.76 x 250 / 400 = 0.47 of the frame's height. Measured lowest over every default scene and view:
// 0.46 (the jump's turntable), 0.48 (its side and perspective views), 0.65 (turntable_pose).
constexpr double kMinPairHeight = 0.40;
// close frames the upper 55% of the rider into the same 76%: measured lowest 0.54 (the jump's landing).
constexpr double kMinCloseRiderHeight = 0.45;

class ViewFraming : public ::testing::TestWithParam<std::string> {};

TEST_P(ViewFraming, EveryViewKeepsHorseAndRiderInFrame) {
  SceneSpec scene = loadScene(fs::path(STIRRUP_SOURCE_DIR) / "scenes" / (GetParam() + ".json"));
  scene.width = 96;
  scene.height = 54;
  scene.samples = 1;
  scene.light_samples = 1;
  scene.ao_samples = 1;
  const rig::RigProfile profile = resolveProfile(scene);
  for (const char* name : {"side", "persp", "close", "turntable", "turntable_pose"}) {
    const CameraSpec& camera = findCamera(scene, name);
    ASSERT_FALSE(camera.view.empty()) << name;
    render::Shot shot(scene, profile, camera, 0);
    std::vector<int> frames = framingFrames(shot.camera(), scene);
    int shown = 0;
    for (std::size_t k = 0; k < frames.size(); k += 6) {
      const int f = frames[k];
      const render::Image im = shot.renderFrame(f);
      const BorderCount c = countBorder(im);
      if (std::string(name) == "close") {
        // close frames the rider above the saddle: the horse runs off the frame, the rider's head never.
        EXPECT_GT(c.rider, 0) << GetParam() << " close frame " << f;
        EXPECT_EQ(c.rider_top, 0) << GetParam() << " close frame " << f << ": the rider touches the top";
        EXPECT_GE(c.rider_height, kMinCloseRiderHeight) << GetParam() << " close frame " << f << ": the rider too small";
      } else {
        EXPECT_EQ(c.matte, 0) << GetParam() << " " << name << " frame " << f
                              << ": horse or rider on the image border";
        // Both in the picture, and large in it: an empty or distant frame touches no border either.
        EXPECT_GT(c.horse, 0) << GetParam() << " " << name << " frame " << f << ": no horse";
        EXPECT_GT(c.rider, 0) << GetParam() << " " << name << " frame " << f << ": no rider";
        EXPECT_GE(c.height, kMinPairHeight) << GetParam() << " " << name << " frame " << f << ": horse and rider too small";
      }
      ++shown;
    }
    EXPECT_GT(shown, 3) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(DefaultScenes, ViewFraming,
                         ::testing::Values("walk", "trot", "canter", "gallop", "stop", "jump", "rear", "buck"));

TEST(ViewPreset, SetsTheLensAndMotionOfEachView) {
  CameraSpec side;
  side.view = "side";
  applyViewPreset(side);
  EXPECT_TRUE(side.orthographic);
  EXPECT_EQ(side.motion, "follow");
  CameraSpec persp;
  persp.view = "persp";
  applyViewPreset(persp);
  EXPECT_FALSE(persp.orthographic);
  EXPECT_NEAR(persp.fov_deg, 2.0 * std::atan(12.0 / 50.0) * 180.0 / 3.14159265358979323846, 1e-9);
  CameraSpec turn;
  turn.view = "turntable";
  applyViewPreset(turn);
  EXPECT_EQ(turn.motion, "orbit");
  EXPECT_EQ(turn.orbit_frames, 96);
  CameraSpec top;
  top.view = "top";
  applyViewPreset(top);
  EXPECT_TRUE(top.orthographic);
  EXPECT_EQ(top.motion, "fixed");
}

// Through the turns and over the hills of a path clip the follow views, turning with the horse, still
// keep horse and rider whole in frame (the framing measures them in the camera's turning frame).
TEST(PathViewFraming, FollowViewsKeepAHorseOnAPathInFrame) {
  const SceneSpec scene = parseScene(nlohmann::json::parse(R"({
    "name": "path1",
    "clip": {"generator": "path", "points": [[0,0],[2000,0],[3500,1000],[3500,3000],[2000,4000],[0,4000]],
             "speed": [[0,150],[4,150],[7,380],[12,380],[15,520],[40,520]]},
    "terrain": {"hills": {"seed": 3, "amplitude_cm": 80, "wavelength_cm": 3000, "octaves": 2}},
    "fps": 24, "frames": "1-480x8", "resolution": [96, 54], "quality": {"samples": 1},
    "cameras": [{"name": "side", "view": "side"}, {"name": "persp", "view": "persp"},
                {"name": "close", "view": "close"}]})"),
                                     "path1.json");
  const rig::RigProfile profile = resolveProfile(scene);
  const auto clip = scene::makeClip(scene.clip);
  const std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
  double turned = 0.0;
  for (int f : frames) turned = std::max(turned, std::abs(clip->sample(frameTime(scene, f)).heading_deg));
  ASSERT_GT(turned, 90.0) << "the clip does turn";
  for (const char* name : {"side", "persp", "close"}) {
    render::Shot shot(scene, profile, findCamera(scene, name), 0);
    for (std::size_t k = 0; k < frames.size(); k += 3) {
      const BorderCount c = countBorder(shot.renderFrame(frames[k]));
      if (std::string(name) == "close") {
        EXPECT_GT(c.rider, 0) << "close frame " << frames[k];
        EXPECT_EQ(c.rider_top, 0) << "close frame " << frames[k] << ": the rider touches the top";
      } else {
        EXPECT_EQ(c.matte, 0) << name << " frame " << frames[k] << ": horse or rider on the image border";
      }
    }
  }
}

// A figure eight (issue 15): two loops of a path clip, 48 m by 20 m, over hills.
SceneSpec figureEight() {
  return parseScene(nlohmann::json::parse(R"({
    "name": "eight",
    "clip": {"generator": "path",
             "points": [[0,0],[1200,-1000],[2400,0],[1200,1000],[0,0],[-1200,-1000],[-2400,0],[-1200,1000],[0,0]],
             "speed": [[0,380],[40,380]]},
    "terrain": {"hills": {"seed": 5, "amplitude_cm": 60, "wavelength_cm": 2500, "octaves": 2}},
    "fps": 24, "frames": "1-720x8", "resolution": [160, 90], "quality": {"samples": 1},
    "cameras": [{"name": "top", "view": "top"}]})"),
                    "eight.json");
}

// The top view looks straight down with +X to the right and +Z down, and holds the whole ground track
// of the scene's frames: every frame's travel (sampled here from the clip, every frame, not only the
// framed ones) is inside the picture with most of the margin to spare, and the track fills it.
TEST(TopView, FramesTheWholeTrackFromAbove) {
  const SceneSpec scene = figureEight();
  const rig::RigProfile profile = resolveProfile(scene);
  render::Shot shot(scene, profile, findCamera(scene, "top"), 0);
  const auto clip = scene::makeClip(scene.clip);
  const CameraFrame first(shot.cameraAtFrame(1), scene.width, scene.height);
  EXPECT_NEAR(glm::length(first.forward() - glm::dvec3(0.0, -1.0, 0.0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(first.right() - glm::dvec3(1.0, 0.0, 0.0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(first.upward() - glm::dvec3(0.0, 0.0, -1.0)), 0.0, 1e-9);
  const Camera cam = shot.cameraAtFrame(1);
  const double half_h = 0.5 * cam.ortho_height_cm, half_w = half_h * scene.width / scene.height;
  double u_lo = 1.0, u_hi = 0.0;
  const std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
  for (int f = frames.front(); f <= frames.back(); ++f) {
    EXPECT_EQ(shot.cameraAtFrame(f).position, cam.position) << "the top view is fixed";
    const rig::HorseFrame h = clip->sample(frameTime(scene, f));
    const double u = 0.5 + 0.5 * (h.travel_cm - cam.target.x) / half_w;     // 0 left, 1 right
    const double v = 0.5 + 0.5 * (h.travel_z_cm - cam.target.z) / half_h;  // 0 top, 1 bottom
    const double inside = 0.5 * shot.camera().frame_margin;
    EXPECT_GT(std::min({u, v, 1.0 - u, 1.0 - v}), inside) << "frame " << f << " at " << h.travel_cm << ", " << h.travel_z_cm;
    u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u);
  }
  EXPECT_GT(u_hi - u_lo, 0.6) << "the track fills the picture's width";
}

// A crowd (issue 19) of six pairs in two ranks of three files, through a turn: each view with no
// follow_pair frames the whole crowd (every pair's skinned vertices, projected here through the
// camera's own definition, inside the picture; no matte on the border, the close view's riders under
// the top), and a view that follows one pair frames that pair alone, as a single pair's view does.
SceneSpec crowdInATurn() {
  return parseScene(nlohmann::json::parse(R"({
    "name": "crowd6", "frames": "1-160x8", "resolution": [160, 90], "quality": {"samples": 1},
    "crowd": {"pairs": 6, "seed": 11,
              "lead": {"points": [[0, 0], [2000, 0], [3500, 1000]], "speed": [[0, 400]]},
              "formation": {"files": 3, "file_spacing_cm": 320, "rank_spacing_cm": 900, "jitter_cm": 10},
              "profiles": {"thesis": 1, "english": 1, "novice": 1}},
    "cameras": [{"name": "side", "view": "side"}, {"name": "persp", "view": "persp"},
                {"name": "close", "view": "close"}, {"name": "turntable", "view": "turntable"},
                {"name": "top", "view": "top"}, {"name": "side4", "view": "side", "follow_pair": 4},
                {"name": "persp4", "view": "persp", "follow_pair": 4}]})"),
                    std::string(STIRRUP_SOURCE_DIR) + "/scenes/crowd6.json");
}

// Where a point falls on the film, u and v in [0, 1] (v down), by the camera's definition
// (scene/camera.h), not the renderer's CameraFrame.
glm::dvec2 filmPoint(const Camera& c, double aspect, const glm::dvec3& p) {
  const glm::dvec3 f = glm::normalize(c.target - c.position), r = glm::normalize(glm::cross(f, c.up));
  const glm::dvec3 u = glm::cross(r, f), q = p - c.position;
  double x = glm::dot(q, r), y = glm::dot(q, u), h = 0.5 * c.ortho_height_cm;
  if (c.projection == Camera::Projection::Perspective) {
    const double z = glm::dot(q, f);
    if (z <= 0.0) return {-1.0, -1.0};
    x /= z, y /= z, h = std::tan(0.5 * glm::radians(c.fov_deg));
  }
  return {0.5 + 0.5 * x / (h * aspect), 0.5 - 0.5 * y / h};
}

TEST(CrowdViewFraming, ViewsWithoutAFollowedPairFrameTheWholeCrowd) {
  const SceneSpec scene = crowdInATurn();
  ASSERT_EQ(scene.pairs.size(), 6u);
  const rig::RigProfile profile = resolveProfile(scene);
  const double aspect = double(scene.width) / scene.height;
  for (const char* name : {"side", "persp", "close", "turntable", "top"}) {
    render::Shot shot(scene, profile, findCamera(scene, name), 0);
    const std::vector<int> frames = framingFrames(shot.camera(), scene);
    for (std::size_t k = 0; k < frames.size(); k += 4) {
      const int f = frames[k];
      const BorderCount c = countBorder(shot.renderFrame(f));
      const Camera cam = shot.cameraAtFrame(f);
      if (std::string(name) == "close") {
        EXPECT_GT(c.rider, 0) << "close frame " << f;
        EXPECT_EQ(c.rider_top, 0) << "close frame " << f << ": a rider touches the top";
        continue;
      }
      EXPECT_EQ(c.matte, 0) << name << " frame " << f << ": a horse or rider on the image border";
      if (cam.projection == Camera::Projection::Orthographic && std::string(name) != "top") {
        // Its film's lower edge stands above the ground (flat here), so no ray starts under it.
        const glm::dvec3 fwd = glm::normalize(cam.target - cam.position);
        const glm::dvec3 up = glm::cross(glm::normalize(glm::cross(fwd, cam.up)), fwd);
        EXPECT_GT(cam.position.y - 0.5 * cam.ortho_height_cm * up.y, 0.0) << name << " frame " << f;
      }
      for (int pair = 0; pair < shot.pairCount(); ++pair) {
        std::vector<glm::dvec3> horse, rider;
        shot.pairPoints(pair, f, 7, horse, rider);
        horse.insert(horse.end(), rider.begin(), rider.end());
        for (const glm::dvec3& p : horse) {
          const glm::dvec2 uv = filmPoint(cam, aspect, p);
          ASSERT_TRUE(uv.x > 0.0 && uv.x < 1.0 && uv.y > 0.0 && uv.y < 1.0)
              << name << " frame " << f << " pair " << pair << " at " << uv.x << ", " << uv.y;
        }
      }
    }
  }
}

TEST(CrowdViewFraming, AViewFollowingAPairFramesThatPair) {
  const SceneSpec scene = crowdInATurn();
  const rig::RigProfile profile = resolveProfile(scene);
  const double aspect = double(scene.width) / scene.height;
  render::Shot crowd_side(scene, profile, findCamera(scene, "side"), 0);
  render::Shot side(scene, profile, findCamera(scene, "side4"), 0), persp(scene, profile, findCamera(scene, "persp4"), 0);
  // The followed pair fills the frame as one pair does (a horse and rider in about 3.2 m of height
  // with margins), far tighter than the whole crowd's.
  EXPECT_LT(side.camera().ortho_height_cm, 0.6 * crowd_side.camera().ortho_height_cm);
  render::Shot crowd_persp(scene, profile, findCamera(scene, "persp"), 0);
  // The width of the followed pair's points on the film, through a camera.
  const auto width = [&](render::Shot& shot, const Camera& cam, int f) {
    std::vector<glm::dvec3> horse, rider;
    shot.pairPoints(4, f, 7, horse, rider);
    double lo = 1, hi = 0;
    for (const glm::dvec3& p : horse) {
      const glm::dvec2 uv = filmPoint(cam, aspect, p);
      lo = std::min(lo, uv.x), hi = std::max(hi, uv.x);
    }
    return hi - lo;
  };
  for (auto [shot, whole] : {std::pair{&side, &crowd_side}, std::pair{&persp, &crowd_persp}}) {
    for (int f : scene::parseFrameList(scene.frames, "frames")) {
      std::vector<glm::dvec3> horse, rider;
      shot->pairPoints(4, f, 7, horse, rider);
      horse.insert(horse.end(), rider.begin(), rider.end());
      double lo = 1, hi = 0;
      const Camera cam = shot->cameraAtFrame(f);
      for (const glm::dvec3& p : horse) {
        const glm::dvec2 uv = filmPoint(cam, aspect, p);
        ASSERT_TRUE(uv.x > 0.0 && uv.x < 1.0 && uv.y > 0.0 && uv.y < 1.0) << "frame " << f << " at " << uv.x << ", " << uv.y;
        lo = std::min(lo, uv.x), hi = std::max(hi, uv.x);
      }
      // A third of the frame or more, as one pair's view (its horse's length), and at least twice what
      // it takes in the view of the whole crowd.
      EXPECT_GT(hi - lo, 0.3) << shot->camera().name << " frame " << f << ": the followed pair fills the frame";
      EXPECT_GT(width(*shot, cam, f), 2.0 * width(*whole, whole->cameraAtFrame(f), f)) << shot->camera().name << " frame " << f;
    }
  }
}

}  // namespace
}  // namespace stirrup::scene
