// What scenes/ holds (README, "A five-minute tour"): every JSON file directly in it is a scene that renders
// from a fresh clone, with nothing beside the repository (no third-party files); scenes needing those, and
// inputs that are not scenes, live in folders of their own (scenes/fox/, scenes/spine/, scenes/profiles/,
// scenes/characters/).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

TEST(ScenesFolder, EveryJsonDirectlyInScenesRendersFromAClone) {
  // The scenes copied where nothing is beside them (as a clone without the third-party folder), with the
  // characters the build made and the profiles.
  const fs::path clone = fs::path(STIRRUP_BINARY_DIR) / "test_scenes_folder" / "clone";
  fs::remove_all(clone.parent_path());
  fs::create_directories(clone);
  fs::copy(fs::path(STIRRUP_SOURCE_DIR) / "scenes", clone / "scenes", fs::copy_options::recursive);
  std::vector<std::string> rendered;
  for (const fs::directory_entry& e : fs::directory_iterator(clone / "scenes")) {
    if (e.path().extension() != ".json") continue;
    const fs::path out = clone / "out" / e.path().stem();
    const CommandResult r = runStirrup("render " + quote(e.path().string()) + " --frames 1 --preset draft --resolution 64x36 --out " +
                                       quote(out.string()));
    EXPECT_EQ(r.exit_code, 0) << e.path().filename() << ": " << r.err;
    EXPECT_TRUE(fs::exists(out) && !fs::is_empty(out)) << e.path().filename() << " rendered no frame";
    rendered.push_back(e.path().stem().string());
  }
  EXPECT_GE(rendered.size(), 14u) << "the default scenes";
}

}  // namespace
}  // namespace stirrup::test
