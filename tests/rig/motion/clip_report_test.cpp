// The report prints each measured number beside its reference and verdict, as text and as JSON.
#include "rig/motion/clip_report.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/motion/procedural_gait.h"

namespace stirrup::rig {
namespace {

TEST(ClipReport, PrintsTheReferenceBesideTheNumbers) {
  const ProceduralGait trot(trotParams(), 4.0);
  const ClipInfo info = measureClip(trot);
  const auto ref = gaitReference("trot");
  ASSERT_TRUE(ref);
  const std::string text = formatClipInfo(info, &*ref);
  EXPECT_NE(text.find("stride frequency (Hz)        1.260   reference 1.24–1.28  ok"), std::string::npos) << text;
  EXPECT_EQ(text.find("OUTSIDE"), std::string::npos) << text;
  const nlohmann::json j = clipInfoJson(info, &*ref);
  EXPECT_EQ(j["footfall_order"], nlohmann::json({"lbHoof", "rfHoof", "rbHoof", "lfHoof"}));
  EXPECT_EQ(j["reference"]["suspensions_per_stride"], 2);
  EXPECT_TRUE(j["all_ok"].get<bool>());
  EXPECT_TRUE(j["verdicts"]["lfHoof.touchdown_phase"].get<bool>());
  EXPECT_TRUE(j["hooves"]["lfHoof"]["touchdown_ok"].get<bool>());
  EXPECT_NE(text.find("verdict: all 16 numbers inside the reference"), std::string::npos) << text;
  EXPECT_FALSE(gaitReference("pace"));
  EXPECT_FALSE(gaitReference("jump")->periodic);
}

}  // namespace
}  // namespace stirrup::rig
