// Replays every checked-in fuzz input, the seed corpora (tests/fuzz/corpus/NAME) and the inputs of past
// findings (tests/fuzz/regressions/NAME), through the fuzz targets (tests/fuzz/targets.h) in the normal
// build, so a regression shows on every test run, with or without clang. A target aborts on anything but
// a one-line InputError, which fails the test. The scene seeds must also get past the reader: each
// reaches its clip and its bake with the files it names (FuzzSceneSeeds).
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
void PrintTo(SceneStage s, std::ostream* os);
void PrintTo(SceneStage s, std::ostream* os) {
  static const char* const kNames[] = {"refused", "read", "profile resolved", "clip made", "baked"};
  *os << kNames[static_cast<int>(s)];
}

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

// A target without past findings has nothing to replay here: reported skipped, not passed.
TEST_P(FuzzInputs, PastFindingsStayFixed) {
  const NamedTarget& t = GetParam();
  const std::vector<fs::path> findings = inputs(kFuzzDir / "regressions" / std::string(t.name));
  if (findings.empty()) GTEST_SKIP() << "no past findings for " << t.name << " (tests/fuzz/regressions/" << t.name << ")";
  for (const fs::path& f : findings) replay(t, f);
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzInputs, ::testing::ValuesIn(kTargets),
                         [](const ::testing::TestParamInfo<NamedTarget>& info) { return std::string(info.param.name); });

// The scene seeds are the shipped scenes (tests/fuzz/corpus/scene_json): each must get through all
// that sceneJson does with it (read, its profile, its clip, its first frames baked) with the files it
// names, or the corpus exercises little but the reader's error paths. Counted by hand: 13 seeds, of
// which the two fox scenes name the shared assets' Fox.glb (checked apart, skipped without them) and
// 11 name only files of the repository (characters/*.glb, profiles, the golden scene's
// ../../scenes/profiles/thesis.json).
const std::vector<std::string> kSeedsOnSharedAssets = {"fox.json", "fox_run.json"};

struct StageCount {
  int seeds = 0, clip = 0, baked = 0;
};
StageCount countStages(bool on_shared_assets) {
  StageCount n;
  for (const fs::path& f : inputs(kFuzzDir / "corpus" / "scene_json")) {
    const std::string name = f.filename().string();
    const bool shared = std::find(kSeedsOnSharedAssets.begin(), kSeedsOnSharedAssets.end(), name) != kSeedsOnSharedAssets.end();
    if (shared != on_shared_assets) continue;
    std::ifstream in(f, std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const SceneStage stage = sceneJsonStage(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    ++n.seeds;
    n.clip += stage >= SceneStage::Clip;
    n.baked += stage == SceneStage::Baked;
    EXPECT_EQ(stage, SceneStage::Baked) << name;
  }
  return n;
}

TEST(FuzzSceneSeeds, ReachTheClipAndTheBakeWithTheFilesTheyName) {
  const StageCount n = countStages(false);
  EXPECT_EQ(n.seeds, 11);
  EXPECT_EQ(n.clip, 11);
  EXPECT_EQ(n.baked, 11);
}

TEST(FuzzSceneSeeds, FoxSeedsReachTheClipAndTheBakeWithTheSharedAssets) {
  if (!fs::exists(fs::path(STIRRUP_SHARED_DIR) / "assets/fox/Fox.glb"))
    GTEST_SKIP() << STIRRUP_SHARED_DIR "/assets/fox/Fox.glb is not here (the shared assets)";
  const StageCount n = countStages(true);
  EXPECT_EQ(n.seeds, 2);
  EXPECT_EQ(n.clip, 2);
  EXPECT_EQ(n.baked, 2);
}

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
