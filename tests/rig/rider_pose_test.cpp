#include "rig/rider_pose.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "tests/rig/default_characters.h"
#include "tests/rig/posed_joints.h"

#include "rig/horse_pose.h"
#include "rig/rider_spine.h"
#include "rig/skin.h"

namespace stirrup::rig {
namespace {

using namespace test;  // defaultHorse, defaultRider; pos, at, finite (tests/rig/posed_joints.h)
const Character& horse() { return defaultHorse(); }
const Character& rider() { return defaultRider(); }

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

// The posing limits (docs/rider-rig.md): the torso's forward lean is scaled to at most max_lean_deg
// keeping its proportions; stirrup swing, toe turn, the feet in toward the belly, the heels' twist and
// the seat's slide back are clamped; small values pass unchanged.
TEST(PoseRider, LimitsScaleTheLeanAndClampTheFeet) {
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
