#include "rig/motion/crowd.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "rig/characters/palette.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

using test::errorOf;

// 30 riders cantering into a gallop through a long bend (the cavalry), files of 6.
CrowdSpec cavalry(int pairs, int files) {
  CrowdSpec s;
  s.pairs = pairs;
  s.lead_points = {{0, 0}, {3000, 0}, {6000, 800}, {9000, 800}};
  s.lead_speed = {{0, 560}, {3, 560}, {5, 900}};  // canter, then gallop from about 4 s
  s.formation.files = files;
  s.formation.file_spacing_cm = 340;
  s.formation.rank_spacing_cm = 800;
  s.formation.jitter_cm = 15;
  s.speed_variation = 0.01;
  s.start_offset_max_s = 1.0;
  s.profile_mix = {{"thesis", 2}, {"novice", 1}};
  s.seed = 7;
  return s;
}

// A short, slow crowd for what does not need a long ride: many pairs cheaply.
CrowdSpec parade(int pairs, int files) {
  CrowdSpec s;
  s.pairs = pairs;
  s.lead_points = {{0, 0}, {600, 0}};
  s.lead_speed = {{0, 300}};
  s.formation.files = files;
  s.formation.file_spacing_cm = 300;
  s.formation.rank_spacing_cm = 600;
  s.formation.jitter_cm = 10;
  s.seed = 3;
  return s;
}

bool samePair(const PairSpec& a, const PairSpec& b) {
  if (a.path.points.size() != b.path.points.size() || a.path.speed.size() != b.path.speed.size()) return false;
  for (std::size_t i = 0; i < a.path.points.size(); ++i)
    if (a.path.points[i] != b.path.points[i]) return false;
  for (std::size_t i = 0; i < a.path.speed.size(); ++i)
    if (a.path.speed[i].at != b.path.speed[i].at || a.path.speed[i].speed != b.path.speed[i].speed) return false;
  return a.clip_offset_s == b.clip_offset_s && a.profile == b.profile && a.withers_height_cm == b.withers_height_cm &&
         a.rider_height_cm == b.rider_height_cm && a.rider_build == b.rider_build && a.path.seed == b.path.seed &&
         a.path.variation == b.path.variation;
}

TEST(Crowd, TheSameSpecGivesTheSamePairs) {
  const auto a = generateCrowd(parade(12, 4), nullptr, 24, "t"), b = generateCrowd(parade(12, 4), nullptr, 24, "t");
  ASSERT_EQ(a.size(), 12u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(samePair(a[i], b[i])) << i;
  // Another seed: every pair differs.
  CrowdSpec other = parade(12, 4);
  other.seed = 4;
  const auto c = generateCrowd(other, nullptr, 24, "t");
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_FALSE(samePair(a[i], c[i])) << i;
    EXPECT_NE(a[i].withers_height_cm, c[i].withers_height_cm) << i;
    EXPECT_NE(a[i].path.seed, c[i].path.seed) << i;
  }
}

// Pair i is drawn from its own generator: the first ten of a crowd of 30 are a crowd of 10.
TEST(Crowd, APairDoesNotDependOnHowManyFollow) {
  const auto ten = generateCrowd(parade(10, 5), nullptr, 24, "t"), thirty = generateCrowd(parade(30, 5), nullptr, 24, "t");
  for (std::size_t i = 0; i < ten.size(); ++i) EXPECT_TRUE(samePair(ten[i], thirty[i])) << i;
}

// The slots: pair 0 is the front rank's leftmost file; a file is file_spacing across, a rank rank_spacing
// behind, each within the jitter. The lead runs along +X here, so across is z and along is x.
TEST(Crowd, PairsStandInTheirSlots) {
  CrowdSpec s = parade(8, 4);
  s.start_offset_max_s = 0.0;  // no phase: each path starts at its slot
  const auto pairs = generateCrowd(s, nullptr, 24, "t");
  for (int i = 0; i < 8; ++i) {
    const glm::dvec2 start = pairs[std::size_t(i)].path.points.front();
    const double z = (i % 4 - 1.5) * 300.0, x = -(i / 4) * 600.0;
    EXPECT_NEAR(start.y, z, 10.0 + 1e-9) << i;
    EXPECT_NEAR(start.x, x, 10.0 + 1e-9) << i;
  }
}

// With a start phase each path begins farther back by what the pair rides in its phase's time, so at
// the shot's first frame it stands in its slot all the same.
TEST(Crowd, AStartPhaseKeepsThePairInItsSlot) {
  CrowdSpec s = parade(8, 4);
  s.start_offset_max_s = 2.0;
  s.formation.jitter_cm = 0.0;
  const auto pairs = generateCrowd(s, nullptr, 24, "t");
  double largest = 0.0;
  for (int i = 0; i < 8; ++i) {
    const PairSpec& p = pairs[std::size_t(i)];
    largest = std::max(largest, p.clip_offset_s);
    const auto clip = makePairClip(p, nullptr, "t");
    const HorseFrame f = clip->sample(p.clip_offset_s);
    EXPECT_NEAR(f.travel_cm, -(i / 4) * 600.0, 1.0) << i;
    EXPECT_NEAR(f.travel_z_cm, (i % 4 - 1.5) * 300.0, 1.0) << i;
  }
  EXPECT_GT(largest, 1.0);  // the phases did spread
}

TEST(Crowd, ProportionsStayInTheirRangesAndVary) {
  CrowdSpec s = parade(100, 10);
  s.withers_height_cm = {150, 170};
  s.rider_height_cm = {155, 185};
  s.rider_build = {0.9, 1.2};
  const auto pairs = generateCrowd(s, nullptr, 24, "t");
  const auto check = [&](auto get, ProportionRange r, const char* what) {
    double lo = 1e9, hi = -1e9, sum = 0, sum2 = 0;
    for (const PairSpec& p : pairs) {
      const double v = get(p);
      EXPECT_GE(v, r.lo) << what;
      EXPECT_LE(v, r.hi) << what;
      lo = std::min(lo, v), hi = std::max(hi, v), sum += v, sum2 += v * v;
    }
    const double w = r.hi - r.lo, mean = sum / 100.0, sd = std::sqrt(sum2 / 100.0 - mean * mean);
    // Spread over the range: a uniform draw's extremes of 100 fall within 5% of each end, its standard
    // deviation is w/√12.
    EXPECT_LT(lo, r.lo + 0.05 * w) << what;
    EXPECT_GT(hi, r.hi - 0.05 * w) << what;
    EXPECT_NEAR(sd, w / std::sqrt(12.0), 0.2 * w / std::sqrt(12.0)) << what;
  };
  check([](const PairSpec& p) { return p.withers_height_cm; }, s.withers_height_cm, "withers");
  check([](const PairSpec& p) { return p.rider_height_cm; }, s.rider_height_cm, "rider height");
  check([](const PairSpec& p) { return p.rider_build; }, s.rider_build, "build");
  // The characters' parameters follow: the horse's withers, the rider's head above the seat.
  for (const PairSpec& p : pairs) {
    EXPECT_FLOAT_EQ(p.horse().withers_height, static_cast<float>(p.withers_height_cm));
    EXPECT_NEAR(p.rider().head.y, 66.0 * p.rider_height_cm / 170.0, 1e-4);
  }
}

TEST(Crowd, TheProfileMixIsHonoured) {
  CrowdSpec s = parade(200, 20);
  s.profile_mix = {{"thesis", 2}, {"english", 0}, {"novice", 1}};
  const auto pairs = generateCrowd(s, nullptr, 24, "t");
  std::map<std::string, int> count;
  for (const PairSpec& p : pairs) ++count[p.profile];
  EXPECT_EQ(count["english"], 0);
  // 2 : 1 of 200: 133 thesis expected, binomial standard deviation 6.7; three of them is 20.
  EXPECT_NEAR(count["thesis"], 133.3, 20.0);
  EXPECT_EQ(count["thesis"] + count["novice"], 200);
}

// Two footprints meet, by the test's own construction: convex quadrilaterals meet when an edge of one
// crosses an edge of the other or one holds a corner of the other.
std::array<glm::dvec2, 4> corners(const GroundRect& g) {
  const glm::dvec2 l = g.axis * g.half_length, w = glm::dvec2{-g.axis.y, g.axis.x} * g.half_width;
  return {g.center + l + w, g.center - l + w, g.center - l - w, g.center + l - w};
}
double cross(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }
bool holds(const std::array<glm::dvec2, 4>& q, glm::dvec2 p) {
  int sign = 0;
  for (int i = 0; i < 4; ++i) {
    const double c = cross(q[(i + 1) % 4] - q[i], p - q[i]);
    const int s = c > 0 ? 1 : c < 0 ? -1 : 0;
    if (s != 0 && sign != 0 && s != sign) return false;
    if (s != 0) sign = s;
  }
  return true;
}
bool segmentsCross(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}
bool meet(const GroundRect& a, const GroundRect& b) {
  const auto p = corners(a), q = corners(b);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (segmentsCross(p[i], p[(i + 1) % 4], q[j], q[(j + 1) % 4])) return true;
  return holds(p, q[0]) || holds(q, p[0]);
}

// Every two pairs, at every frame of the shot, by brute force: the nearest two footprints' gap
// (in the footprints' own terms: whether they meet) and how many frames were looked at.
struct BruteForce {
  bool any_meet = false;
  int frames = 0;
};
BruteForce bruteForce(const std::vector<PairSpec>& pairs, int frames, double fps) {
  std::vector<std::unique_ptr<PathClip>> clips;
  std::vector<PairExtent> extents;
  for (const PairSpec& p : pairs) {
    clips.push_back(makePairClip(p, nullptr, "t"));
    extents.push_back(pairExtent(p.horse(), p.rider()));
  }
  BruteForce out;
  std::vector<GroundRect> g(pairs.size());
  for (int frame = 1; frame <= frames; ++frame, ++out.frames) {
    const double t = (frame - 1) / fps;
    for (std::size_t i = 0; i < pairs.size(); ++i) g[i] = pairFootprint(extents[i], clips[i]->sample(t + pairs[i].clip_offset_s));
    for (std::size_t i = 0; i < pairs.size(); ++i)
      for (std::size_t j = i + 1; j < pairs.size(); ++j) out.any_meet = out.any_meet || meet(g[i], g[j]);
  }
  return out;
}

TEST(Crowd, TheBruteForceCheckSeesAnOverlap) {
  // Not vacuous: two pairs on paths 100 cm apart meet at once.
  PairSpec a, b;
  a.path.points = {{0, 0}, {1000, 0}};
  a.path.speed = {{0, 300}};
  b = a;
  b.path.points = {{0, 100}, {1000, 100}};
  EXPECT_TRUE(bruteForce({a, b}, 2, 24.0).any_meet);
  b.path.points = {{0, 400}, {1000, 400}};
  EXPECT_FALSE(bruteForce({a, b}, 48, 24.0).any_meet);
}

TEST(Crowd, ThirtyPairsNeverOverlap) {
  const CrowdSpec s = cavalry(30, 6);
  const auto pairs = generateCrowd(s, nullptr, 24, "t");
  const int frames = crowdFrames(s, nullptr, 24, "t");
  EXPECT_GT(frames, 24 * 10);  // the whole canter and gallop, over ten seconds
  const BruteForce b = bruteForce(pairs, frames, 24.0);
  EXPECT_EQ(b.frames, frames);
  EXPECT_FALSE(b.any_meet);
}

TEST(Crowd, AHundredPairsNeverOverlap) {
  CrowdSpec s = cavalry(100, 10);
  s.formation.file_spacing_cm = 350;  // ten files reach farther into the bend: its inside turns tighter
  const auto pairs = generateCrowd(s, nullptr, 24, "t");
  const BruteForce b = bruteForce(pairs, crowdFrames(s, nullptr, 24, "t"), 24.0);
  EXPECT_FALSE(b.any_meet);
}

// Pairs differ: proportions, profiles, and their horses' motion (no two move alike).
TEST(Crowd, NoTwoPairsMoveAlike) {
  const auto pairs = generateCrowd(cavalry(30, 6), nullptr, 24, "t");
  std::vector<std::unique_ptr<PathClip>> clips;
  for (const PairSpec& p : pairs) clips.push_back(makePairClip(p, nullptr, "t"));
  for (std::size_t i = 0; i < pairs.size(); ++i)
    for (std::size_t j = i + 1; j < pairs.size(); ++j) {
      const HorseFrame a = clips[i]->sample(3.0 + pairs[i].clip_offset_s), b = clips[j]->sample(3.0 + pairs[j].clip_offset_s);
      double differ = 0.0;
      for (std::size_t c = 0; c < a.controls.value.size(); ++c) differ = std::max(differ, std::abs(a.controls.value[c] - b.controls.value[c]));
      EXPECT_GT(differ, 0.5) << i << " and " << j;
    }
}

// A troop's pairs wear different colours: thirty pairs draw at least five coats and five jackets, the
// same spec draws the same ones, and each pair's characters carry its colours.
TEST(Crowd, PairsWearDifferentColours) {
  const auto pairs = generateCrowd(cavalry(30, 6), nullptr, 24, "t");
  std::set<std::string> coats, jackets, hair, skins;
  for (const PairSpec& p : pairs) coats.insert(p.coat), jackets.insert(p.jacket), hair.insert(p.hair), skins.insert(p.skin);
  EXPECT_GE(coats.size(), 5u);
  EXPECT_GE(jackets.size(), 5u);
  EXPECT_GE(hair.size(), 3u);
  EXPECT_GE(skins.size(), 3u);
  const auto again = generateCrowd(cavalry(30, 6), nullptr, 24, "t");
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_EQ(pairs[i].coat, again[i].coat);
    EXPECT_EQ(pairs[i].jacket, again[i].jacket);
    EXPECT_EQ(pairs[i].horse().coat, findHorseCoat(pairs[i].coat)->coat);
    EXPECT_EQ(pairs[i].rider().coat, findNamedColor(riderJackets(), pairs[i].jacket)->color);
    EXPECT_EQ(pairs[i].rider().hair, findNamedColor(riderHair(), pairs[i].hair)->color);
  }
}

TEST(Crowd, BadSpecsAreOneLineErrors) {
  const auto gen = [](CrowdSpec s) { return errorOf([&] { generateCrowd(s, nullptr, 24, "s.json"); }); };
  CrowdSpec s = parade(4, 2);
  s.pairs = 0;
  EXPECT_EQ(gen(s), "s.json: crowd.pairs: expected a whole number from 1 to 200, got 0");
  s.pairs = 201;
  EXPECT_EQ(gen(s), "s.json: crowd.pairs: expected a whole number from 1 to 200, got 201");
  s = parade(4, 2);
  s.formation.files = 5;
  EXPECT_EQ(gen(s), "s.json: crowd.formation.files: expected a whole number from 1 to the pairs (4), got 5");
  s = parade(4, 2);
  s.withers_height_cm = {140, 170};
  EXPECT_EQ(gen(s), "s.json: crowd.withers_height_cm: expected a range [low, high] within 145 to 175 cm, got [140, 170]");
  s = parade(4, 2);
  s.rider_height_cm = {150, 195};
  EXPECT_EQ(gen(s), "s.json: crowd.rider_height_cm: expected a range [low, high] within 150 to 190 cm, got [150, 195]");
  s = parade(4, 2);
  s.rider_build = {1.1, 0.9};
  EXPECT_EQ(gen(s), "s.json: crowd.rider_build: expected a range [low, high] within 0.85 to 1.25, got [1.1, 0.9]");
  s = parade(4, 2);
  s.profile_mix = {{"thesis", 1}, {"western", 1}};
  EXPECT_EQ(gen(s), "s.json: crowd.profiles.western: expected one of thesis, english, novice");
  s.profile_mix = {{"thesis", 0}, {"novice", 0}};
  EXPECT_EQ(gen(s), "s.json: crowd.profiles: expected at least one profile with a weight > 0");
  s.profile_mix = {{"thesis", -1}};
  EXPECT_EQ(gen(s), "s.json: crowd.profiles.thesis: expected a weight from 0 to 1e+06, got -1");
  s = parade(4, 2);
  s.speed_variation = 0.5;
  EXPECT_EQ(gen(s), "s.json: crowd.speed_variation: expected a fraction from 0 to 0.1, got 0.5");
  s = parade(4, 2);
  s.start_offset_max_s = 3;
  EXPECT_EQ(gen(s), "s.json: crowd.start_offset_max_s: expected seconds from 0 to 2, got 3");
  s = parade(4, 2);
  s.lead_points = {{0, 0}, {40000, 0}};  // 133 s at 300 cm/s
  EXPECT_EQ(gen(s), "s.json: crowd.lead: speed: expected speeds that ride the whole path (40000 cm) within 120 s");
  s = parade(4, 2);
  s.lead_points = {{0, 0}};
  EXPECT_EQ(gen(s).rfind("s.json: crowd.lead: points", 0), 0u) << gen(s);
}

// Spacing closer than the pairs' bodies allow: the message asks for at least a body's width or length.
TEST(Crowd, SpacingTooCloseForTheHorsesIsRejected) {
  const auto needed = [](const std::string& message, const std::string& field) {
    std::smatch m;
    const std::regex re("s\\.json: crowd\\.formation\\." + field + ": expected at least ([0-9]+) cm \\([^)]*\\), got ([0-9]+)");
    EXPECT_TRUE(std::regex_match(message, m, re)) << message;
    return m.size() == 3 ? std::stod(m[1]) : 0.0;
  };
  CrowdSpec s = parade(4, 2);
  s.formation.file_spacing_cm = 80;
  // Two default-sized horses' barrels alone are 2 × 25 cm across, the riders' boots in the stirrups 2 × 31.
  EXPECT_GT(needed(errorOf([&] { generateCrowd(s, nullptr, 24, "s.json"); }), "file_spacing_cm"), 2 * 31.0);
  s = parade(4, 2);
  s.formation.rank_spacing_cm = 200;
  // A horse is 232 cm from its muzzle to its tail's root (140 to -92) before the tail hangs behind.
  EXPECT_GT(needed(errorOf([&] { generateCrowd(s, nullptr, 24, "s.json"); }), "rank_spacing_cm"), 232.0);
}

TEST(Crowd, AFormationWiderThanTheLeadsTurnIsRejected) {
  CrowdSpec s = parade(8, 8);
  s.lead_points = {{0, 0}, {1000, 0}, {1500, 500}, {1500, 1500}};  // a turn of about 5 m radius
  s.formation.file_spacing_cm = 400;
  EXPECT_EQ(errorOf([&] { generateCrowd(s, nullptr, 24, "s.json"); }).rfind("s.json: crowd.formation: expected a formation at most ", 0), 0u);
}

PairSpec rider(std::vector<glm::dvec2> points, double speed) {
  PairSpec p;
  p.path.points = std::move(points);
  p.path.speed = {{0, speed}};
  return p;
}

TEST(Crowd, ExplicitPairsAreChecked) {
  const auto check = [](const std::vector<PairSpec>& pairs) {
    return errorOf([&] { validatePairs(pairs, nullptr, 24, 0, "s.json", "riders"); });
  };
  PairSpec a = rider({{0, 0}, {2000, 0}}, 300), b = rider({{0, 500}, {2000, 500}}, 300);
  EXPECT_EQ(check({a, b}), "(no error)");
  b.withers_height_cm = 180;
  EXPECT_EQ(check({a, b}), "s.json: riders[1].withers_height_cm: expected 145 to 175 cm, got 180");
  b.withers_height_cm = 160;
  b.rider_height_cm = 140;
  EXPECT_EQ(check({a, b}), "s.json: riders[1].rider_height_cm: expected 150 to 190 cm, got 140");
  b.rider_height_cm = 170;
  b.rider_build = 2;
  EXPECT_EQ(check({a, b}), "s.json: riders[1].rider_build: expected 0.85 to 1.25, got 2");
  b.rider_build = 1;
  b.profile = "western";
  EXPECT_EQ(check({a, b}), "s.json: riders[1].profile: expected one of thesis, english, novice, got \"western\"");
  b.profile = "novice";
  b.coat = "purple";
  EXPECT_EQ(check({a, b}), "s.json: riders[1].coat: expected one of bay, chestnut, black, grey, dun, palomino, brown, "
                           "got \"purple\"");
  b.coat = "dun";
  b.hair = "green";
  EXPECT_EQ(check({a, b}), "s.json: riders[1].hair: expected one of brown, black, blonde, auburn, grey, got \"green\"");
  b.hair = "grey";
  b.clip_offset_s = -1;
  EXPECT_EQ(check({a, b}), "s.json: riders[1].start_offset_s: expected seconds from 0 to 2, got -1");
  EXPECT_EQ(check({}), "s.json: riders: expected 1 to 200 pairs, got 0");
  b.clip_offset_s = 0;
  b.path.points = {{0, 500}, {40000, 500}};  // 133 s at 300 cm/s
  EXPECT_EQ(check({a, b}), "s.json: riders[1].speed: expected a ride of at most 120 s, got 133.333 s");
}

// The pairs are checked and their clips made in parallel; the error is still the first bad pair's,
// whichever thread finds one first, and the clips come back in pair order, one a pair.
TEST(Crowd, TheFirstBadPairIsTheErrorAndTheClipsComeInOrder) {
  const auto check = [](const std::vector<PairSpec>& pairs) {
    return errorOf([&] { validatePairs(pairs, nullptr, 24, 0, "s.json", "riders"); });
  };
  std::vector<PairSpec> pairs;
  for (int i = 0; i < 12; ++i) pairs.push_back(rider({{0, 500.0 * i}, {2000 + 100.0 * i, 500.0 * i}}, 300));
  const PairClips clips = validatePairs(pairs, nullptr, 24, 0, "s.json", "riders");
  ASSERT_EQ(clips.size(), pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
    EXPECT_EQ(clips[i]->sample(1.0).travel_z_cm, makePairClip(pairs[i], nullptr, "t")->sample(1.0).travel_z_cm) << i;
  pairs[9].coat = "purple";
  pairs[4].path.points = {{0, 2000}};  // one point: its clip's own error
  pairs[7].rider_build = 2;
  for (int run = 0; run < 5; ++run)
    EXPECT_EQ(check(pairs), "s.json: riders[4]: points: expected at least two points [x, z] (cm), got 1");
}

TEST(Crowd, OverlappingExplicitPathsAreRejected) {
  const auto check = [](const std::vector<PairSpec>& pairs) {
    return errorOf([&] { validatePairs(pairs, nullptr, 24, 0, "s.json", "riders"); });
  };
  // Side by side, 60 cm apart: their horses overlap from the first frame.
  const PairSpec a = rider({{0, 0}, {2000, 0}}, 300), c = rider({{0, 600}, {2000, 600}}, 300);
  EXPECT_EQ(check({a, c, rider({{0, 60}, {2000, 60}}, 300)}),
            "s.json: riders: riders[0] and riders[2] overlap at frame 1 (0 s): expected paths that keep every two horses "
            "apart at every frame");
  // One behind the other, the second faster: it runs into the first. They start 1500 cm apart and close
  // at 300 cm/s, so they meet after 5 s less the time to close the two bodies' reach (at most 1000 cm,
  // over 3.3 s), and before the muzzle reaches the first horse's middle (1500 - 180 cm: 4.4 s).
  const PairSpec lead = rider({{1500, 600}, {6000, 600}}, 300), chaser = rider({{0, 600}, {6000, 600}}, 600);
  const std::string message = check({a, lead, chaser});
  std::smatch m;
  ASSERT_TRUE(std::regex_match(message, m, std::regex("s\\.json: riders: riders\\[1\\] and riders\\[2\\] overlap at frame ([0-9]+) \\(([0-9.]+) s\\): .*")))
      << message;
  const double t = std::stod(m[2]);
  // A generated crowd's pairs are named by number, the formation as what to change.
  EXPECT_EQ(errorOf([&] { validatePairs({a, rider({{0, 60}, {2000, 60}}, 300)}, nullptr, 24, 0, "s.json", "crowd"); }),
            "s.json: crowd.formation: pairs 0 and 1 overlap at frame 1 (0 s): expected a formation that keeps every two "
            "horses apart at every frame (wider spacing, less jitter or speed variation)");
  EXPECT_GT(t, 5.0 - 1000.0 / 300.0);
  EXPECT_LT(t, (1500.0 - 180.0) / 300.0);
  EXPECT_EQ(std::stoi(m[1]), static_cast<int>(std::lround(t * 24.0)) + 1);
}

}  // namespace
}  // namespace stirrup::rig

namespace stirrup::rig {
namespace {

// A pair's path keeps its file's distance from the lead all along, through the bend: the curve through
// its sampled points stays within a millimetre of the true offset curve (kPairPathStepCm's claim).
TEST(Crowd, APairsPathIsTheLeadOffsetSideways) {
  CrowdSpec s = cavalry(6, 6);
  s.formation.jitter_cm = 0.0;
  s.start_offset_max_s = 0.0;
  s.speed_variation = 0.0;
  const auto pairs = generateCrowd(s, nullptr, 24, "t");
  const GroundPath lead(s.lead_points, "t");
  // The lead, densely, continued straight beyond its ends as the pairs' paths are.
  std::vector<glm::dvec2> dense;
  for (double d = -2000.0; d <= lead.length() + 2000.0; d += 2.0) {
    const GroundPath::Sample a = lead.at(std::clamp(d, 0.0, lead.length()));
    dense.push_back(a.position + a.tangent * (d - std::clamp(d, 0.0, lead.length())));
  }
  double worst = 0.0;
  for (int i = 0; i < 6; ++i) {
    const double across = std::abs((i - 2.5) * s.formation.file_spacing_cm);
    const GroundPath own(pairs[std::size_t(i)].path.points, "t");
    for (double d = 0.0; d <= own.length(); d += 37.0) {
      const glm::dvec2 q = own.at(d).position;
      double nearest = 1e300;
      for (const glm::dvec2& p : dense) nearest = std::min(nearest, glm::length(q - p));
      worst = std::max(worst, std::abs(nearest - across));
    }
  }
  EXPECT_LT(worst, 0.1);
}

}  // namespace
}  // namespace stirrup::rig

namespace stirrup::rig {
namespace {

// Over rolling ground every pair's horse stands on the hills under its own path.
TEST(Crowd, PairsRideOverTheTerrain) {
  HillsParams h;
  h.seed = 5;
  h.amplitude_cm = 250;
  h.wavelength_cm = 1500;
  h.octaves = 2;
  const auto hills = std::make_shared<const Terrain>(Terrain::hills(h, "t"));
  const CrowdSpec s = parade(6, 3);
  const auto pairs = generateCrowd(s, hills, 24, "t");
  for (const PairSpec& p : pairs) {
    const auto clip = makePairClip(p, hills, "t");
    const HorseFrame f = clip->sample(1.0 + p.clip_offset_s);
    // The travel frame stands on the ground between the hooves: within a few cm of the hill under it.
    EXPECT_NEAR(f.ground_y_cm, hills->height(f.travel_cm, f.travel_z_cm), 5.0);
  }
  // And the hills are not flat where they ride.
  double lo = 1e9, hi = -1e9;
  for (const PairSpec& p : pairs) {
    const double y = makePairClip(p, hills, "t")->sample(1.0 + p.clip_offset_s).ground_y_cm;
    lo = std::min(lo, y), hi = std::max(hi, y);
  }
  EXPECT_GT(hi - lo, 10.0);
}

}  // namespace
}  // namespace stirrup::rig
