// OutputFolder (cli/output_folder.h): a folder a command creates is taken back when the command
// fails before writing into it, and only then.
#include "cli/output_folder.h"

#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

namespace stirrup::cli {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const char* name) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_output_folder" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(OutputFolder, AFailureBeforeAnyFileRemovesTheFoldersItCreated) {
  const fs::path base = scratch("failed");
  EXPECT_THROW(
      {
        const OutputFolder folder(base / "a" / "b");
        ASSERT_TRUE(fs::is_directory(base / "a" / "b"));
        throw std::runtime_error("mapping: no such joint");
      },
      std::runtime_error);
  EXPECT_FALSE(fs::exists(base / "a"));  // both levels it made are gone
  EXPECT_TRUE(fs::is_directory(base));   // what was there before stays
}

TEST(OutputFolder, AFailureAfterAFileKeepsTheFolder) {
  const fs::path base = scratch("partial");
  EXPECT_THROW(
      {
        const OutputFolder folder(base / "out");
        std::ofstream(base / "out" / "shot.0001.png") << "x";
        throw std::runtime_error("frame 2: cannot pose");
      },
      std::runtime_error);
  EXPECT_TRUE(fs::exists(base / "out" / "shot.0001.png"));
}

TEST(OutputFolder, SuccessKeepsAnEmptyFolderAndAFailureNeverRemovesOneThatExisted) {
  const fs::path base = scratch("kept");
  { const OutputFolder folder(base / "done"); }
  EXPECT_TRUE(fs::is_directory(base / "done"));
  EXPECT_THROW(
      {
        const OutputFolder folder(base / "done");
        throw std::runtime_error("later failure");
      },
      std::runtime_error);
  EXPECT_TRUE(fs::is_directory(base / "done"));
}

}  // namespace
}  // namespace stirrup::cli
