#include "scene/data_dir.h"

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "rig/error.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;

// Sets STIRRUP_DATA for one test and restores it.
class DataDir : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* v = std::getenv("STIRRUP_DATA")) saved_ = v;
    ::unsetenv("STIRRUP_DATA");
    dir_ = fs::temp_directory_path() / ("stirrup_data_dir_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (saved_) ::setenv("STIRRUP_DATA", saved_->c_str(), 1);
    else ::unsetenv("STIRRUP_DATA");
    fs::remove_all(dir_);
  }
  std::optional<std::string> saved_;
  fs::path dir_;
};

TEST_F(DataDir, TheProgramsFolderIsReadFromTheSystem) {
  EXPECT_EQ(fs::canonical(programDir()), fs::canonical(fs::path(STIRRUP_BINARY_DIR) / "tests"));
}

// In the build tree, ../share/stirrup beside a program is the link to the source tree CMake makes
// (render/CMakeLists.txt): the same rule that finds P/share/stirrup for an installed P/bin/stirrup.
TEST_F(DataDir, InTheBuildTreeItIsTheSourceTreeByTheInstalledRule) {
  const std::optional<fs::path> d = findDataDir();
  ASSERT_TRUE(d);
  EXPECT_EQ(*d, fs::canonical(STIRRUP_SOURCE_DIR));
  EXPECT_TRUE(fs::is_regular_file(*d / "scenes/profiles/thesis.json"));
}

TEST_F(DataDir, StirrupDataOverridesAndIsNeverSecondGuessed) {
  fs::create_directories(dir_ / "mine/scenes");
  ::setenv("STIRRUP_DATA", (dir_ / "mine").c_str(), 1);
  EXPECT_EQ(dataDir(), fs::canonical(dir_ / "mine"));
  // A folder without scenes/ is an error naming it, not a silent fall back to the program's data.
  ::setenv("STIRRUP_DATA", dir_.c_str(), 1);
  EXPECT_FALSE(findDataDir());
  try {
    dataDir();
    FAIL() << "no error";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "STIRRUP_DATA: " + dir_.string() +
                                         ": no scenes/ folder there (expected stirrup's data folder, e.g. /usr/share/stirrup)");
  }
}

}  // namespace
}  // namespace stirrup::scene
