#include "rig/crowd_bake.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/motion/crowd.h"
#include "scene/rig_profile_json.h"

namespace stirrup::rig {
namespace {

RigProfile profileNamed(const std::string& name) {
  return scene::loadRigProfile(name, std::string(STIRRUP_SOURCE_DIR) + "/scenes/profiles");
}

// Twelve pairs cantering in three ranks, of mixed profiles.
std::vector<PairSpec> troop() {
  CrowdSpec s;
  s.pairs = 12;
  s.lead_points = {{0, 0}, {2000, 0}, {4000, 500}};
  s.lead_speed = {{0, 400}, {2, 560}};
  s.formation = {4, 300, 700, 10};
  s.start_offset_max_s = 1.0;
  s.speed_variation = 0.01;
  s.profile_mix = {{"thesis", 1}, {"english", 1}, {"novice", 1}};
  return generateCrowd(s, nullptr, 24, "t");
}

bool sameChannels(const RiderChannels& a, const RiderChannels& b) { return a.value == b.value; }

// Each pair's own clip and profile, as a shot makes them.
void clipsAndProfiles(const std::vector<PairSpec>& pairs, std::vector<std::unique_ptr<PathClip>>& clips,
                      std::vector<RigProfile>& profiles) {
  for (const PairSpec& p : pairs) {
    clips.push_back(makePairClip(p, nullptr, "t"));
    profiles.push_back(profileNamed(p.profile));
  }
}

// Each rider's channels in the crowd equal those of her pair baked alone: her own clip (made afresh
// from her pair alone) and her own profile, at her own phase.
TEST(CrowdBake, EachRiderIsHerHorsesAlone) {
  const std::vector<PairSpec> pairs = troop();
  std::vector<std::unique_ptr<PathClip>> clips;
  std::vector<RigProfile> profiles;
  clipsAndProfiles(pairs, clips, profiles);
  std::vector<CrowdPair> crowd;
  for (std::size_t i = 0; i < pairs.size(); ++i) crowd.push_back({clips[i].get(), &profiles[i], pairs[i].clip_offset_s});
  std::vector<std::unique_ptr<PathClip>> alone_clips;
  for (const PairSpec& p : pairs) alone_clips.push_back(makePairClip(p, nullptr, "alone"));
  for (int frame = 1; frame <= 96; frame += 7) {
    const double t = (frame - 1) / 24.0;
    const std::vector<BakedFrame> baked = bakeCrowdFrame(crowd, frame, t);
    ASSERT_EQ(baked.size(), pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const BakedFrame alone = bakeFrame(*alone_clips[i], profileNamed(pairs[i].profile), frame, t + pairs[i].clip_offset_s);
      EXPECT_TRUE(sameChannels(baked[i].rider, alone.rider)) << "pair " << i << " frame " << frame;
      EXPECT_EQ(baked[i].horse.controls.value, alone.horse.controls.value) << "pair " << i << " frame " << frame;
      EXPECT_EQ(baked[i].seconds, t);
    }
  }
}

// Changing one pair's profile changes only her channels; and no two riders move alike.
TEST(CrowdBake, OnePairsProfileChangesOnlyHer) {
  const std::vector<PairSpec> pairs = troop();
  std::vector<std::unique_ptr<PathClip>> clips;
  std::vector<RigProfile> profiles;
  clipsAndProfiles(pairs, clips, profiles);
  const auto crowdOf = [&](const std::vector<RigProfile>& pr) {
    std::vector<CrowdPair> c;
    for (std::size_t i = 0; i < pairs.size(); ++i) c.push_back({clips[i].get(), &pr[i], pairs[i].clip_offset_s});
    return c;
  };
  std::vector<RigProfile> changed = profiles;
  changed[5] = profileNamed(pairs[5].profile == "novice" ? "english" : "novice");
  const auto before = bakeCrowdFrame(crowdOf(profiles), 40, 39 / 24.0), after = bakeCrowdFrame(crowdOf(changed), 40, 39 / 24.0);
  for (std::size_t i = 0; i < pairs.size(); ++i)
    EXPECT_EQ(sameChannels(before[i].rider, after[i].rider), i != 5) << "pair " << i;
  for (std::size_t i = 0; i < pairs.size(); ++i)
    for (std::size_t j = i + 1; j < pairs.size(); ++j) EXPECT_FALSE(sameChannels(before[i].rider, before[j].rider)) << i << " " << j;
}

}  // namespace
}  // namespace stirrup::rig
