// stirrup live (cli/cmd_live.cpp): the line protocol the Blender add-on's Live toggle speaks
// (docs/blender.md, "Live"), end to end through the program. The horse is the default horse trotting in
// a file `stirrup bake` wrote, named as the scene's horse and its clip: its own animation is the horse's
// motion until frames are handed in. The rider's numbers themselves are tested in
// tests/scene/live_rider_test.cpp; here, what goes over the pipe.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/run_command.h"
#include "tests/test_files.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// A scene of the baked trot's own horse under the default rider, and the bake it names.
fs::path trotScene(const fs::path& dir) {
  const fs::path shot = dir / "trot.glb";
  EXPECT_EQ(runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json") + " -o " + quote(shot.string()) + " --frames 1-24").exit_code, 0);
  const nlohmann::json scene = {{"name", "live"},
                                {"frames", "1-24"},
                                {"output", (dir / "out").string()},
                                {"characters", {{"horse", shot.string()}, {"rider", "default"}}},
                                {"clip", {{"file", shot.string()}}}};
  std::ofstream(dir / "scene.json") << scene.dump(2);
  return dir / "scene.json";
}

std::vector<nlohmann::json> linesOf(const std::string& out) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line, nullptr, false));
  return lines;
}

nlohmann::json identities(std::size_t n) {
  nlohmann::json m = nlohmann::json::array();
  for (std::size_t k = 0; k < n; ++k) m.push_back({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  return m;
}

// Ready once with the joints and frames, then one answer a line: the rider at a frame, a frame set,
// a bad request answered with a one-line error and the session going on, and exit 0 at the end of input.
TEST(LiveCli, AnswersALineForEachRequestAndGoesOnAfterABadOne) {
  const fs::path dir = freshTestDir("test_live_cli", "protocol");
  const fs::path scene = trotScene(dir);
  // The horse's joints, for a frame handed in: the ready line says how many.
  const CommandResult first = runCommand("echo | " + quote(STIRRUP_EXE) + " live " + quote(scene.string()) + " --first 0 --last 23");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const nlohmann::json ready = linesOf(first.out).at(0);
  ASSERT_TRUE(ready.value("ready", false)) << first.out;
  EXPECT_EQ(ready["first"], 0);
  EXPECT_EQ(ready["last"], 23);
  EXPECT_EQ(ready["fps"], 24.0);
  const std::size_t horse_joints = ready["horse_joints"].size(), rider_joints = ready["rider_joints"].size();
  EXPECT_GT(horse_joints, 20u);
  EXPECT_GT(rider_joints, 20u);
  // The horse's tack joints, each of them a joint of the horse the tool hands in.
  EXPECT_EQ(ready["tack_joints"], nlohmann::json({"saddle", "lStirrup", "rStirrup", "lRein", "rRein"}));
  for (const nlohmann::json& tack : ready["tack_joints"])
    EXPECT_NE(std::find(ready["horse_joints"].begin(), ready["horse_joints"].end(), tack), ready["horse_joints"].end()) << tack;

  std::ofstream requests(dir / "requests.jsonl");
  requests << nlohmann::json{{"get", 5}}.dump() << "\n"
           << "not json\n"
           << nlohmann::json{{"get", "five"}}.dump() << "\n"
           << nlohmann::json{{"set", {{{"frame", 30}, {"horse", identities(horse_joints)}}}}}.dump() << "\n"
           << nlohmann::json{{"set", {{{"frame", 5}, {"horse", identities(horse_joints - 1)}}}}}.dump() << "\n"
           << nlohmann::json{{"set", {{{"frame", 5}, {"horse", {{1, 2, 3}}}}}}}.dump() << "\n"
           << nlohmann::json{{"set", {{{"frame", 5}, {"horse", identities(horse_joints)}}}}}.dump() << "\n"
           << nlohmann::json{{"get", 5}}.dump() << "\n";
  requests.close();
  const CommandResult r = runCommand(quote(STIRRUP_EXE) + " live " + quote(scene.string()) + " --first 0 --last 23 < " +
                                     quote((dir / "requests.jsonl").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<nlohmann::json> out = linesOf(r.out);
  ASSERT_EQ(out.size(), 9u) << r.out;
  EXPECT_TRUE(out[0]["ready"].get<bool>());
  ASSERT_EQ(out[1]["frame"], 5);
  ASSERT_EQ(out[1]["rider"].size(), rider_joints);
  EXPECT_EQ(out[1]["rider"][0].size(), 16u);
  ASSERT_EQ(out[1]["tack"].size(), 5u) << "one deformation a tack joint";
  EXPECT_EQ(out[1]["tack"][3].size(), 16u);
  EXPECT_EQ(out[2], nlohmann::json({{"error", "expected a JSON object a line"}}));
  EXPECT_EQ(out[3], nlohmann::json({{"error", "get: expected a frame number"}}));
  EXPECT_EQ(out[4], nlohmann::json({{"error", "live: frame 30: expected a frame from 0 to 23"}}));
  EXPECT_EQ(out[5], nlohmann::json({{"error", "live: frame 5: expected " + std::to_string(horse_joints) + " horse joints, got " +
                                                  std::to_string(horse_joints - 1)}}));
  EXPECT_EQ(out[6], nlohmann::json({{"error", "set: frame 5: horse[0]: expected 16 numbers"}}));
  EXPECT_EQ(out[7], nlohmann::json({{"ok", true}}));
  // The horse at frame 5 handed in as every joint at its bind (identity deformations): her pose there moves.
  ASSERT_EQ(out[8]["rider"].size(), rider_joints);
  double moved = 0.0;
  for (std::size_t j = 0; j < rider_joints; ++j)
    for (std::size_t k = 12; k < 15; ++k) moved = std::max(moved, std::abs(out[8]["rider"][j][k].get<double>() - out[1]["rider"][j][k].get<double>()));
  EXPECT_GT(moved, 1e-3);
  // The rein ends go with her hands: the tack at frame 5 moves with the horse handed in.
  ASSERT_EQ(out[8]["tack"].size(), 5u);
  double rein_moved = 0.0;
  for (std::size_t k = 12; k < 15; ++k) rein_moved = std::max(rein_moved, std::abs(out[8]["tack"][3][k].get<double>() - out[1]["tack"][3][k].get<double>()));
  EXPECT_GT(rein_moved, 1e-3);
}

// A scene whose clip is not the horse's own file cannot be kept live: a one-line error naming it.
TEST(LiveCli, ASceneWhoseClipIsNotTheHorsesFileIsAOneLineError) {
  const CommandResult r = runCommand("echo | " + quote(STIRRUP_EXE) + " live " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "stirrup: " STIRRUP_SOURCE_DIR "/scenes/trot.json: clip.file: expected the horse's own file (" STIRRUP_SOURCE_DIR "/scenes/characters/horse.glb): live reads the horse "
                   "as the other tool keys it\n");
  EXPECT_EQ(r.out, "");
}

}  // namespace
}  // namespace stirrup::test
