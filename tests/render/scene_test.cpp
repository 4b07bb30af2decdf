#include "render/scene.h"

#include <gtest/gtest.h>

#include "rig/error.h"

namespace stirrup::render {
namespace {

std::string errorOf(const std::string& json_text) {
  try {
    parseScene(nlohmann::json::parse(json_text), "scenes/x.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Scene, EmptySceneTakesEveryDefault) {
  const SceneSpec s = parseScene(nlohmann::json::object(), "scenes/x.json");
  EXPECT_EQ(s.name, "x");
  EXPECT_EQ(s.fps, 24.0);
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 360);
  EXPECT_EQ(s.profile, "thesis");
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_TRUE(s.cameras[0].orthographic);
  EXPECT_EQ(s.output, "out/x");
}

TEST(Scene, ReadsEveryField) {
  const SceneSpec s = parseScene(nlohmann::json::parse(R"({
    "name": "t", "clip": {"generator": "trot", "speed_cm_s": 300, "duty_factor": 0.42},
    "profile": "novice", "profile_overrides": {"a": 1}, "fps": 30, "frames": "1-10x2",
    "resolution": [320, 180], "quality": {"samples": 4, "light_samples": 2, "ao_samples": 1},
    "sun": {"direction": [0, 1, 0], "angular_radius": 1},
    "cameras": [{"name": "a"}, {"name": "p", "type": "perspective", "fov": 40, "follow": false}],
    "output": "o"})"),
                                 "s.json");
  EXPECT_EQ(s.gait.speed_cm_s, 300.0);
  EXPECT_EQ(s.gait.duty_factor[3], 0.42);
  EXPECT_EQ(s.profile, "novice");
  EXPECT_EQ(s.profile_overrides["a"], 1);
  EXPECT_EQ(s.fps, 30.0);
  EXPECT_EQ(s.frames, "1-10x2");
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.samples, 4);
  EXPECT_EQ(s.sun_angular_radius_deg, 1.0);
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_FALSE(s.cameras[1].orthographic);
  EXPECT_EQ(s.cameras[1].fov_deg, 40.0);
  EXPECT_FALSE(s.cameras[1].follow);
  EXPECT_EQ(&findCamera(s, "p"), &s.cameras[1]);
  EXPECT_THROW(findCamera(s, "nope"), InputError);
}

TEST(Scene, WrongTypeNamesFileFieldAndValue) {
  EXPECT_EQ(errorOf(R"({"cameras": [{}, {"fov": "wide"}]})"),
            "scenes/x.json: cameras[1].fov: expected a number, got \"wide\"");
  EXPECT_EQ(errorOf(R"({"fps": "24"})"), "scenes/x.json: fps: expected a number, got \"24\"");
  EXPECT_EQ(errorOf(R"({"resolution": [640]})"),
            "scenes/x.json: resolution: expected [width, height] in whole pixels, got an array of 1");
  EXPECT_EQ(errorOf(R"({"cameras": [{"position": [1, "a", 2]}]})"),
            "scenes/x.json: cameras[0].position[1]: expected a number, got \"a\"");
  EXPECT_EQ(errorOf(R"({"clip": {"generator": 3}})"), "scenes/x.json: clip.generator: expected a string, got 3");
}

TEST(Scene, UnknownFieldIsAnError) {
  EXPECT_EQ(errorOf(R"({"fsp": 24})"), "scenes/x.json: fsp: unknown field");
  EXPECT_EQ(errorOf(R"({"cameras": [{"fow": 30}]})"), "scenes/x.json: cameras[0].fow: unknown field");
  EXPECT_EQ(errorOf(R"({"quality": {"spp": 3}})"), "scenes/x.json: quality.spp: unknown field");
}

TEST(Scene, OutOfRangeValuesAreErrors) {
  EXPECT_EQ(errorOf(R"({"cameras": [{"type": "fisheye"}]})"),
            "scenes/x.json: cameras[0].type: expected \"orthographic\" or \"perspective\", got \"fisheye\"");
  EXPECT_EQ(errorOf(R"({"frames": "10-1"})"), "scenes/x.json: frames: \"10-1\": expected FIRST <= LAST");
  EXPECT_EQ(errorOf(R"({"fps": 0})"), "scenes/x.json: fps: expected frames per second between 0 and 240");
  EXPECT_EQ(errorOf(R"({"cameras": []})"),
            "scenes/x.json: cameras: expected a non-empty array of cameras, got an array of 0");
  EXPECT_EQ(errorOf(R"([1])"), "scenes/x.json: top level: expected an object, got an array of 1");
}

TEST(Scene, MissingFileNamesTheFile) {
  try {
    loadScene("/nonexistent/trot.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/nonexistent/trot.json: cannot open the file (expected a readable JSON file)");
  }
}

TEST(Scene, ShippedTrotSceneLoads) {
  const SceneSpec s = loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  EXPECT_EQ(s.name, "trot");
  EXPECT_EQ(s.cameras[0].name, "side");
  EXPECT_EQ(frameTime(s, 1), 0.0);
  EXPECT_DOUBLE_EQ(frameTime(s, 25), 1.0);
}

}  // namespace
}  // namespace stirrup::render
