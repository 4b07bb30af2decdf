#include "scene/crowd_json.h"

#include <gtest/gtest.h>

#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

using test::errorOf;

rig::CrowdSpec crowd(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  rig::JsonObjectReader r("s.json", "crowd", j);
  return parseCrowdSpec(r);
}
rig::PairSpec pair(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  rig::JsonObjectReader r("s.json", "riders[2]", j);
  return parsePairSpec(r);
}

TEST(CrowdJson, ReadsEveryField) {
  const rig::CrowdSpec s = crowd(R"({"pairs": 30, "seed": 7,
      "lead": {"points": [[0, 0], [4000, 600]], "speed": [[0, 560], [4, 900]]},
      "formation": {"files": 6, "file_spacing_cm": 260, "rank_spacing_cm": 700, "jitter_cm": 15},
      "speed_variation": 0.02, "start_offset_max_s": 1.5, "profiles": {"thesis": 2, "novice": 1},
      "withers_height_cm": [150, 170], "rider_height_cm": [155, 185], "rider_build": [0.9, 1.1],
      "gait_variation": 0.2})");
  EXPECT_EQ(s.pairs, 30);
  EXPECT_EQ(s.seed, 7u);
  ASSERT_EQ(s.lead_points.size(), 2u);
  EXPECT_EQ(s.lead_points[1], glm::dvec2(4000, 600));
  ASSERT_EQ(s.lead_speed.size(), 2u);
  EXPECT_EQ(s.lead_speed[1].at, 4.0);
  EXPECT_EQ(s.lead_speed[1].speed, 900.0);
  EXPECT_EQ(s.formation.files, 6);
  EXPECT_EQ(s.formation.file_spacing_cm, 260.0);
  EXPECT_EQ(s.formation.rank_spacing_cm, 700.0);
  EXPECT_EQ(s.formation.jitter_cm, 15.0);
  EXPECT_EQ(s.speed_variation, 0.02);
  EXPECT_EQ(s.start_offset_max_s, 1.5);
  EXPECT_EQ(s.gait_variation, 0.2);
  ASSERT_EQ(s.profile_mix.size(), 2u);
  EXPECT_EQ(s.profile_mix[0], (std::pair<std::string, double>{"novice", 1}));  // JSON objects are read in key order
  EXPECT_EQ(s.profile_mix[1], (std::pair<std::string, double>{"thesis", 2}));
  EXPECT_EQ(s.withers_height_cm.lo, 150.0);
  EXPECT_EQ(s.rider_height_cm.hi, 185.0);
  EXPECT_EQ(s.rider_build.lo, 0.9);
}

TEST(CrowdJson, DefaultsAreTheWholeRanges) {
  const rig::CrowdSpec s = crowd(R"({"lead": {"points": [[0, 0], [100, 0]], "speed": [[0, 300]]}})");
  EXPECT_EQ(s.pairs, 1);
  EXPECT_EQ(s.withers_height_cm.lo, 145.0);
  EXPECT_EQ(s.withers_height_cm.hi, 175.0);
  EXPECT_EQ(s.rider_height_cm.lo, 150.0);
  EXPECT_EQ(s.rider_height_cm.hi, 190.0);
}

TEST(CrowdJson, BadFieldsAreOneLineErrors) {
  const std::string lead = R"("lead": {"points": [[0, 0], [100, 0]], "speed": [[0, 300]]})";
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "pairs": "30"})"); }), "s.json: crowd.pairs: expected a whole number, got \"30\"");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "pairs": 2.5})"); }), "s.json: crowd.pairs: expected a whole number, got 2.5");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "riders": 3})"); }), "s.json: crowd.riders: unknown field");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "formation": {"rows": 3}})"); }), "s.json: crowd.formation.rows: unknown field");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "formation": {"jitter_cm": "a bit"}})"); }),
            "s.json: crowd.formation.jitter_cm: expected a number, got \"a bit\"");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "profiles": ["thesis"]})"); }),
            "s.json: crowd.profiles: expected {\"thesis\": weight, ...}, got an array of 1");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "profiles": {"thesis": "2"}})"); }),
            "s.json: crowd.profiles.thesis: expected a weight (a number >= 0), got \"2\"");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "withers_height_cm": 160})"); }),
            "s.json: crowd.withers_height_cm: expected an array of 2 numbers, got 160");
  EXPECT_EQ(errorOf([&] { crowd("{" + lead + R"(, "seed": -1})"); }),
            "s.json: crowd.seed: expected a whole number from 0 to 2147483647, got -1");
  EXPECT_EQ(errorOf([&] { crowd(R"({"pairs": 3})"); }), "s.json: crowd.lead: missing (expected an object)");
  EXPECT_EQ(errorOf([&] { crowd(R"({"lead": {"points": [[0, 0], [1, "a"]], "speed": [[0, 300]]}})"); }),
            "s.json: crowd.lead.points[1]: expected a point [x, z] (cm), got an array of 2");
  EXPECT_EQ(errorOf([&] { crowd(R"({"lead": {"points": [[0, 0], [100, 0]], "speed": [[0, 300]], "over": "distance"}})"); }),
            "s.json: crowd.lead.over: unknown field");
}

TEST(CrowdJson, ReadsARider) {
  const rig::PairSpec p = pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "start_offset_s": 0.5, "profile": "english",
      "seed": 3, "variation": 0.2, "withers_height_cm": 150, "rider_height_cm": 180, "rider_build": 1.1})");
  EXPECT_EQ(p.path.points.size(), 2u);
  EXPECT_EQ(p.path.speed[0].speed, 300.0);
  EXPECT_EQ(p.path.over, rig::SpeedProfile::Over::Time);
  EXPECT_EQ(p.clip_offset_s, 0.5);
  EXPECT_EQ(p.profile, "english");
  EXPECT_EQ(p.path.seed, 3u);
  EXPECT_EQ(p.path.variation, 0.2);
  EXPECT_EQ(p.withers_height_cm, 150.0);
  EXPECT_EQ(p.rider_height_cm, 180.0);
  EXPECT_EQ(p.rider_build, 1.1);
  EXPECT_EQ(p.coat, "bay");  // the default characters' colours unless named
  EXPECT_EQ(p.jacket, "red");
  const rig::PairSpec q = pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "coat": "grey", "jacket": "navy",
      "hair": "blonde", "skin": "olive"})");
  EXPECT_EQ(q.coat, "grey");
  EXPECT_EQ(q.jacket, "navy");
  EXPECT_EQ(q.hair, "blonde");
  EXPECT_EQ(q.skin, "olive");
  EXPECT_EQ(pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "speed_over": "distance"})").path.over,
            rig::SpeedProfile::Over::Distance);
}

TEST(CrowdJson, BadRiderFieldsAreOneLineErrors) {
  EXPECT_EQ(errorOf([&] { pair(R"({"speed": [[0, 300]]})"); }), "s.json: riders[2].points: expected the path's points [[x, z], ...] (cm)");
  EXPECT_EQ(errorOf([&] { pair(R"({"points": [[0, 0], [500, 0]]})"); }),
            "s.json: riders[2].speed: expected speed keys [[seconds, cm/s], ...]");
  EXPECT_EQ(errorOf([&] { pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "hat": "big"})"); }),
            "s.json: riders[2].hat: unknown field");
  EXPECT_EQ(errorOf([&] { pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "horse": "big"})"); }),
            "s.json: riders[2].horse: no such file: big");
  EXPECT_EQ(errorOf([&] { pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "profile": 2})"); }),
            "s.json: riders[2].profile: expected a string, got 2");
  EXPECT_EQ(errorOf([&] { pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "speed_over": "space"})"); }),
            "s.json: riders[2].speed_over: expected \"time\" or \"distance\", got \"space\"");
  EXPECT_EQ(errorOf([&] { pair(R"({"points": [[0, 0], [500, 0]], "speed": [[0, 300]], "variation": 3})"); }),
            "s.json: riders[2].variation: expected a fraction from 0 to 1");
}

}  // namespace
}  // namespace stirrup::scene
