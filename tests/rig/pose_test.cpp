#include "rig/pose.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "tests/rig/default_characters.h"

#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/skin.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/scene.h"

namespace stirrup::rig {
namespace {

using test::defaultHorse;
using test::defaultRider;
const Character& horse() { return defaultHorse(); }
const Character& rider() { return defaultRider(); }
glm::vec3 pos(const std::vector<glm::mat4>& w, int j) { return glm::vec3(w[j][3]); }
glm::vec3 at(const Character& c, const std::vector<glm::mat4>& w, const char* role) { return pos(w, c.role(role)); }
bool finite(const std::vector<glm::mat4>& w) {
  for (const glm::mat4& m : w)
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 4; ++k)
        if (!std::isfinite(m[i][k])) return false;
  return true;
}

// How far the middle joint sits ahead (+X) of the line from the chain root to the fetlock.
float middleAheadOfChord(const std::vector<glm::mat4>& w, const char* leg) {
  const std::string n = leg;
  const glm::vec3 a = at(horse(), w, (n + "Upper").c_str()), m = at(horse(), w, (n + "Middle").c_str());
  const glm::vec3 b = at(horse(), w, (n + "Fetlock").c_str());
  const float t = glm::dot(m - a, b - a) / glm::dot(b - a, b - a);
  return (m - (a + (b - a) * t)).x;
}

TEST(PoseHorse, RestPoseIsTheBindPoseWithHoovesOnTheGround) {
  const Character& h = horse();
  const std::vector<glm::mat4> w = poseHorse(h, HorseFrame{});
  ASSERT_EQ(w.size(), h.skeleton.size());
  const std::vector<glm::mat4> rest = restWorlds(h.skeleton);
  for (std::size_t j = 0; j < w.size(); ++j)
    EXPECT_LT(glm::length(pos(w, int(j)) - pos(rest, int(j))), 0.1f) << h.skeleton.joints[j].name;
  for (const char* leg : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"}) {
    EXPECT_NEAR(at(h, w, leg).y, 0.0f, 0.1f) << leg;
    EXPECT_LT(glm::length(at(h, w, leg) - h.skeleton.restPosition(h.role(leg))), 0.1f);
  }
  // Hooves under the shoulders and hips: fore ahead of hind, left at -Z.
  EXPECT_GT(at(h, w, "lfHoof").x, at(h, w, "lbHoof").x + 80.0f);
  EXPECT_LT(at(h, w, "lfHoof").z, 0.0f);
  EXPECT_GT(at(h, w, "rfHoof").z, 0.0f);
}

TEST(PoseHorse, ProportionsOfAHorse) {
  const Character& h = horse();
  const float withers = h.skeleton.restPosition(h.role("withers")).y;
  EXPECT_GE(withers, 150.0f);
  EXPECT_LE(withers, 170.0f);
  glm::vec3 lo(1e9f), hi(-1e9f);
  float top_at_withers = 0.0f;
  for (const glm::vec3& p : h.mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    if (std::abs(p.x - h.skeleton.restPosition(h.role("withers")).x) < 3.0f && std::abs(p.z) < 3.0f)
      top_at_withers = std::max(top_at_withers, p.y);
  }
  EXPECT_NEAR(top_at_withers, withers, 10.0f);  // the mesh's withers, not just the joint
  EXPECT_NEAR(lo.y, 0.0f, 0.5f);
  EXPECT_GT(hi.x - lo.x, 220.0f);
  EXPECT_LT(hi.x - lo.x, 270.0f);
}

TEST(PoseHorse, HoofChannelsMoveHoovesAndLegsBendTheRightWay) {
  const Character& h = horse();
  HorseFrame f;
  f.travel_cm = 100.0;
  f.controls[HorseChannel::lfHoofTy] = 25.0;
  f.controls[HorseChannel::lfHoofTx] = 5.0;
  f.controls[HorseChannel::lbHoofTy] = 25.0;
  f.controls[HorseChannel::rbHoofTz] = 3.0;
  const std::vector<glm::mat4> w = poseHorse(h, f);
  ASSERT_TRUE(finite(w));
  const glm::vec3 rest_lf = h.skeleton.restPosition(h.role("lfHoof"));
  EXPECT_LT(glm::length(at(h, w, "lfHoof") - (rest_lf + glm::vec3(105, 25, 0))), 0.2f);
  EXPECT_NEAR(at(h, w, "rbHoof").z - h.skeleton.restPosition(h.role("rbHoof")).z, 3.0f, 0.2f);
  EXPECT_NEAR(at(h, w, "rfHoof").y, 0.0f, 0.1f);
  // A lifted foreleg folds at the knee, which points forward; a lifted hind leg's hock points back.
  EXPECT_GT(middleAheadOfChord(w, "lf"), 3.0f);
  EXPECT_LT(middleAheadOfChord(w, "lb"), -3.0f);
}

TEST(PoseHorse, BodyChannelsFollowTheContractSigns) {
  const Character& h = horse();
  const std::vector<glm::mat4> rest = poseHorse(h, HorseFrame{});
  auto posed = [&](HorseChannel c, double v) {
    HorseFrame f;
    f.controls[c] = v;
    return poseHorse(h, f);
  };
  EXPECT_GT(at(h, posed(HorseChannel::rearPivotRz, 10), "withers").y, at(h, rest, "withers").y + 5.0f);
  EXPECT_GT(at(h, posed(HorseChannel::rearPivotRx, 10), "withers").z, 2.0f);  // rolls to its right
  EXPECT_GT(at(h, posed(HorseChannel::rearPivotRy, 10), "head").z, 10.0f);    // yaws to the right
  EXPECT_NEAR(at(h, posed(HorseChannel::rearPivotTy, 7), "root").y, at(h, rest, "root").y + 7.0f, 1e-3f);
  EXPECT_GT(at(h, posed(HorseChannel::backMidRz, 6), "backMid").y, at(h, rest, "backMid").y + 1.0f);
  // Hooves stay planted while the body moves.
  const std::vector<glm::mat4> w = posed(HorseChannel::rearPivotTy, -5);
  EXPECT_NEAR(at(h, w, "lfHoof").y, 0.0f, 0.1f);
  HorseFrame f;
  f.neck_rz = 10;
  f.head_rz = -10;
  f.tail_rz = 20;
  EXPECT_GT(at(h, poseHorse(h, f), "head").y, at(h, rest, "head").y);
}

// The travel frame moves and turns the whole horse rigidly: heading 90° (toward +Z, a right turn) at
// (100, 0, 250) poses every joint as the same frame at the origin, turned about -Y and moved there.
TEST(PoseHorse, TheTravelFrameMovesAndTurnsTheHorseRigidly) {
  HorseFrame f;
  f.controls[HorseChannel::rearPivotRz] = 6.0;
  f.controls[HorseChannel::lfHoofTy] = 15.0;
  f.controls[HorseChannel::rbHoofTx] = -20.0;
  const std::vector<glm::mat4> at_origin = poseHorse(horse(), f);
  f.travel_cm = 100.0;
  f.travel_z_cm = 250.0;
  f.heading_deg = 90.0;
  const std::vector<glm::mat4> turned = poseHorse(horse(), f);
  const glm::mat4 frame = travelMatrix(f);
  // Heading 90°: the horse's forward (+X in its frame) points along world +Z, its right along -X.
  EXPECT_NEAR(glm::length(glm::vec3(frame * glm::vec4(1, 0, 0, 0)) - glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(glm::vec3(frame * glm::vec4(0, 0, 1, 0)) - glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
  for (std::size_t j = 0; j < turned.size(); ++j) {
    const glm::vec3 expected(frame * at_origin[j][3]);
    EXPECT_NEAR(glm::length(glm::vec3(turned[j][3]) - expected), 0.0f, 1e-3f) << horse().skeleton.joints[j].name;
  }
  // The rider with her, the balance stage included (it measures her lean against the saddle's own
  // heading, so a turned travel frame changes nothing in it).
  RiderChannels ch;
  ch[RiderChannel::lowerBackRz] = 12.0;
  HorseFrame f0 = f;
  f0.travel_cm = f0.travel_z_cm = f0.heading_deg = 0.0;
  const MountedPose a = poseMounted(horse(), rider(), f0, ch, RigProfile::thesis());
  const MountedPose b = poseMounted(horse(), rider(), f, ch, RigProfile::thesis());
  EXPECT_NEAR(a.balance.turn_deg, b.balance.turn_deg, 1e-4);
  for (std::size_t j = 0; j < a.rider.size(); ++j)
    EXPECT_NEAR(glm::length(glm::vec3(b.rider[j][3]) - glm::vec3(frame * a.rider[j][3])), 0.0f, 1e-3f)
        << rider().skeleton.joints[j].name;
}

TEST(PoseHorse, ExtremeValuesStayFinite) {
  HorseFrame f;
  for (std::size_t i = 0; i < kHorseChannelCount; ++i) f.controls.value[i] = (i % 2 ? 1 : -1) * 400.0;
  EXPECT_TRUE(finite(poseHorse(horse(), f)));
}

// Never a rubber leg (issue 36): a hind hoof asked 1.5 m behind its rest place (the hairpin
// horse) leaves its leg at full reach with every bone its rest length, and the frame records that hoof
// short of its target by at least what no reach can close.
TEST(PoseHorse, AHoofBeyondItsLegsReachIsFlaggedAndNoBoneStretches) {
  const Skeleton& s = horse().skeleton;
  HorseFrame f;
  f.controls[HorseChannel::lbHoofTx] = -150.0;
  HorseReach reach;
  const std::vector<glm::mat4> w = poseHorse(horse(), f, {}, &reach);
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int parent = s.joints[j].parent;
    if (parent < 0) continue;
    const float rest = glm::length(s.restPosition(int(j)) - s.restPosition(parent));
    EXPECT_NEAR(glm::length(pos(w, int(j)) - pos(w, parent)), rest, 1e-3f) << s.joints[j].name;
  }
  EXPECT_TRUE(reach.overReached(2));
  EXPECT_FALSE(reach.overReached(0));
  EXPECT_FALSE(reach.overReached(1));
  EXPECT_FALSE(reach.overReached(3));
  EXPECT_TRUE(reach.any());
  // How short, at least: the fetlock's target lies |target − pivot| from the hip; the stretched leg
  // spans horseLegFullReach of it, and rolling the hoof over its toe by at most 45° brings the fetlock
  // nearer by at most the chord 2 |fetlock − toe| sin(22.5°).
  const HorseLegParams leg;
  HorseLegJoints j;
  j.fore = false;
  j.pivot = horse().role("lbPivot");
  j.upper = horse().role("lbUpper");
  j.middle = horse().role("lbMiddle");
  j.fetlock = horse().role("lbFetlock");
  j.hoof = horse().role("lbHoof");
  const glm::vec3 rest_hoof = s.restPosition(j.hoof), rest_fetlock = s.restPosition(j.fetlock);
  const glm::vec3 target_fetlock = rest_hoof + glm::vec3(-150.0f, 0.0f, 0.0f) + (rest_fetlock - rest_hoof);
  const glm::vec3 toe = rest_hoof + glm::vec3(leg.toe_cm, 0.0f, 0.0f);
  const float roll_chord = 2.0f * glm::length(rest_fetlock - toe) * std::sin(22.5f * 3.14159265f / 180.0f);
  const float least = glm::length(target_fetlock - pos(w, j.pivot)) - horseLegFullReach(s, j, leg) - roll_chord;
  EXPECT_GT(least, 30.0f);
  EXPECT_GE(reach.short_cm[2], least);
  // Within reach (20 cm behind), nothing is flagged.
  f.controls[HorseChannel::lbHoofTx] = -20.0;
  HorseReach near;
  (void)poseHorse(horse(), f, {}, &near);
  EXPECT_FALSE(near.any());
  for (float c : near.short_cm) EXPECT_LT(c, 0.01f);
}

TEST(PoseRider, AtRestSeatedInTheSaddleWithFeetInTheStirrupsAndHandsOnTheReins) {
  const Character& h = horse();
  const Character& r = rider();
  const std::vector<glm::mat4> hw = poseHorse(h, HorseFrame{});
  const std::vector<glm::mat4> rw = poseRider(r, h, hw, RiderChannels{}, 2.54);
  ASSERT_EQ(rw.size(), r.skeleton.size());
  const glm::vec3 seat = at(h, hw, "saddle");
  const glm::vec3 pelvis = at(r, rw, "pelvis");
  EXPECT_LT(std::abs(pelvis.x - seat.x), 20.0f);  // within the seat's length
  EXPECT_LT(std::abs(pelvis.z - seat.z), 1e-3f);
  EXPECT_GT(pelvis.y, seat.y);
  EXPECT_LT(pelvis.y, seat.y + 15.0f);
  EXPECT_LT(glm::length(at(r, rw, "lBall") - at(h, hw, "lStirrup")), 0.5f);
  EXPECT_LT(glm::length(at(r, rw, "rBall") - at(h, hw, "rStirrup")), 0.5f);
  // Rest pose reproduces the bind pose (in saddle space).
  for (std::size_t j = 0; j < rw.size(); ++j)
    EXPECT_LT(glm::length(pos(rw, int(j)) - (seat + r.skeleton.restPosition(int(j)))), 0.1f)
        << r.skeleton.joints[j].name;
  // Head above the seat by a seated 170 cm person's height, hands ahead of the seat.
  EXPECT_GT(at(r, rw, "head").y - seat.y, 55.0f);
  EXPECT_GT(at(r, rw, "lWrist").x, seat.x + 15.0f);
}

TEST(PoseRider, NothingOfTheRiderPassesIntoTheHorsesTrunk) {
  const Character& h = horse();
  const Character& r = rider();
  const HorseParams hp;
  const std::vector<glm::mat4> hw = poseHorse(h, HorseFrame{});
  const std::vector<glm::mat4> rw = poseRider(r, h, hw, RiderChannels{}, 2.54);
  std::vector<glm::vec3> p, n;
  skinMesh(r.mesh, r.skeleton, rw, p, n);
  int inside = 0;
  for (const glm::vec3& v : p) {
    const glm::vec3 b = (v - hp.barrel_center) / hp.barrel_radii;
    const glm::vec3 c = (v - hp.chest_center) / hp.chest_radii;
    inside += glm::dot(b, b) < 1.0f || glm::dot(c, c) < 1.0f;
  }
  EXPECT_EQ(inside, 0);
}

TEST(PoseRider, CogLiftsThePelvisByExactlyTheRiderUnit) {
  const Character& h = horse();
  const Character& r = rider();
  HorseFrame f;
  f.travel_cm = 321.0;
  f.controls[HorseChannel::rearPivotTy] = 4.0;
  const std::vector<glm::mat4> hw = poseHorse(h, f);
  RiderChannels ch;
  const glm::vec3 rest = at(r, poseRider(r, h, hw, ch, 2.54), "pelvis");
  ch[RiderChannel::cogTy] = 1.5;
  ch[RiderChannel::cogTx] = 0.5;
  const glm::vec3 lifted = at(r, poseRider(r, h, hw, ch, 2.54), "pelvis");
  EXPECT_NEAR(lifted.y - rest.y, 1.5 * 2.54, 1e-3);
  EXPECT_NEAR(lifted.x - rest.x, 0.5 * 2.54, 1e-3);
}

TEST(PoseRider, ChannelsFollowTheContractSigns) {
  const Character& h = horse();
  const Character& r = rider();
  const std::vector<glm::mat4> hw = poseHorse(h, HorseFrame{});
  const std::vector<glm::mat4> rest = poseRider(r, h, hw, RiderChannels{}, 1.0);
  auto posed = [&](RiderChannel c, double v) {
    RiderChannels ch;
    ch[c] = v;
    return poseRider(r, h, hw, ch, 1.0);
  };
  EXPECT_GT(at(r, posed(RiderChannel::lowerBackRz, 15), "head").x, at(r, rest, "head").x + 5.0f);
  EXPECT_GT(at(r, posed(RiderChannel::waistRz, 15), "head").x, at(r, rest, "head").x + 3.0f);
  EXPECT_GT(at(r, posed(RiderChannel::lowerBackRy, 10), "head").z, 3.0f);  // leans to her right
  EXPECT_GT(at(r, posed(RiderChannel::hipRy, 10), "head").z, 3.0f);        // as rearPivot.rx +
  EXPECT_NEAR(at(r, posed(RiderChannel::neckTy, 2), "head").y, at(r, rest, "head").y + 2.0f, 1e-3f);
  EXPECT_GT(at(r, posed(RiderChannel::lWristTy, 5), "lWrist").y, at(r, rest, "lWrist").y + 4.9f);
  EXPECT_GT(at(r, posed(RiderChannel::rWristTx, 5), "rWrist").x, at(r, rest, "rWrist").x + 4.9f);
  EXPECT_LT(at(r, posed(RiderChannel::lFootTz, 4), "lBall").z, at(r, rest, "lBall").z - 3.9f);  // away from belly
  EXPECT_GT(at(r, posed(RiderChannel::rFootTz, 4), "rBall").z, at(r, rest, "rBall").z + 3.9f);
  EXPECT_GT(at(r, posed(RiderChannel::lFootTx, 4), "lBall").x, at(r, rest, "lBall").x + 3.9f);
  EXPECT_LT(at(r, posed(RiderChannel::lKneeTz, 4), "lKnee").z, at(r, rest, "lKnee").z - 1.0f);
  EXPECT_GT(at(r, posed(RiderChannel::rKneeTz, 4), "rKnee").z, at(r, rest, "rKnee").z + 1.0f);
  // Head pitches forward: a point ahead of the head drops.
  const auto head_fwd = [&](const std::vector<glm::mat4>& w) {
    return glm::vec3(w[r.role("head")] * r.skeleton.joints[r.role("head")].inverse_bind *
                     glm::vec4(r.skeleton.restPosition(r.role("head")) + glm::vec3(10, 10, 0), 1.0f));
  };
  EXPECT_LT(head_fwd(posed(RiderChannel::headRz, 20)).y, head_fwd(rest).y - 1.0f);
  // Toe up: the ball stays, the ankle (heel) drops.
  EXPECT_LT(at(r, posed(RiderChannel::lFootRz, 15), "lAnkle").y, at(r, rest, "lAnkle").y - 1.0f);
  // Hair and cloth swing.
  EXPECT_GT(glm::length(at(r, posed(RiderChannel::hairUp, 30), "braid3") - at(r, rest, "braid3")), 1.0f);
  RiderChannels wild;
  for (std::size_t i = 0; i < kRiderChannelCount; ++i) wild.value[i] = (i % 2 ? 1 : -1) * 300.0;
  EXPECT_TRUE(finite(poseRider(r, h, hw, wild, 2.54)));
}

// The rider's spine chain joints in the pelvis's rest frame, for a horse at rest and the hip still.
struct RiderSpinePose {
  std::vector<glm::mat4> world;
  glm::vec3 origin{0.0f};  // where the chain's root (spine0) sits at rest, world
};
RiderSpinePose poseRiderAt(const RiderChannels& ch, double unit = 2.54) {
  const Character& h = horse();
  const Character& r = rider();
  const std::vector<glm::mat4> hw = poseHorse(h, HorseFrame{});
  RiderSpinePose out;
  out.world = poseRider(r, h, hw, ch, unit);
  out.origin = at(h, hw, "saddle") + r.skeleton.restPosition(riderSpine(r).chain[0]);
  return out;
}
double angleDeg(glm::dvec3 a, glm::dvec3 b) {
  return glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
}

// The chain posed from the channels, against what the curve spine's definition (rig/curve_spine.h)
// gives by hand, not against the calls pose.cpp makes. The channels' controllers (docs/curve-spine.md,
// "The rider"): lowerBack.rz 12 bends the lower controller 12 degrees forward, waist.rz 20 the middle
// 20 more, and the chest follows half the waist (chest_follow 0.5): the top 10 more, so the three FK
// bones (10, 11 and 10 cm) lean 12, 32 and 42 degrees forward of upright, in the plane of her back
// (z = 0). lowerBack.rx 9 twists the chest's front 9 degrees to her right, which turns no bone off that
// plane. The spine channels stretch it by (0.3 + 0.2 - 0.1) x 2.54 cm on 31 (Kuhnel's Eq 9). The
// chain runs from the FK root to the FK tip, its tip turned as the top bone with the whole twist, and
// its bones bend forward a little more each, the first about as the lower bone (12 degrees) and the
// last about as the top bone (42): the curve leaves and arrives along them (clamped ends), and a chord
// near an end leans within a couple of degrees of the tangent there.
TEST(PoseRiderSpine, ChainRunsFromTheRootToTheFkTipWithTheTopsTurnAndTwist) {
  const Character& r = rider();
  const RiderSpine layout = riderSpine(r);
  EXPECT_NEAR(layout.fk_lengths[0], 10.0, 1e-4);  // the default rider's lower back → waist → chest → upper chest
  EXPECT_NEAR(layout.fk_lengths[1], 11.0, 1e-4);
  EXPECT_NEAR(layout.fk_lengths[2], 10.0, 1e-4);
  RiderChannels ch;
  ch[RiderChannel::lowerBackRz] = 12.0;
  ch[RiderChannel::waistRz] = 20.0;
  ch[RiderChannel::lowerBackRx] = 9.0;
  ch[RiderChannel::spineCTy] = 0.3;
  ch[RiderChannel::spineDTy] = 0.2;
  ch[RiderChannel::spineFTy] = -0.1;
  const RiderSpinePose posed = poseRiderAt(ch);
  const double stretch = (31.0 + 0.4 * 2.54) / 31.0;
  EXPECT_NEAR(riderSpineStretch(CurveSpine(layout.fk_lengths, kRiderSpineSegments), ch, 2.54), stretch, 1e-9);
  const auto lean = [](double deg) { return glm::dvec3(std::sin(glm::radians(deg)), std::cos(glm::radians(deg)), 0.0); };
  // The FK tip: (14.60, 26.54, 0) cm from the root before the stretch.
  const glm::dvec3 tip = glm::dvec3(posed.origin) + stretch * (10.0 * lean(12.0) + 11.0 * lean(32.0) + 10.0 * lean(42.0));
  const auto joint = [&](int i) { return glm::dvec3(pos(posed.world, layout.chain[static_cast<std::size_t>(i)])); };
  EXPECT_LT(glm::length(joint(0) - glm::dvec3(posed.origin)), 1e-3);
  EXPECT_LT(glm::length(joint(kRiderSpineSegments) - tip), 1e-3);
  // Every joint in the plane of her back; every bone the same length (equal arc lengths on a gentle
  // bend: chords within 0.1% of each other), together no longer than the FK bones whose corners the
  // curve cuts, and no shorter than the straight line from root to tip.
  double total = 0.0, shortest = 1e9, longest = 0.0, previous_lean = -90.0;
  for (int i = 0; i < kRiderSpineSegments; ++i) {
    EXPECT_NEAR(joint(i + 1).z, posed.origin.z, 1e-4) << "spine" << i + 1;
    const glm::dvec3 bone = joint(i + 1) - joint(i);
    const double chord = glm::length(bone);
    total += chord, shortest = std::min(shortest, chord), longest = std::max(longest, chord);
    const double bone_lean = glm::degrees(std::atan2(bone.x, bone.y));
    EXPECT_GT(bone_lean, previous_lean) << "bone " << i;
    if (i == 0) {
      EXPECT_NEAR(bone_lean, 12.0, 2.0);
    }
    previous_lean = bone_lean;
  }
  EXPECT_NEAR(previous_lean, 42.0, 2.0);
  EXPECT_LT(longest / shortest, 1.001);
  EXPECT_LT(total, 31.0 * stretch);
  EXPECT_GT(total, glm::length(tip - glm::dvec3(posed.origin)));
  // The tip's turn (the joint's world rotation from its rest): her up (world +Y at rest) along the top
  // bone, 42 degrees forward; her front (+X at rest) pitched down with it and turned 9 degrees to her
  // right (+Z).
  const glm::mat4& m = posed.world[layout.chain[kRiderSpineSegments]];
  const double c42 = std::cos(glm::radians(42.0)), s42 = std::sin(glm::radians(42.0));
  const double c9 = std::cos(glm::radians(9.0)), s9 = std::sin(glm::radians(9.0));
  EXPECT_LT(glm::length(glm::dvec3(glm::vec3(m[1])) - lean(42.0)), 1e-4);
  EXPECT_LT(glm::length(glm::dvec3(glm::vec3(m[0])) - glm::dvec3(c42 * c9, -s42 * c9, s9)), 1e-4);
  // The neck rides on the tip: its offset from the tip is the rest offset turned by the tip's frame.
  const int top = layout.chain[kRiderSpineSegments];
  const glm::vec3 rest_offset = r.skeleton.restPosition(r.role("neck")) - r.skeleton.restPosition(top);
  const glm::vec3 neck = at(r, posed.world, "neck");
  EXPECT_LT(glm::length(neck - (pos(posed.world, top) + glm::mat3(posed.world[top]) * rest_offset)), 1e-3f);
}

// A lean to her left alone (lowerBack.ry -6; + leans right, toward +Z): the three FK bones lean 6
// degrees toward -Z together, so the chain is straight, its joints every 3.1 cm along that line.
TEST(PoseRiderSpine, ASideLeanTiltsTheStraightChain) {
  const RiderSpine layout = riderSpine(rider());
  RiderChannels ch;
  ch[RiderChannel::lowerBackRy] = -6.0;
  const RiderSpinePose posed = poseRiderAt(ch);
  const glm::dvec3 up(0.0, std::cos(glm::radians(6.0)), -std::sin(glm::radians(6.0)));
  for (int i = 0; i <= kRiderSpineSegments; ++i) {
    const glm::dvec3 expected = glm::dvec3(posed.origin) + 3.1 * i * up;
    EXPECT_LT(glm::length(glm::dvec3(pos(posed.world, layout.chain[static_cast<std::size_t>(i)])) - expected), 1e-3) << "spine" << i;
  }
}

TEST(PoseRiderSpine, AtRestTheTorsoIsUpright) {
  const Character& r = rider();
  const RiderSpine layout = riderSpine(r);
  const RiderSpinePose posed = poseRiderAt(RiderChannels{});
  for (int i = 0; i < kRiderSpineSegments; ++i) {
    const glm::vec3 d = pos(posed.world, layout.chain[i + 1]) - pos(posed.world, layout.chain[i]);
    EXPECT_NEAR(d.y, 3.1f, 1e-4f) << "spine" << i;
    EXPECT_LT(std::abs(d.x) + std::abs(d.z), 1e-4f) << "spine" << i;
    const glm::mat3 turn = glm::mat3(posed.world[layout.chain[i]]);
    for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(turn[c] - glm::mat3(1.0f)[c]), 1e-5f) << "spine" << i;
  }
  // The torso's mesh: every vertex skinned to the chain alone is where the bind pose put it, and
  // its weights are spread over neighbouring chain bones.
  std::vector<glm::vec3> p, n;
  skinMesh(r.mesh, r.skeleton, posed.world, p, n);
  const glm::vec3 seat = posed.origin - r.skeleton.restPosition(layout.chain[0]);
  const auto on_chain = [&](int j) {
    return std::find(layout.chain.begin(), layout.chain.end(), j) != layout.chain.end();
  };
  float worst = 0.0f;
  int torso = 0, blended = 0;
  for (std::size_t v = 0; v < p.size(); ++v) {
    float share = 0.0f;
    int chain_bones = 0;
    for (int k = 0; k < kMaxInfluences; ++k)
      if (r.mesh.weights[v][k] > 0.0f && on_chain(r.mesh.joints[v][k])) {
        share += r.mesh.weights[v][k];
        ++chain_bones;
      }
    if (share < 0.9f) continue;
    ++torso;
    blended += chain_bones == 2;
    worst = std::max(worst, glm::length(p[v] - (seat + r.mesh.positions[v])));
  }
  std::printf("torso vertices (>= 90%% on the chain): %d, on two chain bones: %d, of %zu\n", torso, blended, p.size());
  EXPECT_GT(torso, 1000);
  EXPECT_GT(blended, torso / 2);
  EXPECT_LT(worst, 1e-2f);
}

TEST(PoseRiderSpine, LeaningForwardBendsTheChainSmoothlyTowardTheFront) {
  const Character& r = rider();
  const RiderSpine layout = riderSpine(r);
  RiderChannels ch;
  ch[RiderChannel::lowerBackRz] = 15.0;
  ch[RiderChannel::waistRz] = 15.0 * 1.7;  // Eq 4
  const RiderSpinePose posed = poseRiderAt(ch);
  std::vector<glm::dvec3> bones;
  for (int i = 0; i < kRiderSpineSegments; ++i)
    bones.push_back(glm::dvec3(pos(posed.world, layout.chain[i + 1]) - pos(posed.world, layout.chain[i])));
  const double total = angleDeg(bones.front(), bones.back());
  EXPECT_GT(total, 20.0);  // the waist and the chest follow bend the chain, not just the lower back
  double worst = 0.0, previous_lean = -1.0;
  for (std::size_t i = 0; i < bones.size(); ++i) {
    const double lean = std::atan2(bones[i].x, bones[i].y);  // forward lean of the bone, radians
    EXPECT_GT(lean, previous_lean) << "bone " << i << " leans less than the one below";
    EXPECT_GT(lean, 0.0) << "bone " << i;
    EXPECT_NEAR(bones[i].z, 0.0, 1e-4);
    previous_lean = lean;
    if (i > 0) worst = std::max(worst, angleDeg(bones[i - 1], bones[i]));
  }
  // No kink: the bend is spread over the chain, no neighbouring pair turns more than a few degrees
  // (the FK spine put the whole waist bend in one joint).
  std::printf("lean: chain bend %.2f deg over %d bones, worst neighbouring pair %.2f deg\n", total,
              kRiderSpineSegments, worst);
  EXPECT_LT(worst, 8.0);
  EXPECT_LT(worst, 0.2 * total);
  // The tip ends up well ahead of the root and the head further still.
  const glm::vec3 tip = pos(posed.world, layout.chain[kRiderSpineSegments]);
  EXPECT_GT(tip.x - posed.origin.x, 8.0f);
  EXPECT_GT(at(r, posed.world, "head").x, tip.x);
  // Twist goes to the chest, spread over the chain: lowerBack.rx + turns the chest's front to her right.
  ch = RiderChannels{};
  ch[RiderChannel::lowerBackRx] = 20.0;
  const RiderSpinePose twisted = poseRiderAt(ch);
  const glm::vec3 front = glm::mat3(twisted.world[layout.chain[kRiderSpineSegments]]) * glm::vec3(1, 0, 0);
  EXPECT_NEAR(glm::degrees(std::atan2(front.z, front.x)), 20.0, 1e-3);
  const glm::vec3 low = glm::mat3(twisted.world[layout.chain[0]]) * glm::vec3(1, 0, 0);
  EXPECT_NEAR(glm::degrees(std::atan2(low.z, low.x)), 2.0, 1e-3);
}

TEST(PoseRider, StirrupsFollowTheFeet) {
  const Character& h = horse();
  std::vector<glm::mat4> hw = poseHorse(h, HorseFrame{});
  const glm::vec3 before = at(h, hw, "lStirrup");
  RiderChannels ch;
  ch[RiderChannel::lFootTx] = 2.0;
  placeStirrups(h, hw, ch, 2.54);
  EXPECT_NEAR(at(h, hw, "lStirrup").x - before.x, 5.08f, 1e-3f);
  const std::vector<glm::mat4> rw = poseRider(rider(), h, hw, ch, 2.54);
  EXPECT_LT(glm::length(at(rider(), rw, "lBall") - at(h, hw, "lStirrup")), 0.5f);
}

// The reins run from the bit to the rider's hands: wherever the wrist channels move the hands, the
// horse's rein ends (lRein, rRein) are where the hands close on the reins (lHand, rHand).
TEST(PoseMounted, ReinsEndInTheRidersHands) {
  const Character& h = horse();
  const Character& r = rider();
  HorseFrame f;
  f.controls[HorseChannel::rearPivotRz] = 10.0;
  RiderChannels ch;
  ch[RiderChannel::lWristTx] = 1.5;
  ch[RiderChannel::rWristTy] = -1.0;
  const MountedPose p = poseMounted(h, r, f, ch, RigProfile::thesis());
  for (const char* side : {"l", "r"}) {
    const glm::vec3 rein = glm::vec3(p.horse[h.role(std::string(side) + "Rein")][3]);
    const glm::vec3 hand = glm::vec3(p.rider[r.role(std::string(side) + "Hand")][3]);
    EXPECT_LT(glm::length(rein - hand), 1e-4f) << side;
    EXPECT_GT(glm::length(rein - h.skeleton.restPosition(h.role(std::string(side) + "Rein"))), 5.0f) << side;
  }
}

// The posing limits (docs/rider-rig.md): the torso's forward lean is scaled to at most max_lean_deg
// keeping its proportions; stirrup swing, toe turn, the feet in toward the belly, the heels' twist and
// the seat's slide back are clamped; small values pass unchanged.
TEST(PoseMounted, LimitsScaleTheLeanAndClampTheFeet) {
  RiderPoseParams params;
  RiderChannels ch;
  ch[RiderChannel::hipRz] = 31.0;
  ch[RiderChannel::lowerBackRz] = 39.0;
  ch[RiderChannel::waistRz] = 67.0;
  ch[RiderChannel::lFootTx] = -13.0;
  ch[RiderChannel::rFootRz] = -158.0;
  ch[RiderChannel::lFootTz] = -0.75;  // Eq 17 on the jump: 7.5 cm in against the belly
  ch[RiderChannel::rFootRy] = -26.5;  // Eq 16: heel in
  ch[RiderChannel::cogTx] = -1.0;     // Eq 8: 10 cm back
  const RiderChannels l = limitRiderChannels(ch, params, 10.0);
  const double lean = l[RiderChannel::hipRz] + l[RiderChannel::lowerBackRz] + l[RiderChannel::waistRz] * (1.0 + params.chest_follow);
  EXPECT_NEAR(lean, params.max_lean_deg, 1e-9);
  EXPECT_NEAR(l[RiderChannel::waistRz] / l[RiderChannel::hipRz], 67.0 / 31.0, 1e-9);
  EXPECT_DOUBLE_EQ(l[RiderChannel::lFootTx], -params.max_foot_swing_cm / 10.0);
  EXPECT_DOUBLE_EQ(l[RiderChannel::rFootRz], -params.max_foot_turn_deg);
  EXPECT_DOUBLE_EQ(l[RiderChannel::lFootTz], -params.max_foot_in_cm / 10.0);
  EXPECT_DOUBLE_EQ(l[RiderChannel::rFootRy], -params.max_foot_twist_deg);
  EXPECT_DOUBLE_EQ(l[RiderChannel::cogTx], -params.max_seat_back_cm / 10.0);
  RiderChannels small;
  small[RiderChannel::lowerBackRz] = 5.0;
  small[RiderChannel::lFootTx] = 0.5;
  small[RiderChannel::lFootTz] = -0.2;
  small[RiderChannel::lFootRy] = -9.0;
  small[RiderChannel::cogTx] = -0.5;
  const RiderChannels same = limitRiderChannels(small, params, 10.0);
  EXPECT_EQ(same.value, small.value);
}

}  // namespace
}  // namespace stirrup::rig

namespace stirrup::rig {
namespace {

// Over-reach in the shipped scenes: every frame of each scene's clip posed on the default horse, a
// hoof short of its target by HorseReach::kOverReachCm or more counted, apart while it stands (its
// lift ty 0: the hoof hovers over its print) and while it swings (it misses a point in the air).
struct OverReach {
  int frames = 0, flagged = 0, stance_flagged = 0;
  float worst_stance_cm = 0, worst_swing_cm = 0;
  int worst_stance_frame = 0, worst_swing_frame = 0;
};
OverReach overReachOf(const std::string& name) {
  const render::SceneSpec scene = render::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + name + ".json");
  const auto clip = makeClip(scene.clip, test::defaultHorse());
  OverReach o;
  for (int frame : parseFrameList(scene.frames, name)) {
    HorseReach reach;
    const HorseFrame f = clip->sample(render::frameTime(scene, frame));
    (void)poseHorse(test::defaultHorse(), f, {}, &reach);
    ++o.frames;
    o.flagged += reach.any();
    bool stance_flag = false;
    for (int leg = 0; leg < 4; ++leg) {
      const float c = reach.short_cm[std::size_t(leg)];
      const bool stance = reach.planted[std::size_t(leg)];
      stance_flag |= stance && reach.overReached(leg);
      float& worst = stance ? o.worst_stance_cm : o.worst_swing_cm;
      if (c > worst) (stance ? o.worst_stance_frame : o.worst_swing_frame) = frame, worst = c;
    }
    o.stance_flagged += stance_flag;
  }
  return o;
}

// Measured (docs/horse-limits.md, "Never a rubber leg"): no shipped clip leaves a planted hoof short
// of its print by a centimetre (trail's 2 frames where a fore landing at the end of a trot stride over
// a hill crest fell 2.3 cm short now settle the body 2.4 cm onto it: HorsePoseParams::
// max_stance_settle_cm). In the air, a fore at the end of its swing reaching 60-96 cm ahead of its
// rest place while the trunk rides high in the suspension (trot, canter, the jump's landing), or a
// hind at the start of its swing far behind (the jump's take-off, 94 cm), stays short of the clip's
// point by up to 10 cm: the leg at full reach, the hoof landing a little late. Held to what was
// measured (frames flagged, worst standing and swinging cm) so that it cannot get worse unseen.
TEST(PoseHorse, ShippedScenesOverReachOnlyWhereMeasured) {
  struct Measured {
    const char* name;
    int flagged, stance_flagged;
    float stance_cm, swing_cm;
  };
  for (const Measured& m : {Measured{"walk", 1, 0, 0.63f, 1.09f}, Measured{"trot", 12, 0, 0.24f, 4.08f},
                            Measured{"canter", 10, 0, 0.06f, 5.20f}, Measured{"gallop", 12, 0, 0.0f, 1.89f},
                            Measured{"stop", 10, 0, 0.0f, 6.04f}, Measured{"jump", 25, 0, 0.05f, 10.08f},
                            Measured{"rear", 0, 0, 0.0f, 0.0f}, Measured{"buck", 3, 0, 0.0f, 3.10f},
                            Measured{"cross_country", 44, 0, 0.32f, 5.73f}, Measured{"figure_eight", 28, 0, 0.0f, 2.37f},
                            Measured{"trail", 35, 0, 0.89f, 6.61f}}) {
    const OverReach o = overReachOf(m.name);
    std::printf("  %-14s %3d frames over-reached, %d with a planted hoof short, worst planted %.2f cm (frame %d), in the air %.2f cm\n",
                m.name, o.flagged, o.stance_flagged, o.worst_stance_cm, o.worst_stance_frame, o.worst_swing_cm);
    EXPECT_LE(o.flagged, m.flagged) << m.name;
    EXPECT_LE(o.stance_flagged, m.stance_flagged) << m.name;
    EXPECT_LE(o.worst_stance_cm, m.stance_cm + 0.05f) << m.name << " frame " << o.worst_stance_frame;
    EXPECT_LE(o.worst_swing_cm, m.swing_cm + 0.05f) << m.name << " frame " << o.worst_swing_frame;
  }
}

}  // namespace
}  // namespace stirrup::rig
