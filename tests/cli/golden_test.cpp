// Golden images: two small frames of the trot side view rendered by the program and compared with
// the references checked in under tests/golden/. Rendering is deterministic (per-pixel random
// sequences, fixed BVH quality), so on the machine that made the references the difference is 0;
// the tolerance (Blender's: no more than 0.5% of pixels off by more than 4/255) leaves room for
// another CPU's floating-point paths without letting a moved limb or camera through.
// Update the references after an intended change with scripts/update-goldens.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "render/image_diff.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(STIRRUP_SOURCE_DIR) / "tests/golden";

render::DiffThresholds goldenThresholds() {
  render::DiffThresholds t;
  t.fail = 4.0 / 255.0;
  t.fail_fraction = 0.005;
  t.warn = 1.0 / 255.0;
  t.warn_fraction = 0.0;
  return t;
}

class Golden : public ::testing::TestWithParam<int> {};

TEST_P(Golden, TrotSideMatchesTheReference) {
  const int frame = GetParam();
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "golden_out" / ("frame" + std::to_string(frame));
  fs::remove_all(out);
  const CommandResult r = runStirrup("render " + quote((kGoldenDir / "trot_side.json").string()) +
                                     " --frames " + std::to_string(frame) + " --out " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  char name[64];
  std::snprintf(name, sizeof name, "trot_side.%04d.png", frame);
  const fs::path reference = kGoldenDir / name;
  ASSERT_TRUE(fs::exists(reference)) << reference << " is missing: run scripts/update-goldens";
  const fs::path diff = out / (std::string(name) + ".diff.png");
  const render::DiffResult d = render::compareImageFiles(reference, out / name, goldenThresholds(), diff);
  EXPECT_NE(d.verdict, render::DiffVerdict::Fail)
      << name << ": " << d.summary() << "\n  new: " << (out / name) << "\n  reference: " << reference
      << "\n  diff (x16): " << diff << "\n  after an intended change: scripts/update-goldens";
}

// Frame 4: the diagonal pairs spread wide and the rider lifted; frame 9: the pairs passing, the
// rider sunk back into the saddle.
INSTANTIATE_TEST_SUITE_P(Frames, Golden, ::testing::Values(4, 9));

TEST(GoldenDiff, ADifferentImageFails) {
  // The comparison itself must be able to fail: the two golden frames differ from each other.
  const render::DiffResult d = render::compareImageFiles(kGoldenDir / "trot_side.0004.png",
                                                         kGoldenDir / "trot_side.0009.png", goldenThresholds());
  EXPECT_EQ(d.verdict, render::DiffVerdict::Fail) << d.summary();
}

}  // namespace
}  // namespace stirrup::test
