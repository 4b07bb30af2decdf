// A horse's back, neck and tail read from its skeleton (rig/horse_body.h) and posed by poseHorse
// (rig/horse_pose.h): stick-figure quadrupeds built here with necks, tails and backs of other lengths than the
// generated horse's. Expectations are worked by hand: n joints each turned by neck_rz / n about the
// horse's side axis turn the last of them by neck_rz; a bone's length is its rest length.
#include "rig/horse_body.h"

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "rig/characters/joint_placement.h"
#include "rig/pose.h"

namespace stirrup::rig {
namespace {

struct StickHorseSpec {
  int back_joints = 3;   // between the root and neck1
  int neck_joints = 2;   // neck1 and the joints up to the head
  int tail_joints = 3;
  bool back_mid_role = false;
  bool toe = false;       // an unnamed joint below lfHoof
};

// A quadruped of joints only: the root at the hips (-60, 128), the back straight forward to neck1 at
// (60, 132), the neck rising to the head at (110, 175), the tail hanging back and down, legs straight
// down from the back's ends.
Character stickHorse(const StickHorseSpec& spec) {
  Character c;
  c.name = "stick";
  Skeleton& s = c.skeleton;
  const glm::vec3 root_at{-60.0f, 128.0f, 0.0f}, neck1_at{60.0f, 132.0f, 0.0f}, head_at{110.0f, 175.0f, 0.0f};
  const int root = addJointAt(s, "hips", -1, root_at);
  int parent = root;
  std::vector<int> back;
  for (int i = 1; i <= spec.back_joints; ++i) {
    parent = addJointAt(s, "back" + std::to_string(i), parent, glm::mix(root_at, neck1_at, float(i) / float(spec.back_joints + 1)));
    back.push_back(parent);
  }
  int neck = addJointAt(s, "neck1", parent, neck1_at);
  c.roles["neck1"] = neck;
  for (int i = 1; i < spec.neck_joints; ++i)
    neck = addJointAt(s, "neck" + std::to_string(i + 1), neck, glm::mix(neck1_at, head_at, float(i) / float(spec.neck_joints)));
  c.roles["head"] = addJointAt(s, "head", neck, head_at);
  int tail = root;
  for (int i = 0; i < spec.tail_joints; ++i) {
    tail = addJointAt(s, "tail" + std::to_string(i + 1), tail, root_at + glm::vec3(-30.0f - 12.0f * i, 14.0f - 16.0f * i, 0.0f));
    if (i == 0) c.roles["tail1"] = tail;
  }
  c.roles["root"] = root;
  if (spec.back_mid_role) c.roles["backMid"] = back.front();
  for (const std::string leg : {"lf", "rf", "lb", "rb"}) {
    const bool fore = leg[1] == 'f';
    const float z = leg[0] == 'l' ? -14.0f : 14.0f;
    const float x = fore ? 55.0f : -62.0f;
    const int top = fore ? (back.empty() ? root : back.back()) : root;
    const int upper = addJointAt(s, leg + "Upper", top, {x, 100.0f, z});
    const int middle = addJointAt(s, leg + "Middle", upper, {x + (fore ? 4.0f : -6.0f), 54.0f, z});
    const int fetlock = addJointAt(s, leg + "Fetlock", middle, {x, 20.0f, z});
    const int hoof = addJointAt(s, leg + "Hoof", fetlock, {x + 3.0f, 0.0f, z});
    c.roles[leg + "Upper"] = upper;
    c.roles[leg + "Middle"] = middle;
    c.roles[leg + "Fetlock"] = fetlock;
    c.roles[leg + "Hoof"] = hoof;
    if (leg == "lf" && spec.toe) addJointAt(s, "lfToe", hoof, {x + 9.0f, 0.0f, z});
  }
  return c;
}

glm::vec3 at(const std::vector<glm::mat4>& w, int j) { return glm::vec3(w[j][3]); }

// The angle (degrees) a joint's world frame is turned about the side axis (+Z) from the travel frame.
float turnAboutZ(const glm::mat4& m) { return glm::degrees(std::atan2(m[0][1], m[0][0])); }

void expectBonesKeepTheirLength(const Character& c, const std::vector<glm::mat4>& w, const std::string& what) {
  const Skeleton& s = c.skeleton;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int p = s.joints[j].parent;
    if (p < 0) continue;
    const float rest = glm::length(s.restPosition(int(j)) - s.restPosition(p));
    EXPECT_NEAR(glm::length(at(w, int(j)) - at(w, p)), rest, 1e-3f * std::max(rest, 1.0f)) << what << ": bone " << s.joints[j].name;
  }
}

TEST(HorseBody, FindsTheNeckAndTailChainsOfAnyLength) {
  const Character c = stickHorse({.back_joints = 3, .neck_joints = 5, .tail_joints = 6});
  const HorseBody b = horseBody(c);
  ASSERT_EQ(b.neck.size(), 5u);
  EXPECT_EQ(c.skeleton.joints[b.neck.front()].name, "neck1");
  EXPECT_EQ(c.skeleton.joints[b.neck.back()].name, "neck5");
  EXPECT_EQ(b.tail.size(), 6u);
  EXPECT_EQ(b.tail_length, 6);
  // No backMid: the back joint nearest the middle of the hips (-60, 128) and neck1 (60, 132), (0, 130),
  // is back2 of back1..back3 at (-30, 129), (0, 130), (30, 131).
  EXPECT_FALSE(b.back_from_role);
  EXPECT_EQ(c.skeleton.joints[b.back_turn].name, "back2");
  // A back without a joint between the hips and the neck does not arch.
  EXPECT_EQ(horseBody(stickHorse({.back_joints = 0})).back_turn, -1);
  // backMid named: that joint.
  const Character named = stickHorse({.back_joints = 4, .back_mid_role = true});
  EXPECT_EQ(named.skeleton.joints[horseBody(named).back_turn].name, "back1");
}

TEST(HorseBody, NeckTurnSpreadsOverEveryNeckJointAndBonesKeepTheirLength) {
  for (int n : {1, 2, 3, 6}) {
    const Character c = stickHorse({.neck_joints = n});
    HorseFrame f;
    f.neck_rz = 30.0;
    const std::vector<glm::mat4> w = poseHorse(c, f);
    const HorseBody b = horseBody(c);
    ASSERT_EQ(int(b.neck.size()), n);
    for (int k = 0; k < n; ++k)
      EXPECT_NEAR(turnAboutZ(w[b.neck[k]]), 30.0f * float(k + 1) / float(n), 1e-3f) << n << " neck joints, joint " << k;
    EXPECT_NEAR(turnAboutZ(w[c.role("head")]), 30.0f, 1e-3f) << n;
    expectBonesKeepTheirLength(c, w, std::to_string(n) + " neck joints");
    // The neck bends: with more than one joint the head comes nearer neck1 (a chord of the bend).
    const glm::vec3 rest = c.skeleton.restPosition(c.role("head")) - c.skeleton.restPosition(c.role("neck1"));
    const float chord = glm::length(at(w, c.role("head")) - at(w, c.role("neck1")));
    if (n == 1) EXPECT_NEAR(chord, glm::length(rest), 1e-3f);
    else EXPECT_LT(chord, glm::length(rest) - 0.1f) << n;
  }
}

TEST(HorseBody, TailSwingSpreadsOverTheWholeTail) {
  for (int n : {1, 3, 5, 8}) {
    const Character c = stickHorse({.tail_joints = n});
    HorseFrame up, side;
    up.tail_rz = 24.0;   // + = up: about -Z
    side.tail_ry = 16.0;  // + = to the right: about +Y
    const std::vector<glm::mat4> wu = poseHorse(c, up), ws = poseHorse(c, side);
    const HorseBody b = horseBody(c);
    ASSERT_EQ(int(b.tail.size()), n);
    for (int k = 0; k < n; ++k) EXPECT_NEAR(turnAboutZ(wu[b.tail[k]]), -24.0f * float(k + 1) / float(n), 1e-3f) << n << ", " << k;
    // About +Y: x turns toward -z.
    const glm::mat4& last = ws[b.tail.back()];
    EXPECT_NEAR(glm::degrees(std::atan2(-last[0][2], last[0][0])), 16.0f, 1e-3f) << n;
    expectBonesKeepTheirLength(c, wu, std::to_string(n) + " tail joints, up");
    expectBonesKeepTheirLength(c, ws, std::to_string(n) + " tail joints, side");
  }
}

TEST(HorseBody, BackArchesAtTheJointFoundOrNamed) {
  HorseFrame f;
  f.controls[HorseChannel::backMidRz] = 10.0;
  for (bool named : {false, true}) {
    const Character c = stickHorse({.back_joints = 3, .back_mid_role = named});
    const std::vector<glm::mat4> w = poseHorse(c, f);
    const int turn = c.skeleton.find(named ? "back1" : "back2");
    // The front half pitches down by half the arch at the joint, the joint's parent stays.
    EXPECT_NEAR(turnAboutZ(w[turn]), -5.0f, 1e-3f) << named;
    EXPECT_NEAR(turnAboutZ(w[c.skeleton.joints[turn].parent]), 0.0f, 1e-3f) << named;
    // The joint itself rises: its bone from the parent tilts up by half the arch.
    EXPECT_GT(at(w, turn).y, c.skeleton.restPosition(turn).y + 0.5f) << named;
    expectBonesKeepTheirLength(c, w, named ? "arched at backMid" : "arched at the joint found");
  }
  // Without a back joint the channel moves nothing.
  const Character flat = stickHorse({.back_joints = 0});
  const std::vector<glm::mat4> w = poseHorse(flat, f), rest = poseHorse(flat, HorseFrame{});
  EXPECT_LT(glm::length(at(w, flat.role("head")) - at(rest, flat.role("head"))), 1e-4f);
}

// A joint no role names below a leg's IK chain (a toe) is carried by its hoof as it hangs at rest.
TEST(HorseBody, UnnamedJointsBelowTheLegsAreCarried) {
  const Character c = stickHorse({.toe = true});
  HorseFrame f;
  f.controls[HorseChannel::lfHoofTy] = 18.0;  // lifted: the pastern folds fully
  f.controls[HorseChannel::lfHoofTx] = 10.0;
  const std::vector<glm::mat4> w = poseHorse(c, f);
  const int toe = c.skeleton.find("lfToe"), hoof = c.role("lfHoof");
  EXPECT_NEAR(glm::length(at(w, toe) - at(w, hoof)), 6.0f, 1e-3f);
  // It moved with the hoof: up by about the lift, not left on the ground.
  EXPECT_GT(at(w, toe).y, 10.0f);
  const glm::mat4 expected = w[hoof] * c.skeleton.joints[toe].rest_local;
  EXPECT_LT(glm::length(at(w, toe) - glm::vec3(expected[3])), 1e-4f);
  expectBonesKeepTheirLength(c, w, "lifted fore leg");
}

}  // namespace
}  // namespace stirrup::rig
