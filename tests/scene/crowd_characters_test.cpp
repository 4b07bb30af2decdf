// scene/crowd_characters.h: a crowd's own characters (issue 60). A list of riders and a generated crowd
// naming the shipped horse and rider files (scenes/characters, as a user's files with their mappings):
// each pair naming one rides the file's character, seated on its horse with its own profile, boxed by
// its characters at rest; the shot's evaluator poses it with those very characters; the others stay
// generated. What cannot be is one line naming the file and the field.
#include "scene/crowd_characters.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rig/horse_pose.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "scene/shot_evaluator.h"
#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

// In the shipped scenes' folder, so "characters/..." resolves as it does for scenes/trot.json.
const std::string kFile = STIRRUP_SOURCE_DIR "/scenes/own_characters_test.json";
const nlohmann::json kHorse = {{"file", "characters/horse.glb"}, {"mapping", "characters/horse-mapping.json"}};
const nlohmann::json kRider = {{"file", "characters/rider.glb"}, {"mapping", "characters/rider-mapping.json"}};

TEST(CrowdCharacters, ListedPairsRideTheFilesSeatedAsASinglePairIs) {
  const nlohmann::json j = {{"frames", "1-6"},
                            {"riders", {{{"points", {{0, 0}, {2000, 0}}}, {"speed", {{0, 300}}}, {"horse", kHorse}},
                                        {{"points", {{0, 600}, {2000, 600}}}, {"speed", {{0, 300}}}, {"rider", kRider}, {"profile", "novice"}},
                                        {{"points", {{0, 1200}, {2000, 1200}}}, {"speed", {{0, 300}}}}}}};
  const SceneSpec s = parseScene(j, kFile);
  ASSERT_EQ(s.pairs.size(), 3u);
  const rig::PairCharacters* horse_pair = s.pairs[0].characters.get();
  const rig::PairCharacters* rider_pair = s.pairs[1].characters.get();
  ASSERT_NE(horse_pair, nullptr);
  ASSERT_NE(rider_pair, nullptr);
  EXPECT_EQ(s.pairs[2].characters, nullptr);  // the third rides the generated pair
  EXPECT_EQ(std::filesystem::path(horse_pair->horse->source.file).filename(), "horse.glb");
  EXPECT_TRUE(horse_pair->rider->source.file.empty());  // the generated rider at the pair's proportions
  EXPECT_TRUE(rider_pair->horse->source.file.empty());  // the generated horse
  EXPECT_EQ(std::filesystem::path(rider_pair->rider->source.file).filename(), "rider.glb");
  // The path clip turns the hooves about the file's horse's rest places; the box is its characters'.
  const std::array<glm::dvec2, 4> rest = rig::restHoofPlaces(*horse_pair->horse);
  for (std::size_t h = 0; h < 4; ++h) EXPECT_EQ(horse_pair->extent.hoof_rest[h], rest[h]) << h;
  EXPECT_EQ(horse_pair->own_clip, nullptr);  // a gait along its path
  // The shot's evaluator poses each pair with those characters, at every level of detail.
  ShotEvaluator shot(s, resolveProfile(s), 1);
  for (int level = 0; level < shot.levelCount(); ++level) {
    EXPECT_EQ(&shot.horseAt(0, level), horse_pair->horse.get()) << level;
    EXPECT_EQ(&shot.riderAt(1, level), rider_pair->rider.get()) << level;
  }
  ShotFrame frame;
  FrameRequest request;
  request.frame = 3;
  shot.evaluate(request, frame);
  ASSERT_EQ(frame.pairs.size(), 3u);
  EXPECT_EQ(frame.pairs[0].horse_positions.size(), horse_pair->horse->mesh.vertexCount());
}

TEST(CrowdCharacters, AGeneratedCrowdNamesSomePairs) {
  const nlohmann::json j = nlohmann::json::parse(R"({"frames": "1-6", "crowd": {
    "pairs": 4, "seed": 3, "lead": {"points": [[0, 0], [3000, 0]], "speed": [[0, 300], [3, 300]]},
    "formation": {"files": 2, "file_spacing_cm": 450, "rank_spacing_cm": 1100}}})");
  nlohmann::json named = j;
  named["crowd"]["characters"] = {{{"pairs", "1,3"}, {"horse", kHorse}, {"rider", kRider}}};
  const SceneSpec s = parseScene(named, kFile);
  ASSERT_EQ(s.pairs.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(s.pairs[std::size_t(i)].characters != nullptr, i == 1 || i == 3) << i;
  EXPECT_EQ(s.pairs[1].horse_file, (std::filesystem::path(STIRRUP_SOURCE_DIR "/scenes") / "characters/horse.glb").string());
  // The same pairs, paths and proportions as without the entry: only their characters differ.
  const SceneSpec plain = parseScene(j, kFile);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(s.pairs[i].path.points, plain.pairs[i].path.points) << i;
    EXPECT_EQ(s.pairs[i].rider_height_cm, plain.pairs[i].rider_height_cm) << i;
  }
}

TEST(CrowdCharacters, WhatCannotBeIsOneLineNamingTheField) {
  const nlohmann::json crowd = nlohmann::json::parse(R"({"frames": "1-6", "crowd": {
    "pairs": 2, "lead": {"points": [[0, 0], [3000, 0]], "speed": [[0, 300], [3, 300]]},
    "formation": {"files": 2, "file_spacing_cm": 450}}})");
  const auto error = [&](const nlohmann::json& characters, bool hills = false) {
    nlohmann::json j = crowd;
    j["crowd"]["characters"] = characters;
    if (hills) j["terrain"] = {{"hills", {{"seed", 2}, {"amplitude_cm", 60}, {"wavelength_cm", 3000}}}};
    return stirrup::test::errorOf([&] { parseScene(j, kFile); });
  };
  EXPECT_EQ(error({{{"pairs", "1-2"}, {"horse", kHorse}}}),
            kFile + ": crowd.characters[0].pairs: expected pair indices from 0 to 1, got 2");
  EXPECT_EQ(error({{{"pairs", "0"}, {"horse", kHorse}}, {{"pairs", "0-1"}, {"rider", kRider}}}),
            kFile + ": crowd.characters[1].pairs: pair 0 is named by characters[0] too (expected each pair in one entry at most)");
  EXPECT_EQ(error({{{"pairs", "0"}, {"rider", kRider}, {"animation", "Walk"}}}),
            kFile + ": crowd.characters[0].animation: expected a horse file beside it (\"horse\": its own animation is the file's)");
  EXPECT_EQ(error({{{"pairs", "0"}}}), kFile + ": crowd.characters[0].horse: expected a \"horse\" or \"rider\" file for these pairs");
  EXPECT_EQ(error({{{"pairs", "0"}, {"horse", "nope.glb"}}}),
            kFile + ": crowd.characters[0].horse: no such file: " + (std::filesystem::path(STIRRUP_SOURCE_DIR "/scenes") / "nope.glb").string());
  EXPECT_EQ(error({{{"pairs", "0"}, {"horse", kHorse}, {"animation", "Walk"}}}, true),
            kFile + ": crowd.characters: pair 0 plays its horse's own animation \"Walk\", keyed on flat ground (expected a crowd on flat "
                    "ground, or the generated gait over the terrain)");
  EXPECT_EQ(error(3), kFile + ": crowd.characters: expected a list of {\"pairs\", \"horse\", \"rider\", \"animation\"}, got 3");
}

}  // namespace
}  // namespace stirrup::scene
