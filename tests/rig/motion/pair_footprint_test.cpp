#include "rig/motion/pair_footprint.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "tests/rig/default_characters.h"

#include "rig/bake.h"
#include "rig/characters/proportions.h"
#include "rig/motion/path_clip.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "rig/skin.h"

namespace stirrup::rig {
namespace {

GroundRect rect(glm::dvec2 c, double heading_deg, double hl, double hw) {
  const double h = heading_deg * std::numbers::pi / 180.0;
  return {c, {std::cos(h), std::sin(h)}, hl, hw};
}

TEST(PairFootprint, OverlapsBySeparatingAxes) {
  const GroundRect a = rect({0, 0}, 0, 2, 1);
  // Side by side along x: a gap of 0.5, then an overlap of 0.1.
  EXPECT_FALSE(overlaps(a, rect({4.5, 0}, 0, 2, 1)));
  EXPECT_TRUE(overlaps(a, rect({3.9, 0}, 0, 2, 1)));
  // A square turned 45°: its corner reaches 2 - √2 toward a, so at 3.5 it stops at x = 2.086, at 3.4 at 1.986.
  EXPECT_FALSE(overlaps(a, rect({3.5, 0}, 45, 1, 1)));
  EXPECT_TRUE(overlaps(a, rect({3.4, 0}, 45, 1, 1)));
  // Two thin diagonal rectangles whose axis-aligned boxes overlap but which lie side by side: 3/√2 apart
  // across their length (their widths add to 1), then 0.6·√2 = 0.85 apart.
  const GroundRect d = rect({0, 0}, 45, 5, 0.5);
  EXPECT_FALSE(overlaps(d, rect({1.5, -1.5}, 45, 5, 0.5)));
  EXPECT_TRUE(overlaps(d, rect({0.6, -0.6}, 45, 5, 0.5)));
  // Symmetric.
  EXPECT_TRUE(overlaps(rect({0.6, -0.6}, 45, 5, 0.5), d));
}

// A canter into a gallop through a right and a left turn: the turns roll the body (up to the 20°
// limit), the gallop swings the legs and the tail farthest.
PathClipParams canterToGallopTurns() {
  PathClipParams p;
  p.points = {{0, 0}, {1500, 0}, {2600, 600}, {3200, 1600}, {3800, 2600}, {4900, 3200}, {6500, 3200}};
  p.speed = {{0, 560}, {3, 560}, {5, 950}};
  p.variation = 0.3;
  return p;
}

// How far the farthest vertex of the skinned horse and rider, seen from above, lies outside the pair's
// footprint (negative: inside by that much), over every sixth frame of the ride; the point-in-rectangle
// test here is the test's own. Also the largest roll into a turn the ride made.
struct Outside {
  double cm = -1e9, roll_deg = 0;
};
Outside farthestOutside(const Character& horse, const Character& rider, const PairExtent& e, const RigProfile& profile);
Outside farthestOutside(const HorseParams& hp_params, const RiderParams& rp_params, const RigProfile& profile) {
  const Character horse = hp_params.withers_height == HorseParams{}.withers_height ? test::defaultHorse() : buildHorse(hp_params);
  const Character rider = rp_params.head.y == RiderParams{}.head.y ? test::defaultRider() : buildRider(rp_params, hp_params.mount);
  return farthestOutside(horse, rider, pairExtent(hp_params, rp_params), profile);
}
Outside farthestOutside(const Character& horse, const Character& rider, const PairExtent& e, const RigProfile& profile) {
  PathClipParams params = canterToGallopTurns();
  params.hoof_rest = e.hoof_rest;
  const PathClip clip(params, nullptr, "test");
  Outside out;
  std::vector<glm::vec3> hp, hn, rp, rn;
  for (int frame = 1; frame <= static_cast<int>(clip.duration() * 24.0); frame += 6) {
    const double t = (frame - 1) / 24.0;
    const BakedFrame b = bakeFrame(clip, profile, frame, t);
    out.roll_deg = std::max(out.roll_deg, std::abs(clip.turnRollDeg(t)));
    const MountedPose pose = poseMounted(horse, rider, b.horse, b.rider, profile);
    skinMesh(horse.mesh, horse.skeleton, pose.horse, hp, hn);
    skinMesh(rider.mesh, rider.skeleton, pose.rider, rp, rn);
    const GroundRect g = pairFootprint(e, b.horse);
    const glm::dvec2 across{-g.axis.y, g.axis.x};
    for (const auto* mesh : {&hp, &rp})
      for (const glm::vec3& v : *mesh) {
        const glm::dvec2 d = glm::dvec2{v.x, v.z} - g.center;
        out.cm = std::max({out.cm, std::abs(glm::dot(d, g.axis)) - g.half_length, std::abs(glm::dot(d, across)) - g.half_width});
      }
  }
  return out;
}

// The default pair, and the largest and smallest a crowd may hold (rig/motion/crowd.h's ranges, built
// from the scaled generator parameters), with the thesis profile and a looser seat.
TEST(PairFootprint, HoldsTheSkinnedHorseAndRider) {
  const RigProfile thesis = RigProfile::thesis();
  RigProfile loose = thesis;
  loose.eq1.w1_pivot_pitch *= 2.0;  // twice the lean forward with the horse's pitch
  struct Case {
    const char* name;
    HorseParams horse;
    RiderParams rider;
  };
  const Case cases[] = {{"default", HorseParams{}, RiderParams{}},
                        {"largest", scaledHorse(175, 190), scaledRider(190, 1.25)},
                        {"smallest", scaledHorse(145, 150), scaledRider(150, 0.85)}};
  for (const Case& c : cases)
    for (const RigProfile* profile : std::initializer_list<const RigProfile*>{&thesis, &loose}) {
      const Outside o = farthestOutside(c.horse, c.rider, *profile);
      EXPECT_LE(o.cm, 0.0) << c.name << ": a vertex " << o.cm << " cm outside the footprint";
      // Not vacuous: some vertex comes within the margin and a little of the edge.
      EXPECT_GT(o.cm, -kPoseMarginCm - 5.0) << c.name;
      EXPECT_GT(o.roll_deg, 10.0) << c.name;  // the ride did roll the body into its turns
    }
}

// Measured on the characters themselves (a crowd pair riding a user's horse or rider, issue 60): the box
// of the default pair's skinned meshes at rest holds them over the same ride, and is no looser than
// the generator's parameters' box by more than a margin's worth.
TEST(PairFootprint, MeasuredOnTheCharactersItHoldsThemToo) {
  const PairExtent measured = pairExtent(test::defaultHorse(), test::defaultRider());
  const PairExtent built = pairExtent(HorseParams{}, RiderParams{});
  const Outside o = farthestOutside(test::defaultHorse(), test::defaultRider(), measured, RigProfile::thesis());
  EXPECT_LE(o.cm, 0.0) << "a vertex " << o.cm << " cm outside the footprint";
  EXPECT_GT(o.cm, -kPoseMarginCm - 5.0);
  EXPECT_NEAR(measured.top_cm, built.top_cm, kPoseMarginCm);
  EXPECT_NEAR(measured.half_width_cm, built.half_width_cm, kPoseMarginCm);
  for (std::size_t h = 0; h < 4; ++h) EXPECT_NEAR(glm::length(measured.hoof_rest[h] - built.hoof_rest[h]), 0.0, 1.0) << h;
  std::printf("measured box: %.1f to %.1f cm along, +-%.1f across, %.1f high (the generator's: %.1f to %.1f, +-%.1f, %.1f)\n",
              measured.back_cm, measured.front_cm, measured.half_width_cm, measured.top_cm, built.back_cm, built.front_cm,
              built.half_width_cm, built.top_cm);
}

// A larger pair than the default, built from the scaled generator parameters.
TEST(PairFootprint, GrowsWithTheHorse) {
  HorseParams big;
  big.withers_height *= 1.1f;
  big.barrel_radii *= 1.1f;
  big.muzzle *= 1.1f;
  const PairExtent a = pairExtent(HorseParams{}, RiderParams{}), b = pairExtent(big, RiderParams{});
  EXPECT_GT(b.front_cm, a.front_cm);
  EXPECT_GE(b.half_width_cm, a.half_width_cm);
  // The default horse: the muzzle at 140 cm is inside the head's reach; the tail's 80 cm hang behind its root at -92.
  EXPECT_GT(a.front_cm, 148.0);
  EXPECT_LT(a.back_cm, -172.0);
  EXPECT_GT(a.top_cm, 230.0);  // the rider's crown
}

// Two horses whose paths cross at the same moment meet there; a minute apart they do not.
TEST(PairFootprint, FirstOverlapFindsACrossing) {
  PathClipParams along, across;
  along.points = {{0, 0}, {3000, 0}};
  along.speed = {{0, 300}};
  across.points = {{1500, -1500}, {1500, 1500}};
  across.speed = {{0, 300}};
  const PathClip a(along, nullptr, "a"), b(across, nullptr, "b");
  const PairExtent e = pairExtent(HorseParams{}, RiderParams{});
  const std::vector<const Clip*> clips = {&a, &b};
  const std::vector<PairExtent> extents = {e, e};
  const auto hit = firstOverlap(clips, std::vector<double>{0.0, 0.0}, extents, 24.0, 240);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->a, 0u);
  EXPECT_EQ(hit->b, 1u);
  // Both reach the crossing at 5 s; they meet before, when their footprints' corners first touch.
  EXPECT_GT(hit->seconds, 3.0);
  EXPECT_LT(hit->seconds, 5.0);
  EXPECT_EQ(hit->frame, static_cast<int>(std::lround(hit->seconds * 24.0)) + 1);
  // The second horse starts 6 s late (its clip is sampled 6 s behind... by starting it farther back).
  across.points = {{1500, -3300}, {1500, 1500}};
  const PathClip late(across, nullptr, "late");
  const std::vector<const Clip*> apart = {&a, &late};
  EXPECT_FALSE(firstOverlap(apart, std::vector<double>{0.0, 0.0}, extents, 24.0, 240).has_value());
}

}  // namespace
}  // namespace stirrup::rig
