// stirrup clip make / clip info, end to end.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

fs::path outDir() {
  const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "test-out" / "clip_cli";
  fs::create_directories(d);
  return d;
}

TEST(ClipCli, MakeWritesAGlbThatInfoReadsBack) {
  const fs::path glb = outDir() / "jump.glb";
  fs::remove(glb);
  const CommandResult make = runStirrup("clip make jump --fence_height_cm 110 --seed 7 --fps 24 -o " + quote(glb.string()));
  ASSERT_EQ(make.exit_code, 0) << make.err;
  ASSERT_TRUE(fs::exists(glb));
  const CommandResult info = runStirrup("clip info " + quote(glb.string()) + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["name"], "jump");
  EXPECT_GT(j["hooves"]["lfHoof"]["peak_height_cm"].get<double>(), 110.0);
  EXPECT_TRUE(j["problems"].empty()) << j["problems"];
}

TEST(ClipCli, InfoOnAGeneratorShowsTheReference) {
  const CommandResult r = runStirrup("clip info gallop");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("reference: gallop"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("suspensions per stride       1.00   reference 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("footfall order: lbHoof rbHoof lfHoof rfHoof"), std::string::npos) << r.out;
  const CommandResult j = runStirrup("clip info trot --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_EQ(nlohmann::json::parse(j.out)["reference"]["gait"], "trot");
}

TEST(ClipCli, BadInputIsOneLine) {
  const CommandResult unknown = runStirrup("clip make jump --fence 3 -o " + quote((outDir() / "x.glb").string()));
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_EQ(unknown.err, "stirrup: clip make: fence: unknown field\n");
  const CommandResult gen = runStirrup("clip info pace");
  EXPECT_EQ(gen.exit_code, 1);
  EXPECT_EQ(lineCount(gen.err), 1u) << gen.err;
  EXPECT_NE(gen.err.find("generator"), std::string::npos) << gen.err;
  const CommandResult missing = runStirrup("clip info nowhere.glb");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(lineCount(missing.err), 1u) << missing.err;
}

TEST(ClipCli, FoxThroughTheMapping) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets/fox/Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << fox << " is not there";
  const fs::path mapping = fs::path(STIRRUP_SOURCE_DIR) / "scenes/fox-mapping.json";
  for (const char* animation : {"Walk", "Run"}) {
    const CommandResult r = runStirrup("clip info " + quote(fox.string()) + " --mapping " + quote(mapping.string()) +
                                       " --animation " + animation + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["name"], animation);
    EXPECT_GE(j["strides"].get<int>(), 2);
    for (const char* h : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"})
      EXPECT_GT(j["hooves"][h]["peak_height_cm"].get<double>(), 20.0) << animation << " " << h;
  }
}

TEST(ClipCli, EveryMovementSceneBakes) {
  for (const char* scene : {"walk", "trot", "canter", "gallop", "stop", "jump", "rear", "buck"}) {
    const fs::path csv = outDir() / (std::string(scene) + ".csv");
    const CommandResult r = runStirrup("bake " + quote(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + scene + ".json") +
                                       " --channels " + quote(csv.string()));
    EXPECT_EQ(r.exit_code, 0) << scene << ": " << r.err;
  }
}

}  // namespace
}  // namespace stirrup::test
