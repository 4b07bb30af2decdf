// Replays every checked-in fuzz input, the seed corpora (tests/fuzz/corpus/NAME) and the inputs of past
// findings (tests/fuzz/regressions/NAME), through the fuzz targets (tests/fuzz/targets.h) in the normal
// build, so a regression shows on every test run, with or without clang. A target aborts on anything but
// a one-line InputError, which fails the test.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/fuzz/targets.h"

namespace stirrup::fuzz {

// Test names show the target's name (found by ADL, so outside the anonymous namespace).
void PrintTo(const NamedTarget& t, std::ostream* os);
void PrintTo(const NamedTarget& t, std::ostream* os) { *os << t.name; }

namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(STIRRUP_SOURCE_DIR) / "tests" / "fuzz";

std::vector<fs::path> inputs(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

void replay(const NamedTarget& target, const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  ASSERT_TRUE(in) << file;
  const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  SCOPED_TRACE(file.string());
  EXPECT_EQ(target.run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), 0);
}

class FuzzInputs : public ::testing::TestWithParam<NamedTarget> {};

TEST_P(FuzzInputs, SeedCorpusReadsWithoutFindings) {
  const NamedTarget& t = GetParam();
  const std::vector<fs::path> seeds = inputs(kFuzzDir / "corpus" / std::string(t.name));
  EXPECT_FALSE(seeds.empty()) << "no seeds in tests/fuzz/corpus/" << t.name;
  for (const fs::path& f : seeds) replay(t, f);
  EXPECT_TRUE(fs::exists(kFuzzDir / ("fuzz_" + std::string(t.name) + ".cpp"))) << "no libFuzzer target for " << t.name;
}

TEST_P(FuzzInputs, PastFindingsStayFixed) {
  const NamedTarget& t = GetParam();
  for (const fs::path& f : inputs(kFuzzDir / "regressions" / std::string(t.name))) replay(t, f);
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzInputs, ::testing::ValuesIn(kTargets),
                         [](const ::testing::TestParamInfo<NamedTarget>& info) { return std::string(info.param.name); });

// Every folder of inputs belongs to a target (a typo in a folder name would silently replay nothing).
TEST(FuzzInputFolders, NameKnownTargets) {
  for (const char* kind : {"corpus", "regressions"})
    for (const auto& e : fs::directory_iterator(kFuzzDir / kind)) {
      if (!e.is_directory()) continue;
      const std::string name = e.path().filename().string();
      EXPECT_TRUE(std::any_of(std::begin(kTargets), std::end(kTargets), [&](const NamedTarget& t) { return t.name == name; }))
          << kind << "/" << name << " is not a fuzz target";
    }
}

}  // namespace
}  // namespace stirrup::fuzz
