// The rigid rider (RigProfile::rigid, the built-in profile "rigid"): a rider fixed to the saddle, the
// contrast the layered review movies show against the rigged rider.
#include <cmath>
#include <filesystem>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "tests/rig/default_characters.h"

#include "rig/bake.h"
#include "rig/motion/procedural_gait.h"
#include "rig/pose.h"
#include "rig/rider_rig.h"
#include "scene/rig_profile_json.h"

namespace stirrup::rig {
namespace {

using test::defaultHorse;
using test::defaultRider;
const Character& horse() { return defaultHorse(); }
const Character& rider() { return defaultRider(); }

// The rider's pelvis in the posed saddle's frame.
glm::mat4 pelvisInSaddle(const ProceduralGait& clip, const RigProfile& profile, double seconds) {
  const BakedFrame b = bakeFrame(clip, profile, 1, seconds);
  const MountedPose pose = poseMounted(horse(), rider(), b.horse, b.rider, profile);
  return glm::inverse(pose.horse[size_t(horse().role("saddle"))]) * pose.rider[size_t(rider().role("pelvis"))];
}

float maxDifference(const glm::mat4& a, const glm::mat4& b) {
  float d = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
  return d;
}

TEST(RigidRider, BuiltInProfileSetsEveryRiderChannelToRest) {
  const RigProfile rigid = scene::loadRigProfile("rigid", std::filesystem::path(STIRRUP_SOURCE_DIR) / "scenes/profiles");
  EXPECT_EQ(rigid.name, "rigid");
  EXPECT_TRUE(rigid.rigid);
  EXPECT_FALSE(RigProfile::thesis().rigid);
  // A horse far from rest: pitched, rolled, hooves high and spread.
  HorseChannels h;
  h[HorseChannel::rearPivotRz] = 12;
  h[HorseChannel::rearPivotRx] = -6;
  h[HorseChannel::rearPivotTy] = 20;
  h[HorseChannel::lfHoofTy] = 40;
  h[HorseChannel::rfHoofTy] = 35;
  h[HorseChannel::lfHoofTx] = 30;
  h[HorseChannel::lbHoofTx] = -25;
  const RiderChannels r = evaluateRider(h, rigid);
  for (size_t i = 0; i < r.value.size(); ++i) EXPECT_EQ(r.value[i], 0.0) << "rider channel " << i;
  // The same horse moves the thesis rider.
  const RiderChannels t = evaluateRider(h, RigProfile::thesis());
  double moved = 0;
  for (double v : t.value) moved += std::abs(v);
  EXPECT_GT(moved, 10.0);
}

TEST(RigidRider, PelvisFollowsTheSaddleExactlyWhileTheThesisRidersDoesNot) {
  const ProceduralGait clip(gallopParams(900.0, Lead::Right), 2.0);
  const RigProfile rigid = RigProfile::rigidRider();
  const RigProfile thesis = RigProfile::thesis();
  // Over one gallop stride (2 Hz) at 24 fps the saddle pitches, rolls, rises and falls.
  const glm::mat4 rigid0 = pelvisInSaddle(clip, rigid, 0.0), thesis0 = pelvisInSaddle(clip, thesis, 0.0);
  float rigid_motion = 0, thesis_motion = 0, saddle_motion = 0;
  const BakedFrame b0 = bakeFrame(clip, rigid, 1, 0.0);
  const glm::vec3 saddle0 =
      glm::vec3(poseMounted(horse(), rider(), b0.horse, b0.rider, rigid).horse[size_t(horse().role("saddle"))][3]);
  for (int f = 1; f <= 12; ++f) {
    const double t = f / 24.0;
    rigid_motion = std::max(rigid_motion, maxDifference(pelvisInSaddle(clip, rigid, t), rigid0));
    thesis_motion = std::max(thesis_motion, maxDifference(pelvisInSaddle(clip, thesis, t), thesis0));
    const BakedFrame b = bakeFrame(clip, rigid, 1, t);
    const glm::vec3 saddle = glm::vec3(
        poseMounted(horse(), rider(), b.horse, b.rider, rigid).horse[size_t(horse().role("saddle"))][3]);
    saddle_motion = std::max(saddle_motion, std::abs(saddle.y - saddle0.y));
  }
  EXPECT_GT(saddle_motion, 2.0f) << "the saddle should move over a gallop stride";
  EXPECT_LT(rigid_motion, 1e-3f) << "the rigid rider's pelvis must stay put in the saddle";
  EXPECT_GT(thesis_motion, 0.5f) << "the thesis rider's pelvis should move in the saddle (lift, seat shift, hip)";
}

TEST(RigidRider, ProfileFileKeyAndJson) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "stirrup_rigid_profile_test";
  std::filesystem::create_directories(dir);
  {
    std::FILE* f = std::fopen((dir / "statue.json").c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("{\"rigid\": true, \"eq7.w2_scale\": 0.02}", f);
    std::fclose(f);
    f = std::fopen((dir / "bad.json").c_str(), "w");
    std::fputs("{\"rigid\": 1}", f);
    std::fclose(f);
  }
  const RigProfile p = scene::loadRigProfile((dir / "statue.json").string(), dir);
  EXPECT_TRUE(p.rigid);
  EXPECT_EQ(scene::profileToJson(p).value("rigid", false), true);
  EXPECT_FALSE(scene::profileToJson(RigProfile::thesis()).contains("rigid"));
  try {
    scene::loadRigProfile((dir / "bad.json").string(), dir);
    FAIL() << "a non-boolean rigid should be an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("rigid: expected true or false"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace stirrup::rig
