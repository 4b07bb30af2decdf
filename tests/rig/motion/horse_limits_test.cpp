#include "rig/motion/horse_limits.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/motion/terrain.h"
#include "rig/motion/terrain_mesh.h"

namespace stirrup::rig {
namespace {

constexpr double kPi = std::numbers::pi;

PathClipParams straight(double length_cm, std::vector<SpeedProfile::Key> speed) {
  PathClipParams p;
  p.points = {{0.0, 0.0}, {length_cm, 0.0}};
  p.speed = std::move(speed);
  return p;
}

// A plane rising `along_deg` toward +x and `across_deg` toward +z, as a two-triangle mesh terrain
// reaching well past the paths below (heights the test knows exactly: the plane's).
std::shared_ptr<const Terrain> plane(double along_deg, double across_deg) {
  const double gx = std::tan(along_deg * kPi / 180.0), gz = std::tan(across_deg * kPi / 180.0);
  std::vector<glm::dvec3> v;
  for (const double z : {-2000.0, 2000.0})
    for (const double x : {-2000.0, 6000.0}) v.push_back({x, gx * x + gz * z, z});
  const std::vector<std::uint32_t> idx = {0, 1, 3, 0, 3, 2};
  return std::make_shared<const Terrain>(Terrain::mesh(std::make_shared<const TerrainMesh>(v, idx, "plane")));
}

std::string errorOf(const PathClipParams& p, const std::shared_ptr<const Terrain>& terrain = nullptr) {
  return PathLimitCheck(p, terrain.get(), "shot.json", "clip").error();
}

// A circle of radius r (cm) through n points, starting at the origin heading +x, turning right.
std::vector<glm::dvec2> circle(double r, int n, double turns) {
  std::vector<glm::dvec2> pts;
  for (int i = 0; i <= int(n * turns); ++i) {
    const double a = 2.0 * kPi * i / n;
    pts.push_back({r * std::sin(a), r * (1.0 - std::cos(a))});
  }
  return pts;
}

TEST(HorseLimits, TheAccelerationPowerReachesFifteenMetresASecondInFiveSeconds) {
  // Hand-worked: a0 = 0.6 × 981 = 588.6 cm/s²; P solves P / 2a0² + 1500² / 2P = 5 s, P² − 3 464 356 P
  // + 779 507 010 000 (a0² × 1500²) = 0, smaller root 241 888 cm²/s³ (24.19 W/kg).
  const HorseLimits l;
  EXPECT_NEAR(l.accelPowerCm2S3(), 241888.4, 1.0);
  const double P = l.accelPowerCm2S3(), a0 = 588.6;
  EXPECT_NEAR(P / (2 * a0 * a0) + 1500.0 * 1500.0 / (2 * P), 5.0, 1e-9);
}

TEST(HorseLimits, ASpeedBeyondTheRecordIsRefused) {
  EXPECT_EQ(errorOf(straight(5000, {{0, 2500}})),
            "shot.json: clip.speed: segment 0 from 0.00 s: a speed of 2500 cm/s, beyond the 1966 cm/s no horse has been "
            "timed above (the record, 70.76 km/h)");
  EXPECT_EQ(errorOf(straight(5000, {{0, 1900}})), "");
}

TEST(HorseLimits, SpeedingUpHarderThanAHorseIsRefused) {
  // 100 to 300 cm/s in 0.25 s: 800 cm/s² (two keys: the profile is linear), beyond 0.6 g = 588.6 cm/s²
  // (the power limit, 241 888 / 300 = 806 cm/s², is looser at these speeds).
  EXPECT_EQ(errorOf(straight(3000, {{0, 100}, {0.25, 300}})),
            "shot.json: clip.speed: segment 0 from 0.00 s: speeding up at 800 cm/s² at 100 cm/s, beyond the 589 cm/s² a "
            "horse reaches at that speed (Williams et al. 2009)");
  // At speed the power limit binds: 1000 to 1200 cm/s in 1 s is 200 cm/s², inside 241 888 / v at every
  // speed up to 1209 cm/s; 1000 to 1400 cm/s in 1 s is 400 cm/s², beyond 241 888 / 1000 = 242 at once.
  EXPECT_EQ(errorOf(straight(5000, {{0, 1000}, {1, 1200}})), "");
  const std::string fast = errorOf(straight(5000, {{0, 1000}, {1, 1400}}));
  EXPECT_EQ(fast.substr(0, 60), "shot.json: clip.speed: segment 0 from 0.00 s: speeding up at");
}

TEST(HorseLimits, SlowingHarderThanAHorseIsRefused) {
  // 1000 to 100 cm/s in 1 s: 900 cm/s², beyond 0.9 g = 882.9 cm/s².
  EXPECT_EQ(errorOf(straight(3000, {{0, 1000}, {1, 100}})),
            "shot.json: clip.speed: segment 0 from 0.00 s: slowing at 900 cm/s², beyond the 883 cm/s² a horse brakes at "
            "(Williams et al. 2009)");
  EXPECT_EQ(errorOf(straight(3000, {{0, 1000}, {2, 100}})), "");  // 450 cm/s²
}

TEST(HorseLimits, ATurnTighterThanTheHoovesGripIsRefused) {
  // Three quarters of a 10 m circle at 1000 cm/s: round it the turn asks 1000²/1000 = 1000 cm/s², beyond
  // 0.8 × 981 = 784.8. (The spline bends a little tighter where it ends: its end tangent is the
  // reflected neighbour's; the error names the worst place.)
  PathClipParams p;
  p.points = circle(1000.0, 48, 0.75);
  p.speed = {{0, 1000}};
  const PathLimitCheck c(p, nullptr, "shot.json", "clip");
  std::smatch m;
  const std::string e = c.error();
  ASSERT_TRUE(std::regex_match(e, m, std::regex(
      "shot\\.json: clip\\.points: segment [0-9]+ from [0-9.]+ s: a turn of ([0-9]+) cm radius at 1000 cm/s asks "
      "([0-9]+) cm/s² \\(v²/r\\) of the hooves' grip, beyond 785 cm/s² \\(friction 0\\.8 × g; Tan and Wilson 2011\\)")))
      << e;
  EXPECT_GE(std::stod(m[2]), 1000.0 * 0.98);
  // Halfway round (the path is 3/4 × 2π × 1000 = 4712 cm long, ridden at 1000 cm/s) the spline through
  // 48 points of the circle is within 2% of its radius.
  const std::vector<LimitBreach> mid = c.during(2.356 - 0.02, 2.356 + 0.02);
  ASSERT_EQ(mid.size(), 1u);
  EXPECT_EQ(mid[0].limit, HorseLimit::Turn);
  EXPECT_NEAR(mid[0].value, 1000.0, 20.0);
  EXPECT_NEAR(mid[0].bound, 784.8, 1e-9);
  // At 700 cm/s, 490 cm/s² round it and a little more at the end, inside the grip.
  p.speed = {{0, 700}};
  EXPECT_EQ(errorOf(p), "");
}

TEST(HorseLimits, AClimbSteeperThanARiddenHorseClimbsIsRefused) {
  // A plane rising 40° along the path: grade 40° beyond 35°; its footing (40°) is inside 45°.
  EXPECT_EQ(errorOf(straight(3000, {{0, 180}}), plane(40, 0)),
            "shot.json: terrain: under clip.points, segment 0 from 0.00 s: a climb of 40.0° under the horse, beyond the "
            "35.0° a ridden horse climbs");
  EXPECT_EQ(errorOf(straight(3000, {{0, 180}}), plane(30, 0)), "");
}

TEST(HorseLimits, ADescentSteeperThanARiddenHorseDescendsIsRefused) {
  // The same plane ridden the other way (−x): a 40° descent is inside 45°; a 50° one is not (its
  // footing breaks too, from the same sample: the descent is named first).
  PathClipParams p = straight(3000, {{0, 180}});
  p.points = {{3000, 0}, {0, 0}};
  EXPECT_EQ(errorOf(p, plane(40, 0)), "");
  EXPECT_EQ(errorOf(p, plane(50, 0)),
            "shot.json: terrain: under clip.points, segment 0 from 0.00 s: a descent of 50.0° under the horse, beyond the "
            "45.0° a ridden horse descends");
}

TEST(HorseLimits, CanteringOnASteepGradeIsRefused) {
  // 25° climbs: walked, inside every limit; cantered (600 cm/s, above the trot-canter change at 500),
  // beyond the 20° a horse is cantered on.
  EXPECT_EQ(errorOf(straight(3000, {{0, 180}}), plane(25, 0)), "");
  EXPECT_EQ(errorOf(straight(3000, {{0, 600}}), plane(25, 0)),
            "shot.json: terrain: under clip.points, segment 0 from 0.00 s: a grade of 25.0° at the canter or gallop (600 "
            "cm/s), beyond the 20.0° a horse is cantered on");
}

TEST(HorseLimits, GroundTooSteepForAHoofIsRefused) {
  // A sidehill of 50° across the path: no grade along it, but every hoof stands on 50° ground.
  EXPECT_EQ(errorOf(straight(3000, {{0, 180}}), plane(0, 50)),
            "shot.json: terrain: under clip.points, segment 0 from 0.00 s: ground sloping 50.0° under a hoof (across its "
            "12 cm footprint), beyond the 45.0° a hoof stands on");
  EXPECT_EQ(errorOf(straight(3000, {{0, 180}}), plane(0, 40)), "");
}

// Each gait's top speed (issue 49): at its limit a gait passes, a centimetre a second beyond it is
// refused with the limit and where it comes from; a pace or an amble is no gait of the four.
TEST(HorseLimits, EachGaitHasATopSpeed) {
  for (const auto& [gait, top] : {std::pair{"walk", 250.0}, {"trot", 1485.0}, {"canter", 1000.0}, {"gallop", 1966.0}}) {
    EXPECT_FALSE(gaitSpeedBreach({"speed_cm_s", gait, top})) << gait;
    const std::optional<GaitSpeedBreach> b = gaitSpeedBreach({"speed_cm_s", gait, top + 1.0});
    ASSERT_TRUE(b) << gait;
    EXPECT_EQ(b->bound_cm_s, top) << gait;
  }
  EXPECT_FALSE(gaitSpeedBreach({"speed_cm_s", "pace", 5000}));
  EXPECT_EQ(gaitSpeedBreach({"speed_cm_s", "walk", 900})->text(),
            "900 cm/s is faster than a horse walks (at most 250 cm/s: horses change to the trot at 160-230 cm/s, Froude 0.35, "
            "Griffin et al. 2004; a walk held past that, an estimate)");
  EXPECT_EQ(gaitSpeedBreach({"speed_cm_s", "trot", 1600})->text(),
            "1600 cm/s is faster than a horse trots (at most 1485 cm/s: the fastest trotted mile, 1:48.4, Homicide Hunter 2018)");
  EXPECT_EQ(gaitSpeedBreach({"approach_speed_cm_s", "canter", 1200})->text("; then this"),
            "1200 cm/s is faster than a horse canters (at most 1000 cm/s: estimated from horses changing to the gallop at "
            "700-800 cm/s and ridden canters of 800-1000; then this)");
  EXPECT_EQ(gaitSpeedBreach({"entry_speed_cm_s", "gallop", 2000})->text(),
            "2000 cm/s is faster than a horse gallops (at most 1966 cm/s: the fastest recorded horse, 70.76 km/h, Winning Brew 2008)");
  // The gallop's is the record a path's speed is held to: one figure.
  HorseLimits slower;
  slower.top_speed_cm_s = 1500;
  EXPECT_TRUE(gaitSpeedBreach({"speed_cm_s", "gallop", 1600}, slower));
}

TEST(HorseLimits, TheIssuesImpossibleShotsAreRefused) {
  // "A path of 20 cm hairpins at 1500 cm/s".
  PathClipParams hairpins;
  hairpins.points = {{0, 0}, {300, 0}, {300, 20}, {0, 20}, {0, 40}, {300, 40}, {300, 60}, {0, 60}};
  hairpins.speed = {{0, 1500}};
  const PathLimitCheck turns(hairpins, nullptr, "shot.json", "clip");
  ASSERT_FALSE(turns.breaches().empty());
  double worst = 0;
  for (const LimitBreach& b : turns.breaches()) {
    EXPECT_EQ(b.limit, HorseLimit::Turn);
    worst = std::max(worst, b.value);
  }
  // A 180° hairpin within the horse's 121 cm: at least 1500² π / 121 = 58 400 cm/s².
  EXPECT_GT(worst, 58000.0);
  // The error names the worst: a hairpin, not the spline's gentle bend at the start.
  EXPECT_TRUE(std::regex_search(turns.error(), std::regex("^shot\\.json: clip\\.points: segment [0-9] from [0-9.]+ s: a turn of "
                                                           "[0-9]{2} cm radius at 1500 cm/s asks [0-9]{5,} cm/s²")))
      << turns.error();

  // "Hills of 5000 cm amplitude at 100 cm wavelength".
  HillsParams h;
  h.amplitude_cm = 5000;
  h.wavelength_cm = 100;
  h.octaves = 1;
  const Terrain spikes = Terrain::hills(h, "shot.json");
  const PathLimitCheck ground(straight(3000, {{0, 180}}), &spikes, "shot.json", "clip");
  bool footing = false, grade = false;
  for (const LimitBreach& b : ground.breaches()) {
    footing |= b.limit == HorseLimit::Footing;
    grade |= b.limit == HorseLimit::Climb || b.limit == HorseLimit::Descent;
  }
  EXPECT_TRUE(footing);
  EXPECT_TRUE(grade);
  EXPECT_EQ(ground.error().substr(0, 47), "shot.json: terrain: under clip.points, segment ") << ground.error();
}

TEST(HorseLimits, AFramesWarningNamesTheLimitsBrokenWithinIt) {
  // 800 cm/s² from 100 to 300 cm/s over the first 0.25 s: frames there break the acceleration limit,
  // frames after it none.
  const PathLimitCheck c(straight(3000, {{0, 100}, {0.25, 300}}), nullptr, "shot.json", "clip");
  const std::vector<LimitBreach> early = c.during(0.1 - 1.0 / 48, 0.1 + 1.0 / 48);
  ASSERT_EQ(early.size(), 1u);
  EXPECT_EQ(early[0].limit, HorseLimit::Acceleration);
  EXPECT_NEAR(early[0].value, 800.0, 0.5);
  EXPECT_NEAR(early[0].bound, 588.6, 0.01);
  EXPECT_TRUE(c.during(1.0 - 1.0 / 48, 1.0 + 1.0 / 48).empty());
}

}  // namespace
}  // namespace stirrup::rig
