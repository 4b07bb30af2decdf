// rig/frame_check.h: each rule finds a fault planted in a real posed frame of the default pair, by the
// amount planted, and the unchanged frame has none. The faults are made by moving joints of the posed
// frame (a hand 8 cm off its rein, the rider 20 cm down into the horse, ...), so the expected values are
// the distances moved, not the code's own output.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "rig/bake.h"
#include "rig/frame_check.h"
#include "rig/horse_leg.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "tests/rig/default_characters.h"

namespace stirrup::rig {
namespace {

const PairCheck::GroundHeight kFlat = [](double, double) { return 0.0; };

struct Posed {
  BakedFrame baked;
  MountedPose pose;
};

// The default pair at a frame of the default trot (24 fps).
Posed trotFrame(int frame) {
  static const RigProfile profile = RigProfile::thesis();
  static const std::unique_ptr<Clip> clip = scene::makeClip(scene::ClipSpec{});
  Posed p;
  p.baked = bakeFrame(*clip, profile, frame, (frame - 1) / 24.0);
  p.pose = poseMounted(test::defaultHorse(), test::defaultRider(), p.baked.horse, p.baked.rider, profile);
  return p;
}

// Warnings and failures (notes, hooves missing a point in the air, are not faults).
std::vector<CheckFinding> findingsOf(const PairCheck& check, std::vector<FrameMeasures> frames) {
  std::vector<CheckFinding> out;
  for (CheckFinding& f : check.judge(frames, 0))
    if (f.severity != CheckSeverity::Note) out.push_back(std::move(f));
  return out;
}

// The first frame of the trot (from 2) whose hooves down were down the frame before too, two at least:
// a diagonal pair in stance.
int stanceFrame() {
  for (int f = 2; f < 48; ++f) {
    const Posed a = trotFrame(f - 1), b = trotFrame(f);
    int both = 0;
    for (std::size_t leg = 0; leg < 4; ++leg) both += a.pose.reach.planted[leg] && b.pose.reach.planted[leg];
    if (both >= 2) return f;
  }
  return -1;
}

const CheckFinding* find(const std::vector<CheckFinding>& f, const std::string& rule, const std::string& where = "") {
  for (const CheckFinding& x : f)
    if (x.rule == rule && (where.empty() || x.where == where)) return &x;
  return nullptr;
}

void translate(std::vector<glm::mat4>& world, glm::vec3 by) {
  for (glm::mat4& m : world) m[3] += glm::vec4(by, 0.0f);
}

class FrameCheck : public ::testing::Test {
 protected:
  const Character& horse = test::defaultHorse();
  const Character& rider = test::defaultRider();
  const PairCheck check{horse, rider, RigProfile::thesis().balance};
  FrameMeasures measure(int frame, const Posed& p) const { return check.measure(frame, (frame - 1) / 24.0, p.baked.horse, p.pose, kFlat); }
};

// Frames 10 and 11 of the trot as posed: no fault, and every rule measurable on the default pair.
TEST_F(FrameCheck, TheDefaultTrotHasNoFinding) {
  EXPECT_TRUE(check.unmeasured().empty());
  const std::vector<CheckFinding> f = findingsOf(check, {measure(10, trotFrame(10)), measure(11, trotFrame(11))});
  for (const CheckFinding& x : f) ADD_FAILURE() << x.rule << " " << x.where << ": " << x.text;
}

TEST_F(FrameCheck, AHandOffItsReinIsFoundByHowFar) {
  Posed p = trotFrame(10);
  const FrameMeasures before = measure(10, p);
  ASSERT_LT(before.hand_off_cm[0], 0.01f);  // posing puts the rein's end in her hand
  p.pose.rider[std::size_t(rider.role("lHand"))][3] += glm::vec4(0.0f, 8.0f, 0.0f, 0.0f);  // 8 cm up
  const std::vector<CheckFinding> f = findingsOf(check, {measure(10, p)});
  const CheckFinding* x = find(f, "hand-off-rein", "left");
  ASSERT_NE(x, nullptr);
  EXPECT_NEAR(x->value, 8.0, 0.02);
  EXPECT_EQ(x->severity, CheckSeverity::Warning);  // 3 cm warns, 10 cm fails
  EXPECT_EQ(find(f, "hand-off-rein", "right"), nullptr);
}

TEST_F(FrameCheck, AFootOutOfItsStirrupIsFoundByHowFar) {
  Posed p = trotFrame(10);
  const float before = measure(10, p).foot_off_cm[1];
  ASSERT_LT(before, 1.0f);
  p.pose.rider[std::size_t(rider.role("rBall"))][3] += glm::vec4(7.0f, 0.0f, 0.0f, 0.0f);  // 7 cm ahead of the tread
  const std::vector<CheckFinding> f = findingsOf(check, {measure(10, p)});
  const CheckFinding* x = find(f, "foot-off-stirrup", "right");
  ASSERT_NE(x, nullptr);
  EXPECT_NEAR(x->value, 7.0, before + 0.01);
  EXPECT_EQ(x->severity, CheckSeverity::Failure);  // past half the tread (6 cm)
}

// The whole rider 20 cm lower: her seat and legs go through the saddle into the barrel.
TEST_F(FrameCheck, ARiderSunkIntoTheHorseIsFound) {
  Posed p = trotFrame(10);
  translate(p.pose.rider, {0.0f, -20.0f, 0.0f});
  const std::vector<CheckFinding> f = findingsOf(check, {measure(10, p)});
  const CheckFinding* x = find(f, "rider-in-horse");
  ASSERT_NE(x, nullptr);
  EXPECT_EQ(x->severity, CheckSeverity::Failure);
  EXPECT_GE(x->value, 10.0);
  EXPECT_LE(x->value, 20.0 + 4.0);  // no deeper than the 20 cm moved and the 3.9 cm the pair already presses
}

// The whole horse 4 cm lower: every hoof down on the ground goes 4 cm into it (less what it stood above).
TEST_F(FrameCheck, HoovesIntoTheGroundAreFoundByHowDeep) {
  const int frame = stanceFrame();
  ASSERT_GT(frame, 0);
  Posed p = trotFrame(frame);
  const FrameMeasures before = measure(frame, p);
  translate(p.pose.horse, {0.0f, -4.0f, 0.0f});
  translate(p.pose.rider, {0.0f, -4.0f, 0.0f});
  const std::vector<CheckFinding> f = findingsOf(check, {measure(frame, p)});
  int down = 0;
  for (int leg = 0; leg < 4; ++leg) {
    if (!before.down[std::size_t(leg)]) continue;
    ++down;
    const char* names[] = {"lf", "rf", "lb", "rb"};
    const CheckFinding* x = find(f, "hoof-in-ground", names[leg]);
    ASSERT_NE(x, nullptr) << names[leg];
    EXPECT_NEAR(x->value, 4.0, 0.3) << names[leg];  // a planted sole stands on the ground within 0.3 cm
    EXPECT_EQ(x->severity, CheckSeverity::Failure) << names[leg];
  }
  EXPECT_GE(down, 2);  // a diagonal pair
}

// The horse 2 cm further along at the second frame than its clip put it: its down hooves skate 2 cm.
TEST_F(FrameCheck, AHoofSlidingWhileDownIsFoundByHowFar) {
  const int frame = stanceFrame();
  ASSERT_GT(frame, 0);
  const Posed a = trotFrame(frame - 1);
  Posed b = trotFrame(frame);
  const FrameMeasures clean = measure(frame, b);
  translate(b.pose.horse, {2.0f, 0.0f, 0.0f});
  const std::vector<CheckFinding> f = findingsOf(check, {measure(frame - 1, a), measure(frame, b)});
  int found = 0;
  for (const CheckFinding& x : f) {
    if (x.rule != "hoof-slide") continue;
    ++found;
    EXPECT_EQ(x.frame, frame);
    EXPECT_NEAR(x.value, 2.0, 0.35) << x.where;  // within what the unshifted sole moves a frame (< 0.35 cm)
    EXPECT_EQ(x.severity, CheckSeverity::Warning);
  }
  int both_down = 0;
  for (std::size_t leg = 0; leg < 4; ++leg) both_down += measure(frame - 1, a).down[leg] && clean.down[leg];
  EXPECT_EQ(found, both_down);
  EXPECT_GE(found, 2);
}

// A hoof sliding on purpose (the sliding stop's hind hooves) is not a fault.
TEST_F(FrameCheck, AHoofTheClipSlidesOnPurposeIsNotAFault) {
  const int frame = stanceFrame();
  ASSERT_GT(frame, 0);
  const Posed a = trotFrame(frame - 1);
  Posed b = trotFrame(frame);
  translate(b.pose.horse, {2.0f, 0.0f, 0.0f});
  ASSERT_NE(find(findingsOf(check, {measure(frame - 1, a), measure(frame, b)}), "hoof-slide"), nullptr);
  b.baked.horse.hoof_sliding = {true, true, true, true};
  EXPECT_EQ(find(findingsOf(check, {measure(frame - 1, a), measure(frame, b)}), "hoof-slide"), nullptr);
}

// The rider turned 60 degrees forward about her pelvis: her trunk leans past the thesis band's 35.
TEST_F(FrameCheck, ATrunkOutsideTheBalanceBandIsFound) {
  Posed p = trotFrame(10);
  const double lean = measure(10, p).trunk_lean_deg;
  const glm::vec3 pelvis(p.pose.rider[std::size_t(rider.role("pelvis"))][3]);
  const glm::vec3 heading = glm::normalize(glm::vec3(p.pose.horse[std::size_t(horse.role("saddle"))][0]) * glm::vec3(1, 0, 1));
  const glm::vec3 axis = glm::normalize(glm::cross(glm::vec3(0, 1, 0), heading));  // turning about it tips up toward heading
  const glm::mat4 turn = glm::translate(glm::mat4(1.0f), pelvis) * glm::rotate(glm::mat4(1.0f), glm::radians(60.0f), axis) *
                         glm::translate(glm::mat4(1.0f), -pelvis);
  for (glm::mat4& m : p.pose.rider) m = turn * m;
  const FrameMeasures m = measure(10, p);
  EXPECT_NEAR(m.trunk_lean_deg, lean + 60.0, 0.5);
  const CheckFinding* x = find(findingsOf(check, {m}), "trunk-balance", "forward");
  ASSERT_NE(x, nullptr);
  EXPECT_NEAR(x->value, lean + 60.0 - 35.0, 0.5);
  EXPECT_EQ(x->severity, CheckSeverity::Failure);
}

// A planted hind hoof 150 cm behind its place: the leg stays at full reach (no bone stretches:
// PoseHorse.AHoofBeyondItsLegsReachIsFlaggedAndNoBoneStretches) and check fails the frame.
TEST_F(FrameCheck, APlantedHoofBeyondReachIsAnOverReachFailure) {
  const int frame = stanceFrame();
  ASSERT_GT(frame, 0);
  Posed p = trotFrame(frame);
  int planted = -1;
  for (int leg = 2; leg < 4 && planted < 0; ++leg)
    if (p.pose.reach.planted[std::size_t(leg)]) planted = leg;
  ASSERT_GE(planted, 0);
  const HorseChannel tx = planted == 2 ? HorseChannel::lbHoofTx : HorseChannel::rbHoofTx;
  p.baked.horse.controls[tx] -= 150.0;
  const RigProfile profile = RigProfile::thesis();
  p.pose = poseMounted(horse, rider, p.baked.horse, p.baked.rider, profile);
  const std::vector<CheckFinding> f = findingsOf(check, {measure(frame, p)});
  const CheckFinding* x = find(f, "over-reach", planted == 2 ? "lb" : "rb");
  ASSERT_NE(x, nullptr);
  EXPECT_EQ(x->severity, CheckSeverity::Failure);
  EXPECT_GE(x->value, 5.0);  // the leg swings back from its hip, but 150 cm is far past any hind's reach
}

// The one contact test (hoofLiftCm, hoofDown) on a hoof whose joint stands 5 cm above its sole (a user's
// horse: the default horse's is on it): at its rest height it is down; rolled 20 degrees over its toe
// edge (6 cm ahead on the sole, the edge the leg solve rolls it over) it is still down, its joint 1.75 cm up;
// raised 1 cm it is not; over a ground 10 cm lower it is not; 2 cm into the ground it is.
TEST(HoofContact, AHoofRollingOverItsToeIsDownAndOneLiftedIsNot) {
  const float rest = 5.0f;  // the hoof joint's rest height above the ground
  const glm::mat4 at_rest = glm::translate(glm::mat4(1.0f), {30.0f, rest, 10.0f});
  EXPECT_NEAR(hoofLiftCm(at_rest, rest, kFlat), 0.0, 1e-6);
  EXPECT_TRUE(hoofDown(hoofLiftCm(at_rest, rest, kFlat)));
  const HorseLegParams leg;
  const glm::vec3 toe(30.0f + leg.toe_cm, 0.0f, 10.0f);
  const glm::mat4 rolled = glm::translate(glm::mat4(1.0f), toe) * glm::rotate(glm::mat4(1.0f), glm::radians(-20.0f), {0, 0, 1}) *
                           glm::translate(glm::mat4(1.0f), -toe) * at_rest;
  EXPECT_GT(rolled[3].y - rest, 1.5f);  // the joint lifted by the roll (6 sin 20 + 5 (cos 20 - 1) = 1.75 cm)
  EXPECT_NEAR(hoofLiftCm(rolled, rest, kFlat), 0.0, 1e-4);
  EXPECT_TRUE(hoofDown(hoofLiftCm(rolled, rest, kFlat)));
  const glm::mat4 raised = glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}) * at_rest;
  EXPECT_NEAR(hoofLiftCm(raised, rest, kFlat), 1.0, 1e-5);
  EXPECT_FALSE(hoofDown(hoofLiftCm(raised, rest, kFlat)));
  EXPECT_NEAR(hoofLiftCm(at_rest, rest, [](double, double) { return -10.0; }), 10.0, 1e-5);
  EXPECT_NEAR(hoofLiftCm(glm::translate(glm::mat4(1.0f), {0.0f, -2.0f, 0.0f}) * at_rest, rest, kFlat), -2.0, 1e-5);
}

// Over the default trot's first two strides: every hoof the clip plants is down by the contact test, the
// ones the leg has rolled over the toe or heel at the ends of a stance (joint raised past the band)
// among them; a hoof the clip lifts a centimetre or more never is.
TEST_F(FrameCheck, EveryHoofTheTrotPlantsIsDownRollingOrNot) {
  int planted = 0, rolled = 0;
  for (int f = 1; f <= 48; ++f) {
    const Posed p = trotFrame(f);
    const FrameMeasures m = measure(f, p);
    static constexpr std::array<HorseChannel, 4> kLift = {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy, HorseChannel::lbHoofTy,
                                                          HorseChannel::rbHoofTy};
    static constexpr std::array<const char*, 4> kHooves = {"lfHoof", "rfHoof", "lbHoof", "rbHoof"};
    for (std::size_t leg = 0; leg < 4; ++leg) {
      const double ty = p.baked.horse.controls[kLift[leg]];
      const int hoof = horse.role(kHooves[leg]);
      const double raised = p.pose.horse[std::size_t(hoof)][3].y - horse.skeleton.restPosition(hoof).y;
      if (ty >= 1.0) {
        EXPECT_FALSE(m.down[leg]) << "frame " << f << " leg " << leg << " lifted " << ty;
      }
      if (ty != 0.0) continue;
      ++planted;
      rolled += raised > kHoofContactCm;
      EXPECT_TRUE(m.down[leg]) << "frame " << f << " leg " << leg << " planted, joint raised " << raised << ", lift " << m.lift_cm[leg];
    }
  }
  EXPECT_GT(rolled, 0);
  std::printf("default trot, 48 frames: %d planted hoof-frames all down, %d of them rolled over an edge\n", planted, rolled);
}

// soleSlide: the least any point of the sole moves. A square sole 10 cm wide rolled about its front
// edge does not slide; moved 2 cm it slides 2; rolled about a line between its vertices (the middle of
// two edges), it does not slide either.
TEST(SoleSlide, RollingIsNotSlidingAndSkatingIs) {
  const std::vector<std::pair<int, glm::vec3>> sole = {{0, {0, 0, 0}}, {1, {10, 0, 0}}, {2, {0, 0, 10}}, {3, {10, 0, 10}}};
  const auto moved = [&](const glm::mat4& m) {
    std::vector<std::pair<int, glm::vec3>> out;
    for (const auto& [v, p] : sole) out.emplace_back(v, glm::vec3(m * glm::vec4(p, 1.0f)));
    return out;
  };
  // Rolled 20 degrees about the front edge (x = 10, along z): the front vertices stay.
  const glm::mat4 roll_front = glm::translate(glm::mat4(1.0f), {10, 0, 0}) * glm::rotate(glm::mat4(1.0f), glm::radians(20.0f), {0, 0, 1}) *
                               glm::translate(glm::mat4(1.0f), {-10, 0, 0});
  EXPECT_NEAR(soleSlide(sole, moved(roll_front)), 0.0, 1e-4);
  EXPECT_NEAR(soleSlide(sole, moved(glm::translate(glm::mat4(1.0f), {2, 0, 0}))), 2.0, 1e-5);
  EXPECT_NEAR(soleSlide(sole, moved(glm::translate(glm::mat4(1.0f), {0, 5, 1.5f}))), 1.5, 1e-5);  // lifting is not sliding
  // Turned 30 degrees about the vertical through x = 5, z = 0 (the middle of the edge from vertex 0 to 1).
  const glm::mat4 pivot_mid = glm::translate(glm::mat4(1.0f), {5, 0, 0}) * glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), {0, 1, 0}) *
                              glm::translate(glm::mat4(1.0f), {-5, 0, 0});
  EXPECT_NEAR(soleSlide(sole, moved(pivot_mid)), 0.0, 1e-4);
  EXPECT_DOUBLE_EQ(soleSlide({}, sole), 0.0);  // nothing down before: nothing slid
}

}  // namespace
}  // namespace stirrup::rig
