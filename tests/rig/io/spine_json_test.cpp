#include "rig/io/spine_json.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "tests/input_error.h"

#include "rig/error.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

using test::errorOf;

class SpineJson : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() / ("stirrup_spine_json_test_" + std::string(
      ::testing::UnitTest::GetInstance()->current_test_info()->name()));
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& text) {
    const fs::path f = dir_ / "spine.json";
    std::ofstream(f) << text;
    return f.string();
  }
};

TEST_F(SpineJson, ReadsTheShippedDemo) {
  const SpineFile s = readSpineFile(STIRRUP_SOURCE_DIR "/scenes/spine/demo.json");
  EXPECT_EQ(s.bones, (std::array<double, 3>{10, 11, 10}));
  EXPECT_EQ(s.segments, 10);
  EXPECT_EQ(s.layout, ChainLayout::EqualArcLength);
  ASSERT_EQ(s.poses.size(), 6u);
  EXPECT_EQ(s.poses[2].controllers.middle, glm::dvec3(0, 0, -70));
  EXPECT_EQ(s.poses[4].controllers.top, glm::dvec3(270, 0, 20));
  EXPECT_EQ(s.poses[0].stretch, 1.0);
}

TEST_F(SpineJson, ErrorsNameTheFileAndTheField) {
  const std::string f = write(R"({"bones": [10, 11, 10], "segments": 10, "layout": "equal_chord",
    "poses": [{"lower": [0, 0, 0], "middle": [0, "x", 0], "top": [0, 0, 0]}]})");
  EXPECT_EQ(errorOf([&] { readSpineFile(f); }), f + ": poses[0].middle[1]: expected a number, got \"x\"");
  const std::string g = write(R"({"bones": [10, 11, 10], "segments": 40, "poses": []})");
  EXPECT_EQ(errorOf([&] { readSpineFile(g); }), g + ": segments: expected a whole number from 3 to 32, got 40");
}

TEST_F(SpineJson, ResultJsonCarriesEveryJointAndTheLengths) {
  const SpineFile s = readSpineFile(STIRRUP_SOURCE_DIR "/scenes/spine/demo.json");
  const CurveSpine spine(s.bones, s.segments, s.layout);
  const SpineResult r = spine.solve(s.poses[1].controllers, 1.0);
  const nlohmann::json j = spineResultToJson(r, 1.0);
  EXPECT_EQ(j["joints"].size(), r.joints.size());
  EXPECT_EQ(j["layout"], "equal_arc_length");
  EXPECT_DOUBLE_EQ(j["length"].get<double>(), r.length);
  const nlohmann::json& q = j["joints"][3]["rotation"];
  EXPECT_DOUBLE_EQ(q[0].get<double>(), r.joints[3].rotation.w);
  EXPECT_DOUBLE_EQ(q[3].get<double>(), r.joints[3].rotation.z);
}

}  // namespace
}  // namespace stirrup::rig
