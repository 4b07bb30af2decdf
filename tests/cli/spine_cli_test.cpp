// `stirrup spine`: the output format, atomic -o, --plot, and one-line errors naming file and field.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

class SpineCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("stirrup_spine_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) {
    const fs::path file = dir_ / name;
    std::ofstream(file) << text;
    return file;
  }

  fs::path dir_;
};

const char* kGood = R"({"bones": [10, 11, 10], "segments": 10, "poses": [
  {"lower": [0, 0, 0], "middle": [0, 0, 0], "top": [0, 0, 0]},
  {"lower": [0, 0, 35], "middle": [0, 0, -70], "top": [270, 0, 60]},
  {"lower": [0, 0, 10], "middle": [0, 0, 10], "top": [0, 0, 10], "stretch": 1.2}]})";

TEST_F(SpineCli, WritesEveryPoseToStdout) {
  const fs::path in = write("good.json", kGood);
  const CommandResult r = runStirrup("spine " + quote(in.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json out = nlohmann::json::parse(r.out);
  ASSERT_EQ(out["poses"].size(), 3u);
  for (const nlohmann::json& pose : out["poses"]) {
    EXPECT_EQ(pose["fk"].size(), 4u);
    EXPECT_EQ(pose["curve_points"].size(), 5u);
    EXPECT_GE(pose["samples"].size(), 100u);
    ASSERT_EQ(pose["joints"].size(), 11u);
    for (const nlohmann::json& j : pose["joints"]) {
      ASSERT_EQ(j["position"].size(), 3u);
      ASSERT_EQ(j["rotation"].size(), 4u);
      double norm = 0.0;
      for (double c : j["rotation"]) norm += c * c;
      EXPECT_NEAR(norm, 1.0, 1e-9);
    }
    // The chain starts at the root and ends at the tip of bone 3.
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(pose["joints"][0]["position"][k].get<double>(), 0.0, 1e-9);
      EXPECT_NEAR(pose["joints"][10]["position"][k].get<double>(), pose["fk"][3][k].get<double>(), 1e-9);
    }
  }
  EXPECT_NEAR(out["poses"][0]["length"].get<double>(), 31.0, 1e-9);
  EXPECT_NEAR(out["poses"][0]["joints"][10]["position"][1].get<double>(), 31.0, 1e-9);
  EXPECT_NEAR(out["poses"][1]["joints"][10]["twist"].get<double>(), 270.0, 1e-12);
  EXPECT_NEAR(out["poses"][1]["joints"][4]["twist"].get<double>(), 135.0, 1e-12);
  EXPECT_NEAR(out["poses"][2]["length"].get<double>() / 1.2,
              nlohmann::json::parse(runStirrup("spine " + quote(write("s1.json",
                  R"({"bones": [10, 11, 10], "segments": 10, "poses": [{"lower": [0, 0, 10], "middle": [0, 0, 10], "top": [0, 0, 10]}]})").string())).out)["poses"][0]["length"].get<double>(),
              1e-9);
}

TEST_F(SpineCli, WritesFileAndPlot) {
  const fs::path in = write("good.json", kGood);
  const fs::path out = dir_ / "out" / "spine.json", png = dir_ / "out" / "spine.png";
  const CommandResult r = runStirrup("spine " + quote(in.string()) + " -o " + quote(out.string()) + " --plot " +
                                     quote(png.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(nlohmann::json::parse(readText(out))["poses"].size(), 3u);
  EXPECT_FALSE(fs::exists(out.string() + ".tmp"));
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 1000u);
}

TEST_F(SpineCli, HelpDocumentsFormatUnitsAndOrder) {
  const CommandResult r = runStirrup("spine --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s : {"bones", "segments", "poses", "cm", "degrees", "Rz(rz)", "rotation", "--plot", "stretch"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

struct BadCase {
  const char* json;
  const char* message;  // the whole error line after "stirrup: FILE: "
};

TEST_F(SpineCli, BadInputIsOneLineNamingFileAndField) {
  const BadCase cases[] = {
      {R"({"segments": 10, "poses": []})", "bones: missing (expected 3 numbers)"},
      {R"({"bones": [10, 11], "segments": 10, "poses": []})", "bones: expected 3 numbers, got 2"},
      {R"({"bones": [10, -1, 10], "segments": 10, "poses": []})", "bones[1]: expected a positive length in cm, got -1"},
      {R"({"bones": [10, "a", 10], "segments": 10, "poses": []})", "bones[1]: expected a number, got \"a\""},
      {R"({"bones": [10, 11, 10], "poses": []})", "segments: missing (expected a whole number from 3 to 32)"},
      {R"({"bones": [10, 11, 10], "segments": 40, "poses": []})", "segments: expected a whole number from 3 to 32, got 40"},
      {R"({"bones": [10, 11, 10], "segments": 2.5, "poses": []})", "segments: expected a whole number from 3 to 32, got 2.5"},
      {R"({"bones": [10, 11, 10], "segments": 10})", "poses: missing (expected an array of poses)"},
      {R"({"bones": [10, 11, 10], "segments": 10, "poses": {}})", "poses: expected a non-empty array of poses, got an object"},
      {R"({"bones": [10, 11, 10], "segments": 10, "poses": [{"lower": [0,0,0], "middle": [0,0,0], "top": [0,0,0]},
          {"lower": [0,0,0], "middle": [0,0,0], "top": [0,0,0]},
          {"lower": [0,0,0], "middle": [0,0], "top": [0,0,0]}]})",
       "poses[2].middle: expected 3 numbers, got 2"},
      {R"({"bones": [10, 11, 10], "segments": 10, "poses": [{"lower": [0,0,0], "middle": [0,0,0]}]})",
       "poses[0].top: missing (expected 3 numbers)"},
      {R"({"bones": [10, 11, 10], "segments": 10, "poses": [{"lower": [0,0,0], "middle": [0,0,0], "top": [0,null,0]}]})",
       "poses[0].top[1]: expected a number, got null"},
      {R"({"bones": [10, 11, 10], "segments": 10, "poses": [{"lower": [0,0,0], "middle": [0,0,0], "top": [0,0,0], "stretch": 0}]})",
       "poses[0].stretch: expected a positive factor, got 0"},
      {R"({"bones": [10, 11, 10], "segments": 10, "poses": [{"lower": [0,0,0], "middle": [0,0,0], "top": [0,0,0], "twist": 3}]})",
       "poses[0].twist: unknown field"},
      {R"({"bones": [10, 11, 10], "segments": 10, "pose": []})", "poses: missing (expected an array of poses)"},
  };
  for (const BadCase& c : cases) {
    const fs::path in = write("spine.json", c.json);
    const CommandResult r = runStirrup("spine " + quote(in.string()));
    EXPECT_EQ(r.exit_code, 1) << c.json;
    EXPECT_EQ(r.err, "stirrup: " + in.string() + ": " + c.message + "\n") << c.json;
    EXPECT_TRUE(r.out.empty());
  }
  // Unreadable and malformed files.
  const CommandResult missing = runStirrup("spine " + quote((dir_ / "nope.json").string()));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(lineCount(missing.err), 1u);
  EXPECT_NE(missing.err.find("nope.json: cannot open"), std::string::npos) << missing.err;
  const CommandResult broken = runStirrup("spine " + quote(write("broken.json", "{\"bones\": [").string()));
  EXPECT_EQ(broken.exit_code, 1);
  EXPECT_EQ(lineCount(broken.err), 1u);
  EXPECT_NE(broken.err.find("broken.json: not valid JSON"), std::string::npos) << broken.err;
}

}  // namespace
}  // namespace stirrup::test
