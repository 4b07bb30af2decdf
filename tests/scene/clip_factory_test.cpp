// The clip factory (scene/clip_factory.cpp): a scene's "clip" object read and checked once, with
// errors naming the file and the field, and made into the right kind of clip. What each generator's
// motion looks like is tested with the movements (movement_clips_test.cpp, path_clip_test.cpp).
#include "scene/clip_factory.h"

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rig/error.h"
#include "rig/io/gltf_character.h"
#include "rig/motion/movement.h"
#include "rig/motion/terrain.h"
#include "tests/input_error.h"
#include "tests/rig/io/baked_trot.h"

namespace stirrup::scene {
namespace {

using stirrup::test::errorOf;
namespace fs = std::filesystem;

ClipSpec parse(const nlohmann::json& j) {
  rig::JsonObjectReader r("scenes/x.json", "clip", j);
  return parseClipSpec(r, ".");
}
std::string parseError(const nlohmann::json& j) {
  return errorOf([&] { parse(j); });
}

TEST(ClipSpec, UnknownParameterNamesFileAndField) {
  nlohmann::json j = {{"generator", "jump"}, {"fence_hieght_cm", 90}};
  rig::JsonObjectReader r("scenes/x.json", "clip", j);
  try {
    parseClipSpec(r, ".");
    FAIL();
  } catch (const rig::InputError& e) {
    EXPECT_STREQ(e.what(), "scenes/x.json: clip.fence_hieght_cm: unknown field");
  }
  nlohmann::json bad = {{"generator", "rear"}, {"angle_deg", 95}};
  rig::JsonObjectReader r2("scenes/x.json", "clip", bad);
  EXPECT_THROW(parseClipSpec(r2, "."), rig::InputError);
}

TEST(ClipSpec, TheGeneratorsAndTheParametersEachAccepts) {
  EXPECT_EQ(clipGenerators(), (std::vector<std::string>{"walk", "trot", "canter", "gallop", "sequence", "stop", "jump",
                                                        "rear", "buck", "path"}));
  // A steady gait's seven, then the four every generator has.
  EXPECT_EQ(clipGeneratorParameters("trot"),
            (std::vector<std::string>{"speed_cm_s", "stride_hz", "hoof_lift_cm", "duty_factor", "trunk_bounce_cm",
                                      "pitch_deg", "roll_deg", "duration_s", "variation", "seed", "lead"}));
  EXPECT_EQ(clipGeneratorParameters("rear").front(), "angle_deg");
  EXPECT_TRUE(clipGeneratorParameters("amble").empty());
}

TEST(ClipSpec, BadValuesAreOneLineErrorsNamingTheField) {
  EXPECT_EQ(parseError({{"generator", "amble"}}),
            "scenes/x.json: clip.generator: expected one of walk, trot, canter, gallop, sequence, stop, jump, rear, buck, "
            "path, got \"amble\"");
  EXPECT_EQ(parseError({{"generator", "trot"}, {"speed_cm_s", 2500}}),
            "scenes/x.json: clip.speed_cm_s: expected a number from 0 to 2000, got 2500");
  EXPECT_EQ(parseError({{"generator", "trot"}, {"lead", "up"}}),
            "scenes/x.json: clip.lead: expected \"left\" or \"right\", got \"up\"");
  EXPECT_EQ(parseError({{"generator", "jump"}, {"approach_strides", 2.5}}),
            "scenes/x.json: clip.approach_strides: expected a whole number");
  // A bound that depends on another field: a kick takes at most 60% of its buck's period.
  EXPECT_EQ(parseError({{"generator", "buck"}, {"period_s", 1.0}, {"kick_s", 0.7}}),
            "scenes/x.json: clip.kick_s: expected a number from 0.15 to 0.6, got 0.7");
  EXPECT_EQ(parseError({{"generator", "sequence"}, {"segment_s", 2.0}, {"blend_s", 2.0}}),
            "scenes/x.json: clip.blend_s: expected a number from 0.1 to 1.9, got 2");
  EXPECT_EQ(parseError({{"generator", "sequence"}, {"gaits", "walk,amble"}}),
            "scenes/x.json: clip.gaits: expected walk, trot, canter or gallop, got \"amble\"");
  EXPECT_EQ(parseError({{"generator", "trot"}, {"file", "x.glb"}}),
            "scenes/x.json: clip.generator: expected either \"generator\" or \"file\", not both");
  EXPECT_EQ(parseError({{"generator", "path"}, {"points", {{0, 0}, {1000, 0}}}}),
            "scenes/x.json: clip.speed: expected either \"speed\" keys or \"segment_gaits\", one of the two");
}

TEST(ClipSpec, SteadyGaitsAreTheirParametersOverTheGaitsOwn) {
  const ClipSpec trot = parse({{"generator", "trot"}, {"speed_cm_s", 350}, {"duty_factor", 0.5}});
  const std::optional<rig::GaitParams> g = steadyGaitParams(trot);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->speed_cm_s, 350.0);
  EXPECT_EQ(g->duty_factor, (std::array<double, 4>{0.5, 0.5, 0.5, 0.5}));
  EXPECT_EQ(g->stride_hz, rig::trotParams().stride_hz);  // not given: the trot's own
  EXPECT_FALSE(steadyGaitParams(parse({{"generator", "jump"}})));
  // Without variation a steady gait is the closed-form periodic gait; with it, a generated movement.
  EXPECT_NE(dynamic_cast<const rig::ProceduralGait*>(makeClip(trot).get()), nullptr);
  EXPECT_NE(dynamic_cast<const rig::MovementClip*>(makeClip(parse({{"generator", "trot"}, {"variation", 0.2}})).get()), nullptr);
  EXPECT_NE(dynamic_cast<const rig::MovementClip*>(makeClip(parse({{"generator", "rear"}})).get()), nullptr);
}

// The speed of every gait a generator rides, with the field that sets it, for the gaits' top speeds
// (rig/motion/horse_limits.h): given or the generator's own; none for the rear, the buck and a path.
TEST(ClipSpec, EveryGaitAGeneratorRidesIsListedWithItsSpeedAndField) {
  const auto speeds = [](const nlohmann::json& j) {
    std::vector<std::string> out;
    for (const rig::GaitSpeed& g : generatedGaitSpeeds(parse(j))) out.push_back(g.field + " " + g.gait + " " + std::to_string(int(g.speed_cm_s)));
    return out;
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(speeds({{"generator", "walk"}, {"speed_cm_s", 240}}), V{"speed_cm_s walk 240"});
  EXPECT_EQ(speeds({{"generator", "trot"}}), V{"speed_cm_s trot 360"});
  EXPECT_EQ(speeds({{"generator", "gallop"}, {"speed_cm_s", 1500}}), V{"speed_cm_s gallop 1500"});
  EXPECT_EQ(speeds({{"generator", "stop"}, {"entry_speed_cm_s", 1200}}), V{"entry_speed_cm_s gallop 1200"});
  EXPECT_EQ(speeds({{"generator", "jump"}}), V{"approach_speed_cm_s canter 600"});
  EXPECT_EQ(speeds({{"generator", "sequence"}, {"gaits", "walk,canter"}}), (V{"gaits[0] walk 180", "gaits[1] canter 600"}));
  EXPECT_EQ(speeds({{"generator", "rear"}}), V{});
  EXPECT_EQ(speeds({{"generator", "path"}, {"points", {{0, 0}, {1000, 0}}}, {"speed", {{0, 300}}}}), V{});
}

// "segment_gaits": each segment at its gait's speed over the middle half of the segment: on a straight
// 1000 cm path, keys at 250 and 750 cm.
TEST(ClipSpec, SegmentGaitsKeyTheMiddleHalfOfEachSegment) {
  const ClipSpec spec = parse({{"generator", "path"}, {"points", {{0, 0}, {1000, 0}}}, {"segment_gaits", {"walk"}}});
  const std::optional<rig::PathClipParams> p = pathClipParams(spec);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->over, rig::SpeedProfile::Over::Distance);
  const double walk = rig::gaitParamsByName("walk")->speed_cm_s;
  ASSERT_EQ(p->speed.size(), 2u);
  EXPECT_NEAR(p->speed[0].at, 250.0, 1e-9);
  EXPECT_NEAR(p->speed[1].at, 750.0, 1e-9);
  EXPECT_EQ(p->speed[0].speed, walk);
  EXPECT_EQ(p->speed[1].speed, walk);
  EXPECT_FALSE(pathClipParams(parse({{"generator", "trot"}})));
  EXPECT_NE(dynamic_cast<const rig::PathClip*>(makeClip(spec).get()), nullptr);
}

// ---- A horse's own animation (rig/io/keyed_horse_clip.h), read from a file with no control nodes: the
// default horse's trot as stirrup bakes it (tests/rig/io/baked_trot.h).

// With no mapping, a file that holds no control nodes is a horse: with the scene's horse made from that
// very file, the clip keys the horse itself; without it (or on another horse), its controls alone.
TEST(ClipSpec, AHorsesOwnFileKeysTheHorse) {
  const ClipSpec spec = parse({{"file", rig::test::bakedTrot().file.string()}});
  EXPECT_TRUE(spec.generator.empty());
  EXPECT_FALSE(spec.character_mapping);
  EXPECT_FALSE(readsControlNodes(spec));
  EXPECT_NEAR(fileClipDuration(spec), (rig::test::kFrames - 1) / rig::test::kFps, 1e-4);
  const rig::Character own = rig::loadCharacterGltf(rig::test::bakedTrot().file, rig::CharacterKind::Horse);
  EXPECT_TRUE(makeClip(spec, own)->sample(0.5).keyed_pose);
  EXPECT_FALSE(makeClip(spec)->sample(0.5).keyed_pose);
  EXPECT_FALSE(makeClip(spec, rig::test::defaultHorse())->sample(0.5).keyed_pose);
  // The controls are the same either way: the horse's own motion.
  EXPECT_DOUBLE_EQ(makeClip(spec, own)->sample(0.5).controls[rig::HorseChannel::lfHoofTy],
                   makeClip(spec)->sample(0.5).controls[rig::HorseChannel::lfHoofTy]);
}

// The mapping `stirrup character map` writes (roles) names the same file's joints for the clip: one
// mapping for a horse and its animation. A joint it names that the file does not have is one line.
TEST(ClipSpec, ACharacterMappingReadsTheAnimationThroughItsRoles) {
  const fs::path dir = fs::temp_directory_path() / ("stirrup-clip-roles-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const rig::Character own = rig::loadCharacterGltf(rig::test::bakedTrot().file, rig::CharacterKind::Horse);
  nlohmann::json roles;
  for (const auto& [role, j] : own.roles) roles[role] = own.skeleton.joints[std::size_t(j)].name;
  const fs::path map = dir / "trot-map.json";
  std::ofstream(map) << nlohmann::json{{"character", "horse"}, {"roles", roles}}.dump();
  const ClipSpec spec = parse({{"file", rig::test::bakedTrot().file.string()}, {"mapping", map.string()}, {"animation", "trot"}});
  EXPECT_TRUE(spec.character_mapping);
  const auto clip = makeClip(spec);
  EXPECT_GT(clip->sample(1.0).travel_cm - clip->sample(0.0).travel_cm, 300.0) << "a trot travels 360 cm a second";
  roles["lfHoof"] = "lfHoofTip";
  std::ofstream(map) << nlohmann::json{{"character", "horse"}, {"roles", roles}}.dump();
  EXPECT_EQ(parseError({{"file", rig::test::bakedTrot().file.string()}, {"mapping", map.string()}}),
            map.string() + ": roles.lfHoof: no joint named \"lfHoofTip\" in " + rig::test::bakedTrot().file.string());
  fs::remove_all(dir);
}

// A horse's own animation is not set on uneven ground: its hooves are where they were keyed.
TEST(ClipSpec, AHorsesOwnAnimationOnTerrainIsAOneLineError) {
  ClipSpec spec = parse({{"file", rig::test::bakedTrot().file.string()}});
  spec.terrain = std::make_shared<rig::Terrain>();
  EXPECT_EQ(errorOf([&] { makeClip(spec); }),
            "scenes/x.json: clip.file: " + rig::test::bakedTrot().file.string() +
                ": a horse's animation read from its file rides on flat ground (its hooves are where they were keyed); remove "
                "the scene's \"terrain\"");
}

}  // namespace
}  // namespace stirrup::scene
