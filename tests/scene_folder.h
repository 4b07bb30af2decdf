// Scene folders for the tests that run the program on scenes of their own: a fresh folder a test that
// holds the repository's thesis profile, and the scene files written into it.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace stirrup::test {

// The repository's thesis profile (scenes/profiles/thesis.json), for a scene written outside scenes/.
inline std::filesystem::path thesisProfile() { return std::filesystem::path(STIRRUP_SOURCE_DIR) / "scenes/profiles/thesis.json"; }

// A test's own folder, STIRRUP_BINARY_DIR/GROUP/<the test's name> (one folder per test: CTest runs tests
// in parallel processes), emptied before the test, with profiles/thesis.json in it for its scenes to
// name; write(NAME, TEXT) puts a scene file (or any file) in it.
class SceneFolderTest : public ::testing::Test {
 protected:
  explicit SceneFolderTest(const std::string& group)
      : dir(std::filesystem::path(STIRRUP_BINARY_DIR) / group / ::testing::UnitTest::GetInstance()->current_test_info()->name()) {}
  void SetUp() override {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir / "profiles");
    std::filesystem::copy_file(thesisProfile(), dir / "profiles/thesis.json");
  }
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const std::filesystem::path f = dir / name;
    std::ofstream(f) << text;
    return f;
  }

  std::filesystem::path dir;
};

}  // namespace stirrup::test
