// stirrup bake --channels: the CSV of every channel of every frame, and the help that documents it.
#include <algorithm>
#include <map>
#include <set>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/channels.h"
#include "tests/cli/run_command.h"
#include "tests/cli/bake_support.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

TEST(Bake, WritesEveryChannelOfEveryFrame) {
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "test_bake" / "trot.csv";
  fs::remove_all(out.parent_path());
  const CommandResult r = runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json") +
                                     " --frames 1-48x2 --channels " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  std::stringstream csv(readText(out));
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = split(line);
  ASSERT_EQ(header.size(), 2 + rig::kHorseChannelCount + rig::kRiderChannelCount);
  EXPECT_EQ(header[0], "frame");
  EXPECT_EQ(header[1], "time");
  for (auto n : rig::kHorseChannelNames)
    EXPECT_NE(std::find(header.begin(), header.end(), std::string(n)), header.end()) << n;
  for (auto n : rig::kRiderChannelNames)
    EXPECT_NE(std::find(header.begin(), header.end(), std::string(n)), header.end()) << n;

  const auto column = [&](const std::string& n) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), n) - header.begin());
  };
  std::vector<double> lift, frame;
  while (std::getline(csv, line)) {
    const auto cells = split(line);
    ASSERT_EQ(cells.size(), header.size());
    frame.push_back(std::stod(cells[0]));
    lift.push_back(std::stod(cells[column("cog.ty")]));
  }
  ASSERT_EQ(frame.size(), 24u);
  EXPECT_EQ(frame.front(), 1.0);
  EXPECT_EQ(frame.back(), 47.0);
  // The rider bounces at the trot: the lift varies over two seconds of trot.
  const auto [lo, hi] = std::minmax_element(lift.begin(), lift.end());
  EXPECT_GT(*hi - *lo, 0.05);
}

TEST(Bake, HelpDocumentsTheCsv) {
  const CommandResult r = runStirrup("bake --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--channels"), std::string::npos);
  EXPECT_NE(r.out.find("docs/channels.md"), std::string::npos);
}

}  // namespace
}  // namespace stirrup::test
