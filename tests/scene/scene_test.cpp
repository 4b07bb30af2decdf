#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "rig/bake.h"
#include "rig/io/character_mapping_json.h"
#include "rig/io/gltf_clip.h"
#include "rig/motion/gait_reference.h"
#include "rig/motion/path_clip.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "scene/camera.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "tests/rig/default_characters.h"

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

std::string errorOf(const std::string& json_text) {
  return stirrup::test::errorOf([&] { parseScene(nlohmann::json::parse(json_text), "scenes/x.json"); });
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
    "profile": "novice", "profile_overrides": {"eq7.lift_limit": 9}, "fps": 30, "frames": "1-10x2",
    "resolution": [320, 180], "quality": {"samples": 4, "light_samples": 2, "ao_samples": 1},
    "sun": {"direction": [0, 1, 0], "angular_radius": 1},
    "haze": {"visibility_cm": 30000, "ortho_depth_cm": 900},
    "cameras": [{"name": "a"}, {"name": "p", "type": "perspective", "fov": 40, "follow": false}],
    "output": "o"})"),
                                 "s.json");
  EXPECT_EQ(s.gait.speed_cm_s, 300.0);
  EXPECT_EQ(s.gait.duty_factor[3], 0.42);
  EXPECT_EQ(s.profile, "novice");
  EXPECT_EQ(s.profile_overrides["eq7.lift_limit"], 9);
  EXPECT_EQ(s.fps, 30.0);
  EXPECT_EQ(s.frames, "1-10x2");
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.samples, 4);
  EXPECT_EQ(s.sun_angular_radius_deg, 1.0);
  EXPECT_EQ(s.haze_visibility_cm, 30000.0);
  EXPECT_EQ(s.haze_ortho_depth_cm, 900.0);
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_FALSE(s.cameras[1].orthographic);
  EXPECT_EQ(s.cameras[1].fov_deg, 40.0);
  EXPECT_FALSE(s.cameras[1].follow);
  EXPECT_EQ(&findCamera(s, "p"), &s.cameras[1]);
  EXPECT_THROW(findCamera(s, "nope"), rig::InputError);
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
  EXPECT_EQ(errorOf(R"({"fps": 0})"), "scenes/x.json: fps: expected frames per second from 1 to 240, got 0");
  EXPECT_EQ(errorOf(R"({"haze": {"visibility_cm": 500000}})"),
            "scenes/x.json: haze.visibility_cm: expected centimetres from 100 to 100000 (the ground ends 1 km out), got 500000");
  EXPECT_EQ(errorOf(R"({"haze": {"ortho_depth_cm": "far"}})"),
            "scenes/x.json: haze.ortho_depth_cm: expected a number, got \"far\"");
  EXPECT_EQ(errorOf(R"({"haze": {"fog": 1}})"), "scenes/x.json: haze.fog: unknown field");
  EXPECT_EQ(errorOf(R"({"cameras": []})"),
            "scenes/x.json: cameras: expected a non-empty array of cameras, got an array of 0");
  EXPECT_EQ(errorOf(R"([1])"), "scenes/x.json: top level: expected an object, got an array of 1");
}

TEST(Scene, MissingFileNamesTheFile) {
  try {
    loadScene("/nonexistent/trot.json");
    FAIL();
  } catch (const rig::InputError& e) {
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

// Every shipped path scene (issue 15), as the renderer plays it (makeSceneClip, with its horse's rest
// hoof places): the travel frame within 1 cm of the curve through the points and heading within 1° of
// its direction of motion at every frame; every steady section inside gait-reference.md (a left lead
// mirrored); no planted hoof sliding or sinking (clip info's measure, in the world); the frames cover
// the whole clip.
TEST(Scene, ShippedPathScenesFollowTheirPathsAndPassTheReference) {
  int scenes = 0;
  for (const char* name : {"cross_country", "figure_eight", "trail"}) {
    const SceneSpec s = loadScene(std::string(STIRRUP_SOURCE_DIR "/scenes/") + name + ".json");
    const std::unique_ptr<rig::Clip> clip = makeSceneClip(s);
    const auto* path = dynamic_cast<const rig::PathClip*>(clip.get());
    ASSERT_NE(path, nullptr) << name;
    ++scenes;
    std::vector<glm::dvec2> dense;
    for (double d = 0; d <= path->path().length(); d += 1.0) dense.push_back(path->path().at(d).position);
    const std::vector<int> frames = scene::parseFrameList(s.frames, name);
    EXPECT_NEAR(frameTime(s, frames.back()), clip->duration(), 1.0 / s.fps) << name << ": the frames cover the clip";
    double worst_cm = 0, worst_deg = 0;
    for (int f : frames) {
      const double t = frameTime(s, f);
      const rig::HorseFrame h = clip->sample(t), a = clip->sample(t - 1e-3), b = clip->sample(t + 1e-3);
      double nearest = 1e9;
      for (const glm::dvec2& d : dense) nearest = std::min(nearest, glm::length(d - glm::dvec2(h.travel_cm, h.travel_z_cm)));
      worst_cm = std::max(worst_cm, nearest);
      const double moving = std::atan2(b.travel_z_cm - a.travel_z_cm, b.travel_cm - a.travel_cm) * 180.0 / std::numbers::pi;
      if (t > 1e-3) worst_deg = std::max(worst_deg, std::abs(std::remainder(h.heading_deg - moving, 360.0)));
    }
    EXPECT_LT(worst_cm, 1.0) << name;
    EXPECT_LT(worst_deg, 1.0) << name;
    const rig::MovementClip straight(path->movement());
    for (const rig::PathClip::Section& sec : path->sections()) {
      rig::ClipInfoOptions o;
      o.start_s = sec.start_s + 0.5 * sec.blend_in_s;
      o.end_s = sec.end_s - 0.5 * sec.blend_out_s;
      const bool leads = sec.gait == rig::PathGait::Canter || sec.gait == rig::PathGait::Gallop;
      o.mirror = leads && sec.lead == rig::Lead::Left;
      const auto ref = rig::gaitReference(rig::pathGaitName(sec.gait));
      ASSERT_TRUE(ref);
      for (const rig::Verdict& v : rig::clipVerdicts(rig::measureClip(straight, o), *ref))
        EXPECT_TRUE(v.ok) << name << " " << rig::pathGaitName(sec.gait) << " " << o.start_s << "-" << o.end_s << " s: " << v.key
                          << " = " << v.value;
    }
    EXPECT_TRUE(rig::measureClip(*clip).problems.empty()) << name;
  }
  EXPECT_EQ(scenes, 3);
}

}  // namespace
}  // namespace stirrup::scene

namespace stirrup::scene {
namespace {

// A crowd (issue 19): "crowd" generates the pairs, "riders" lists them; a scene without either keeps
// its one horse and rider.
constexpr const char* kCrowd = R"({"crowd": {"pairs": 6, "seed": 4,
    "lead": {"points": [[0, 0], [1500, 0]], "speed": [[0, 360]]},
    "formation": {"files": 3, "file_spacing_cm": 300, "rank_spacing_cm": 600, "jitter_cm": 10},
    "profiles": {"english": 1, "novice": 1}}})";

TEST(SceneCrowd, ASceneWithoutACrowdHasNoPairs) {
  const SceneSpec s = parseScene(nlohmann::json::object(), "scenes/x.json");
  EXPECT_FALSE(s.crowd.has_value());
  EXPECT_TRUE(s.pairs.empty());
  EXPECT_TRUE(loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/trail.json").pairs.empty());
}

TEST(SceneCrowd, ACrowdBlockGeneratesItsPairs) {
  const SceneSpec s = parseScene(nlohmann::json::parse(kCrowd), "scenes/x.json");
  ASSERT_TRUE(s.crowd.has_value());
  EXPECT_EQ(s.crowd->pairs, 6);
  ASSERT_EQ(s.pairs.size(), 6u);
  for (const rig::PairSpec& p : s.pairs) EXPECT_TRUE(p.profile == "english" || p.profile == "novice") << p.profile;
  // The same file gives the same crowd.
  const SceneSpec again = parseScene(nlohmann::json::parse(kCrowd), "scenes/x.json");
  for (std::size_t i = 0; i < s.pairs.size(); ++i) EXPECT_EQ(s.pairs[i].withers_height_cm, again.pairs[i].withers_height_cm);
}

TEST(SceneCrowd, ARidersListIsReadAndChecked) {
  const SceneSpec s = parseScene(nlohmann::json::parse(R"({"riders": [
      {"points": [[0, 0], [1000, 0]], "speed": [[0, 300]], "profile": "english", "withers_height_cm": 150},
      {"points": [[0, 400], [1000, 400]], "speed": [[0, 300]], "rider_height_cm": 185}]})"),
                                 "scenes/x.json");
  ASSERT_EQ(s.pairs.size(), 2u);
  EXPECT_EQ(s.pairs[0].profile, "english");
  EXPECT_EQ(s.pairs[0].withers_height_cm, 150.0);
  EXPECT_EQ(s.pairs[1].rider_height_cm, 185.0);
}

TEST(SceneCrowd, BadCrowdsAreOneLineErrors) {
  EXPECT_EQ(errorOf(R"({"crowd": {"pairs": 0, "lead": {"points": [[0, 0], [1500, 0]], "speed": [[0, 360]]}}})"),
            "scenes/x.json: crowd.pairs: expected a whole number from 1 to 200, got 0");
  EXPECT_EQ(errorOf(R"({"crowd": {"pairs": 500, "lead": {"points": [[0, 0], [1500, 0]], "speed": [[0, 360]]}}})"),
            "scenes/x.json: crowd.pairs: expected a whole number from 1 to 200, got 500");
  EXPECT_EQ(errorOf(R"({"crowd": {"lead": {"points": [[0, 0], [1500, 0]], "speed": [[0, 360]]},
                        "withers_height_cm": [120, 160]}})"),
            "scenes/x.json: crowd.withers_height_cm: expected a range [low, high] within 145 to 175 cm, got [120, 160]");
  EXPECT_EQ(errorOf(R"({"crowd": {"lead": {"points": [[0, 0], [1500, 0]], "speed": [[0, 360]]}, "profiles": {"rodeo": 1}}})"),
            "scenes/x.json: crowd.profiles.rodeo: expected one of thesis, english, novice");
  EXPECT_EQ(errorOf(R"({"crowd": {"lead": {"points": [[0, 0], [1500, 0]], "speed": [[0, 360]]}, "size": 3}})"),
            "scenes/x.json: crowd.size: unknown field");
  EXPECT_EQ(errorOf(R"({"riders": {}})"), "scenes/x.json: riders: expected a non-empty array of riders, got an object");
  EXPECT_EQ(errorOf(R"({"riders": [{"points": [[0, 0], [1000, 0]], "speed": [[0, 300]], "rider_height_cm": 200}]})"),
            "scenes/x.json: riders[0].rider_height_cm: expected 150 to 190 cm, got 200");
  EXPECT_EQ(errorOf(R"({"riders": [{"points": [[0, 0], [1000, 0]], "speed": [[0, 300]]},
                                   {"points": [[0, 50], [1000, 50]], "speed": [[0, 300]]}]})"),
            "scenes/x.json: riders: riders[0] and riders[1] overlap at frame 1 (0 s): expected paths that keep every two "
            "horses apart at every frame");
  EXPECT_EQ(errorOf(std::string(R"({"clip": {"generator": "walk"}, )") + (kCrowd + 1)),
            "scenes/x.json: clip: expected no clip beside \"crowd\" (each pair rides its own path)");
  EXPECT_EQ(errorOf(R"({"crowd": {"lead": {"points": [[0, 0], [1500, 0]], "speed": [[0, 360]]}},
                        "riders": [{"points": [[0, 0], [1000, 0]], "speed": [[0, 300]]}]})"),
            "scenes/x.json: riders: expected either \"crowd\" or \"riders\", not both");
}

// A crowd without "frames" plays its lead's whole ride: 1500 cm at 360 cm/s is 4.17 s, so at 24 fps
// frames 1 (t = 0) to 101 (t = 4.167 s). Given frames are kept, and a riders list keeps the default.
TEST(SceneCrowd, ACrowdPlaysItsLeadsRideUnlessFramesAreGiven) {
  EXPECT_EQ(parseScene(nlohmann::json::parse(kCrowd), "scenes/x.json").frames, "1-101");
  nlohmann::json given = nlohmann::json::parse(kCrowd);
  given["frames"] = "1-20";
  EXPECT_EQ(parseScene(given, "scenes/x.json").frames, "1-20");
  EXPECT_EQ(parseScene(nlohmann::json::parse(R"({"riders": [{"points": [[0, 0], [1000, 0]], "speed": [[0, 300]]}]})"),
                       "scenes/x.json")
                .frames,
            SceneSpec{}.frames);
}

// A crowd scene has no one clip: asking for it is a one-line error rather than the default trot nobody
// rides (bake, clip info and rig balance take each pair's own).
TEST(SceneCrowd, ACrowdHasNoOneClip) {
  try {
    makeSceneClip(parseScene(nlohmann::json::parse(kCrowd), "scenes/x.json"));
    FAIL() << "no error";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "scenes/x.json: crowd: expected a scene of one horse and rider here (each pair of "
                                     "a crowd rides its own clip)");
  }
  EXPECT_NE(makeSceneClip(parseScene(nlohmann::json::object(), "scenes/x.json")), nullptr);
}

// A camera's follow_pair names a pair of the crowd: out of range, negative, in a scene without a crowd,
// or a crowd on a treadmill, it is a one-line error naming the camera's field.
TEST(SceneCrowd, FollowPairMustNameAPairOfTheCrowd) {
  nlohmann::json ok = nlohmann::json::parse(kCrowd);
  ok["cameras"] = nlohmann::json::parse(R"([{"view": "side"}, {"name": "one", "view": "close", "follow_pair": 5}])");
  const SceneSpec s = parseScene(ok, "scenes/x.json");
  EXPECT_EQ(s.cameras[0].follow_pair, -1);
  EXPECT_EQ(s.cameras[1].follow_pair, 5);
  nlohmann::json bad = ok;
  bad["cameras"][1]["follow_pair"] = 6;
  EXPECT_EQ(errorOf(bad.dump()),
            "scenes/x.json: cameras[1].follow_pair: expected a pair index from 0 to 5 (the crowd has 6 pairs), got 6");
  bad["cameras"][1]["follow_pair"] = -1;
  EXPECT_EQ(errorOf(bad.dump()), "scenes/x.json: cameras[1].follow_pair: expected a pair index from 0 to 199, got -1");
  EXPECT_EQ(errorOf(R"({"cameras": [{"view": "side", "follow_pair": 0}]})"),
            "scenes/x.json: cameras[0].follow_pair: expected no follow_pair in a scene without a \"crowd\" or \"riders\"");
  bad["cameras"][1]["follow_pair"] = 0;
  bad["cameras"][1]["treadmill"] = true;
  EXPECT_EQ(errorOf(bad.dump()), "scenes/x.json: cameras[1].treadmill: expected false in a crowd scene");
}

}  // namespace
}  // namespace stirrup::scene

namespace stirrup::scene {
namespace {

// Limits a horse has (rig/motion/horse_limits.h), checked when a scene loads.

std::string loadError(const std::string& json, const SceneLoadOptions& options = {}) {
  try {
    (void)parseScene(nlohmann::json::parse(json), "scenes/x.json", options);
  } catch (const rig::InputError& e) {
    return e.what();
  }
  return "";
}

// Every scene directly in scenes/ loads, and none of its paths (path clips and crowd pairs) comes near
// a limit: each path is read (the paths counted), each with no breach.
TEST(SceneLimits, EveryDefaultSceneIsInsideAHorsesLimits) {
  int paths = 0, scenes = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(STIRRUP_SOURCE_DIR) / "scenes")) {
    const std::string name = e.path().filename().string();
    // Only the scenes directly in scenes/ (the Fox's, in scenes/fox/, name a third-party asset).
    if (e.path().extension() != ".json") continue;
    SceneSpec s;
    ASSERT_NO_THROW(s = loadScene(e.path(), {true})) << name;
    ++scenes;
    for (const SceneSpec::PathLimits& l : s.limits) {
      ++paths;
      EXPECT_TRUE(l.check->breaches().empty()) << name << ": " << l.check->error();
    }
    EXPECT_TRUE(s.gait_breaches.empty()) << name << ": " << s.gait_breaches.front().text();
    EXPECT_NO_THROW((void)loadScene(e.path())) << name;
  }
  EXPECT_GE(scenes, 14);
  // cross_country, figure_eight and trail have one path each; cavalry and ride_out one a pair.
  EXPECT_GE(paths, 3 + 2 * 2);
}

TEST(SceneLimits, AnImpossiblePathIsRefusedWhenTheSceneLoads) {
  // A straight 50 m at 2500 cm/s: faster than any horse has been timed.
  EXPECT_EQ(loadError(R"({"clip": {"generator": "path", "points": [[0, 0], [5000, 0]], "speed": [[0, 2500]]}})"),
            "scenes/x.json: clip.speed: segment 0 from 0.00 s: a speed of 2500 cm/s, beyond the 1966 cm/s no horse has "
            "been timed above (the record, 70.76 km/h) (allow_impossible or --allow-impossible renders it anyway)");
  // The issue's: 20 cm hairpins at 1500 cm/s; hills of 5000 cm amplitude at 100 cm wavelength.
  const std::string hairpins = loadError(
      R"({"clip": {"generator": "path", "points": [[0, 0], [300, 0], [300, 20], [0, 20], [0, 40], [300, 40]], "speed": [[0, 1500]]}})");
  EXPECT_EQ(hairpins.rfind("scenes/x.json: clip.points: segment ", 0), 0u) << hairpins;
  EXPECT_NE(hairpins.find("cm radius at 1500 cm/s asks "), std::string::npos) << hairpins;
  const std::string hills = loadError(
      R"({"clip": {"generator": "path", "points": [[0, 0], [3000, 0]], "speed": [[0, 180]]},
          "terrain": {"hills": {"seed": 1, "amplitude_cm": 5000, "wavelength_cm": 100, "octaves": 1}}})");
  EXPECT_EQ(hills.rfind("scenes/x.json: terrain: under clip.points, segment ", 0), 0u) << hills;
  // A rider of a crowd is checked too, named by its index.
  const std::string rider = loadError(R"({"riders": [
      {"points": [[0, 0], [1000, 0]], "speed": [[0, 300]]},
      {"points": [[0, 400], [5000, 400]], "speed": [[0, 2500]]}]})");
  EXPECT_EQ(rider.rfind("scenes/x.json: riders[1].speed: segment 0 from 0.00 s: a speed of 2500 cm/s", 0), 0u) << rider;
}

// A generated gait faster than horses go at it (issue 49): a walk at 900 cm/s, a gallop past the record,
// a trot past the trotting record, a canter a gallop's pace; each at its top speed loads.
TEST(SceneLimits, AGaitFasterThanHorsesGoAtItIsRefusedWhenTheSceneLoads) {
  EXPECT_EQ(loadError(R"({"clip": {"generator": "walk", "speed_cm_s": 900}})"),
            "scenes/x.json: clip.speed_cm_s: 900 cm/s is faster than a horse walks (at most 250 cm/s: horses change to the "
            "trot at 160-230 cm/s, Froude 0.35, Griffin et al. 2004; a walk held past that, an estimate; allow_impossible or "
            "--allow-impossible renders it anyway)");
  EXPECT_EQ(loadError(R"({"clip": {"generator": "gallop", "speed_cm_s": 2000}})"),
            "scenes/x.json: clip.speed_cm_s: 2000 cm/s is faster than a horse gallops (at most 1966 cm/s: the fastest recorded "
            "horse, 70.76 km/h, Winning Brew 2008; allow_impossible or --allow-impossible renders it anyway)");
  EXPECT_EQ(loadError(R"({"clip": {"generator": "trot", "speed_cm_s": 1600}})").rfind(
                "scenes/x.json: clip.speed_cm_s: 1600 cm/s is faster than a horse trots (at most 1485 cm/s: ", 0),
            0u);
  EXPECT_EQ(loadError(R"({"clip": {"generator": "canter", "speed_cm_s": 1200}})").rfind(
                "scenes/x.json: clip.speed_cm_s: 1200 cm/s is faster than a horse canters (at most 1000 cm/s: ", 0),
            0u);
  for (const char* inside : {R"({"clip": {"generator": "walk", "speed_cm_s": 250}})", R"({"clip": {"generator": "trot", "speed_cm_s": 1485}})",
                             R"({"clip": {"generator": "canter", "speed_cm_s": 1000}})", R"({"clip": {"generator": "gallop", "speed_cm_s": 1966}})",
                             R"({"clip": {"generator": "stop", "entry_speed_cm_s": 1700}})", R"({"clip": {"generator": "jump", "approach_speed_cm_s": 900}})",
                             R"({"clip": {"generator": "sequence", "gaits": "walk,trot,canter,gallop"}})"})
    EXPECT_EQ(loadError(inside), "") << inside;
  // Allowed, by the scene or the load option: it loads, and every frame says so.
  const std::string walk = R"({"clip": {"generator": "walk", "speed_cm_s": 900})";
  for (const SceneSpec& s : {parseScene(nlohmann::json::parse(walk + "}"), "scenes/x.json", {true}),
                             parseScene(nlohmann::json::parse(walk + R"(, "allow_impossible": true})"), "scenes/x.json")}) {
    ASSERT_EQ(s.gait_breaches.size(), 1u);
    EXPECT_EQ(impossibleFrameWarning(s, 3),
              "scenes/x.json: frame 3 (0.083 s): beyond a horse's limits (allowed): gait speed: clip.speed_cm_s: 900 cm/s is "
              "faster than a horse walks (at most 250 cm/s: horses change to the trot at 160-230 cm/s, Froude 0.35, Griffin et "
              "al. 2004; a walk held past that, an estimate)");
  }
}

TEST(SceneLimits, AllowImpossibleLoadsAndWarnsEachFrameThatBreaksALimit) {
  // 100 to 300 cm/s over the first 0.25 s: 800 cm/s², beyond 0.6 g; at 24 fps frames 1-7 (0 to 0.25 s)
  // speed up that hard, frame 8 (0.292 s) no longer.
  const std::string json = R"({"clip": {"generator": "path", "points": [[0, 0], [3000, 0]], "speed": [[0, 100], [0.25, 300]]})";
  EXPECT_NE(loadError(json + "}"), "");
  for (const SceneSpec& s : {parseScene(nlohmann::json::parse(json + "}"), "scenes/x.json", {true}),
                             parseScene(nlohmann::json::parse(json + R"(, "allow_impossible": true})"), "scenes/x.json")}) {
    EXPECT_TRUE(s.allow_impossible);
    EXPECT_EQ(impossibleFrameWarning(s, 1),
              "scenes/x.json: frame 1 (0.000 s): beyond a horse's limits (allowed): acceleration: speeding up at 800 cm/s² at "
              "100 cm/s, beyond the 589 cm/s² a horse reaches at that speed (Williams et al. 2009)");
    EXPECT_NE(impossibleFrameWarning(s, 7), "");
    EXPECT_EQ(impossibleFrameWarning(s, 8), "");
  }
  // A scene inside the limits warns of nothing.
  const SceneSpec fine = parseScene(nlohmann::json::parse(R"({"clip": {"generator": "path", "points": [[0, 0], [3000, 0]], "speed": [[0, 300]]}})"),
                                    "scenes/x.json", {true});
  EXPECT_EQ(impossibleFrameWarning(fine, 1), "");
}

}  // namespace
}  // namespace stirrup::scene

namespace stirrup::scene {
namespace {

// Every number a scene, a mapping or a profile can hold, set in turn to the values a mutation run feeds a
// reader (issue 60): each is refused as the file loads, in one line naming the file and the field, or is a
// value that makes sense for the field, and then no number that is not finite reaches the rig (a few
// frames baked, rig::bakeFrame's own check, and posed). 1e308 makes sense for no field: always refused.
constexpr double kAbsurd[] = {1e-320, 1e308, -1e308, -1.0, 0.0};

struct NumberField {
  nlohmann::json::json_pointer at;
  std::string key;  // the nearest object key above it: what the message must name
};

void numberFields(const nlohmann::json& j, const nlohmann::json::json_pointer& at, const std::string& key, std::vector<NumberField>& out) {
  if (j.is_number()) out.push_back({at, key});
  if (j.is_object())
    for (const auto& [k, v] : j.items()) numberFields(v, at / k, k, out);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) numberFields(j[i], at / i, key, out);
}

bool finite(const std::vector<glm::mat4>& joints) {
  for (const glm::mat4& m : joints)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(m[c][r])) return false;
  return true;
}

// A scene that loaded: its first, middle and last frames baked (rig::bakeFrame throws std::logic_error on
// a number that is not finite) and posed on the default pair, its fixed cameras made into a film.
void expectFiniteMotion(const SceneSpec& s, const std::string& what) {
  const rig::RigProfile profile = resolveProfile(s);
  std::vector<std::shared_ptr<const rig::Clip>> clips(s.pair_clips.begin(), s.pair_clips.end());
  if (s.pairs.empty()) clips.push_back(makeSceneClip(s));
  const std::vector<int> frames = scene::parseFrameList(s.frames, "frames");
  for (const auto& clip : clips)
    for (const int f : {frames.front(), frames[frames.size() / 2], frames.back()}) {
      rig::BakedFrame b;
      ASSERT_NO_THROW(b = rig::bakeFrame(*clip, profile, f, frameTime(s, f))) << what;
      const rig::MountedPose pose = rig::poseMounted(rig::test::defaultHorse(), rig::test::defaultRider(), b.horse, b.rider, profile);
      EXPECT_TRUE(finite(pose.horse) && finite(pose.rider)) << what << ": frame " << f;
    }
  for (const CameraSpec& c : s.cameras) {
    if (!c.view.empty()) continue;
    Camera cam;
    cam.projection = c.orthographic ? Camera::Projection::Orthographic : Camera::Projection::Perspective;
    cam.position = {c.position[0], c.position[1], c.position[2]};
    cam.target = {c.target[0], c.target[1], c.target[2]};
    cam.fov_deg = c.fov_deg, cam.ortho_height_cm = c.ortho_height_cm;
    EXPECT_NO_THROW(CameraFrame(cam, s.width, s.height)) << what;
  }
}

// Each number of `base` set to each absurd value: refused in one line naming `file` and the field, or
// (for a value the field may hold) loaded and moving finitely. Returns how many were refused.
int mutateEveryNumber(const nlohmann::json& base, const std::string& file) {
  std::vector<NumberField> fields;
  numberFields(base, nlohmann::json::json_pointer(), "", fields);
  int refused = 0;
  for (const NumberField& f : fields)
    for (const double v : kAbsurd) {
      nlohmann::json j = base;
      j[f.at] = v;
      const std::string what = f.at.to_string() + " = " + rig::numberText(v);
      std::optional<SceneSpec> s;
      const std::string e = stirrup::test::errorOf([&] { s = parseScene(j, file); }, "");
      if (!e.empty()) {
        ++refused;
        EXPECT_EQ(e.rfind(file + ": ", 0), 0u) << what << ": " << e;
        // The field, or for two pairs moved into each other the list naming both (riders[0] and riders[1]).
        const std::string list = f.at.to_string().substr(1, f.at.to_string().find('/', 1) - 1);
        EXPECT_TRUE(e.find(f.key) != std::string::npos || e.find(list + ": " + list + "[") != std::string::npos ||
                    e.find(list + ".formation: pairs ") != std::string::npos)
            << what << ": " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << what;
        continue;
      }
      EXPECT_LT(std::abs(v), 1e300) << what << " was accepted";
      expectFiniteMotion(*s, what);
    }
  return refused;
}

const std::string kFile = "/nonexistent/numbers/x.json";

TEST(SceneNumbers, APathOverHillsWithItsLookAndCamerasRefusesEveryAbsurdNumber) {
  const nlohmann::json base = nlohmann::json::parse(R"({
    "fps": 24, "frames": "1-12", "resolution": [64, 36],
    "clip": {"generator": "path", "points": [[0, 0], [800, 0], [1600, 300]], "speed": [[0, 300], [2, 500]],
             "variation": 0.1, "seed": 3, "roll_limit_deg": 20, "duration_s": 30},
    "terrain": {"hills": {"seed": 4, "amplitude_cm": 50, "wavelength_cm": 3000, "octaves": 2}},
    "quality": {"samples": 4, "light_samples": 1, "ao_samples": 1},
    "sun": {"direction": [0.45, 0.75, 0.5], "angular_radius": 2},
    "haze": {"visibility_cm": 30000, "ortho_depth_cm": 900},
    "cameras": [{"name": "o", "ortho_height": 300, "position": [0, 120, 900], "target": [0, 120, 0], "frame_margin": 0.1},
                {"name": "p", "type": "perspective", "fov": 40, "position": [0, 150, 900], "target": [0, 100, 0],
                 "motion": "orbit", "orbit_deg_per_frame": 2, "orbit_frames": 48, "damping": 0.5, "hold_frame": 3},
                {"name": "f", "type": "perspective", "focal_length": 35, "position": [500, 150, 900], "target": [0, 100, 0]}],
    "reference": {"file": "ref.png", "offset": 0, "rate": 1, "scale": 0.7, "position": [10, 10], "opacity": 0.5,
                  "shift_x": [1, 2], "crop": [0, 0, 10, 10],
                  "grid": {"rows": 2, "columns": 3, "margins": [0, 0, 0, 0], "cell_crop": [0, 0, 5, 5]}}})");
  ASSERT_NO_THROW(expectFiniteMotion(parseScene(base, kFile), "the scene as written"));
  const int refused = mutateEveryNumber(base, kFile);
  EXPECT_GT(refused, 0);
  // The mutation run's one way past the readers: 1e-320 frames a second.
  EXPECT_EQ(stirrup::test::errorOf([&] { parseScene(nlohmann::json{{"fps", 1e-320}}, kFile); }),
            kFile + ": fps: expected frames per second from 1 to 240, got 9.99989e-321");
}

// Every parameter of every generator, absent from the base and set in turn.
TEST(SceneNumbers, EveryGeneratorsParametersRefuseEveryAbsurdNumber) {
  for (const std::string& generator : scene::clipGenerators()) {
    if (generator == "path") continue;  // above, with its points and speeds
    for (const std::string& key : scene::clipGeneratorParameters(generator)) {
      if (key == "gaits" || key == "lead" || key == "end_with_stop") continue;  // names and a flag, not numbers
      SCOPED_TRACE(generator + "." + key);
      mutateEveryNumber({{"frames", "1-6"}, {"allow_impossible", true}, {"clip", {{"generator", generator}, {key, 1}}}}, kFile);
    }
  }
}

TEST(SceneNumbers, ACrowdAndAListOfRidersRefuseEveryAbsurdNumber) {
  const nlohmann::json crowd = nlohmann::json::parse(R"({"frames": "1-6", "crowd": {
    "pairs": 2, "seed": 7, "lead": {"points": [[0, 0], [3000, 0]], "speed": [[0, 300], [3, 300]]},
    "formation": {"files": 2, "file_spacing_cm": 400, "rank_spacing_cm": 1000, "jitter_cm": 10},
    "speed_variation": 0.02, "start_offset_max_s": 0.5, "profiles": {"thesis": 1, "novice": 1},
    "withers_height_cm": [150, 170], "rider_height_cm": [160, 180], "rider_build": [0.9, 1.1], "gait_variation": 0.1}})");
  EXPECT_GT(mutateEveryNumber(crowd, kFile), 0);
  const nlohmann::json riders = nlohmann::json::parse(R"({"frames": "1-6", "riders": [
    {"points": [[0, 0], [2000, 0]], "speed": [[0, 300], [2, 320]], "start_offset_s": 0.3, "seed": 3, "variation": 0.1,
     "withers_height_cm": 160, "rider_height_cm": 170, "rider_build": 1},
    {"points": [[0, 500], [2000, 500]], "speed": [[0, 300]]}]})");
  EXPECT_GT(mutateEveryNumber(riders, kFile), 0);
}

TEST(SceneNumbers, EveryProfileParameterRefusesEveryAbsurdNumber) {
  for (const rig::RigParameter& p : rig::rigParameters()) {
    SCOPED_TRACE(std::string(p.key));
    mutateEveryNumber({{"frames", "1-6"}, {"profile_overrides", {{std::string(p.key), (p.min + p.max) / 2}}}}, kFile);
  }
}

// A mapping file's numbers, read as a character's and as a clip's mapping.
TEST(SceneNumbers, MappingFilesRefuseEveryAbsurdNumber) {
  const std::filesystem::path dir = std::filesystem::path(STIRRUP_BINARY_DIR) / "test_scene_numbers";
  std::filesystem::create_directories(dir);
  const nlohmann::json character = nlohmann::json::parse(std::ifstream(std::filesystem::path(STIRRUP_SOURCE_DIR) / "scenes/characters/horse-mapping.json"));
  const nlohmann::json clip = {{"mode", "skeleton"}, {"scale_cm", 100}, {"forward", {0, 0, 1}}, {"up", {0, 1, 0}}, {"speed_cm_s", 300},
                               {"nodes", {{"lfHoof", "a"}, {"rfHoof", "b"}, {"lbHoof", "c"}, {"rbHoof", "d"}}}};
  for (const auto& [base, as_clip] : {std::pair{character, false}, std::pair{clip, true}}) {
    std::vector<NumberField> fields;
    numberFields(base, nlohmann::json::json_pointer(), "", fields);
    ASSERT_FALSE(fields.empty());
    for (const NumberField& f : fields)
      for (const double v : kAbsurd) {
        nlohmann::json j = base;
        j[f.at] = v;
        const std::filesystem::path file = dir / "mapping.json";
        std::ofstream(file) << j.dump();
        const std::string what = f.at.to_string() + " = " + rig::numberText(v);
        std::optional<glm::dmat4> to_rig;
        const std::string e = stirrup::test::errorOf([&] {
          if (as_clip) {
            const rig::ClipMapping m = rig::loadClipMapping(file);
            rig::CharacterMapping c;
            c.scale_cm = m.scale_cm, c.forward = m.forward, c.up = m.up;
            to_rig = rig::mappingToRig(c);
          } else {
            to_rig = rig::mappingToRig(rig::loadCharacterMapping(file, rig::CharacterKind::Horse));
          }
        }, "");
        if (!e.empty()) {
          // The field, or the other axis it must stand at right angles to.
          const std::string partner = f.key == "forward" ? "up" : f.key == "up" ? "forward" : f.key;
          EXPECT_TRUE(e.rfind(file.string() + ": " + f.key, 0) == 0 || e.rfind(file.string() + ": " + partner, 0) == 0) << what << ": " << e;
          continue;
        }
        EXPECT_LT(std::abs(v), 1e300) << what << " was accepted";
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite((*to_rig)[c][r])) << what;
      }
  }
}

}  // namespace
}  // namespace stirrup::scene
