// The standing test humanoid: layout, names per convention, proportions (Winter 2009, Fig. 4.1: each
// length a fraction of the height, worked out below for 170 cm), rest poses, the spine's rest curve,
// the skinned mesh and its texture.
#include "rig/characters/standing_humanoid.h"

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/error.h"

namespace stirrup::rig {
namespace {

constexpr float kRadToDeg = 180.0f / std::numbers::pi_v<float>;

// Skeleton-only checks build with a coarse grid (the skeleton does not depend on it).
StandingHumanoidParams coarse(HumanoidNames names = HumanoidNames::Mixamo) {
  StandingHumanoidParams p = humanoidConventionDefaults(names);
  p.cell = 4.0f;
  return p;
}

glm::vec3 at(const StandingHumanoid& h, const std::string& name) { return h.character.skeleton.restPosition(h.character.skeleton.require(name)); }
std::string parentName(const StandingHumanoid& h, const std::string& name) {
  const Skeleton& s = h.character.skeleton;
  const int p = s.joints[s.require(name)].parent;
  return p < 0 ? "" : s.joints[p].name;
}
int countBone(const StandingHumanoid& h, HumanoidBone bone) {
  int n = 0;
  for (const HumanoidJointLabel& l : h.labels) n += l.bone == bone;
  return n;
}
// Joints strictly between `from` and its ancestor `to`, walking up.
int jointsBetween(const StandingHumanoid& h, const std::string& from, const std::string& to) {
  const Skeleton& s = h.character.skeleton;
  int n = 0;
  for (int j = s.joints[s.require(from)].parent; j >= 0; j = s.joints[j].parent) {
    if (s.joints[j].name == to) return n;
    ++n;
  }
  return -1;
}
float degreesBelowHorizontal(glm::vec3 d) { return std::asin(-glm::normalize(d).y) * kRadToDeg; }

// Default layout, Mixamo names: every joint and its parent, counted by hand from the convention
// (pelvis, 3 spine, neck, head, head end; per side a clavicle, upper arm, forearm, hand at the wrist,
// a hand joint in the palm, thumb 1-3 + end, index 1-3 + end, thigh, shin, foot, toe, toe end).
TEST(StandingHumanoid, MixamoNamesAndHierarchy) {
  const StandingHumanoid h = buildStandingHumanoid(coarse(HumanoidNames::Mixamo));
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"mixamorig:Hips", ""},
      {"mixamorig:Spine", "mixamorig:Hips"},
      {"mixamorig:Spine1", "mixamorig:Spine"},
      {"mixamorig:Spine2", "mixamorig:Spine1"},
      {"mixamorig:Neck", "mixamorig:Spine2"},
      {"mixamorig:Head", "mixamorig:Neck"},
      {"mixamorig:HeadTop_End", "mixamorig:Head"},
      {"mixamorig:LeftShoulder", "mixamorig:Spine2"},
      {"mixamorig:LeftArm", "mixamorig:LeftShoulder"},
      {"mixamorig:LeftForeArm", "mixamorig:LeftArm"},
      {"mixamorig:LeftHand", "mixamorig:LeftForeArm"},
      {"mixamorig:LeftInHandMiddle", "mixamorig:LeftHand"},
      {"mixamorig:LeftHandThumb1", "mixamorig:LeftHand"},
      {"mixamorig:LeftHandThumb2", "mixamorig:LeftHandThumb1"},
      {"mixamorig:LeftHandThumb3", "mixamorig:LeftHandThumb2"},
      {"mixamorig:LeftHandThumb4", "mixamorig:LeftHandThumb3"},
      {"mixamorig:LeftHandIndex1", "mixamorig:LeftInHandMiddle"},
      {"mixamorig:LeftHandIndex2", "mixamorig:LeftHandIndex1"},
      {"mixamorig:LeftHandIndex3", "mixamorig:LeftHandIndex2"},
      {"mixamorig:LeftHandIndex4", "mixamorig:LeftHandIndex3"},
      {"mixamorig:RightShoulder", "mixamorig:Spine2"},
      {"mixamorig:RightArm", "mixamorig:RightShoulder"},
      {"mixamorig:RightHand", "mixamorig:RightForeArm"},
      {"mixamorig:LeftUpLeg", "mixamorig:Hips"},
      {"mixamorig:LeftLeg", "mixamorig:LeftUpLeg"},
      {"mixamorig:LeftFoot", "mixamorig:LeftLeg"},
      {"mixamorig:LeftToeBase", "mixamorig:LeftFoot"},
      {"mixamorig:LeftToe_End", "mixamorig:LeftToeBase"},
      {"mixamorig:RightUpLeg", "mixamorig:Hips"},
      {"mixamorig:RightToe_End", "mixamorig:RightToeBase"}};
  for (const auto& [name, parent] : expected) {
    ASSERT_GE(h.character.skeleton.find(name), 0) << name;
    EXPECT_EQ(parentName(h, name), parent) << name;
  }
  EXPECT_EQ(h.character.skeleton.size(), 43u);  // 7 trunk + 2 x 13 arm + 2 x 5 leg
  for (const Joint& j : h.character.skeleton.joints) EXPECT_EQ(j.name.rfind("mixamorig:", 0), 0u) << j.name;
  EXPECT_TRUE(h.character.roles.empty());  // a stranger's file: no stirrup roles
}

// Rigify's generated deform bones, with its layout: limbs in two halves, two neck bones (spine.004,
// spine.005, head spine.006, as the human meta-rig has them), and the limbs detached from the trunk as
// Blender's deform-only export leaves them.
TEST(StandingHumanoid, RigifyNamesAndLayout) {
  const StandingHumanoid h = buildStandingHumanoid(coarse(HumanoidNames::Rigify));
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"DEF-spine", ""},
      {"DEF-spine.001", "DEF-spine"},
      {"DEF-spine.002", "DEF-spine.001"},
      {"DEF-spine.003", "DEF-spine.002"},
      {"DEF-spine.004", "DEF-spine.003"},
      {"DEF-spine.005", "DEF-spine.004"},
      {"DEF-spine.006", "DEF-spine.005"},
      {"DEF-shoulder.L", ""},
      {"DEF-upper_arm.L", ""},
      {"DEF-upper_arm.L.001", "DEF-upper_arm.L"},
      {"DEF-forearm.L", "DEF-upper_arm.L.001"},
      {"DEF-forearm.L.001", "DEF-forearm.L"},
      {"DEF-hand.L", "DEF-forearm.L.001"},
      {"DEF-palm.02.L", "DEF-hand.L"},
      {"DEF-thumb.01.L", "DEF-hand.L"},
      {"DEF-f_index.01.L", "DEF-palm.02.L"},
      {"DEF-f_index.03.L", "DEF-f_index.02.L"},
      {"DEF-thigh.L", ""},
      {"DEF-thigh.L.001", "DEF-thigh.L"},
      {"DEF-shin.L", "DEF-thigh.L.001"},
      {"DEF-shin.L.001", "DEF-shin.L"},
      {"DEF-foot.L", "DEF-shin.L.001"},
      {"DEF-toe.L", "DEF-foot.L"},
      {"DEF-upper_arm.R.001", "DEF-upper_arm.R"},
      {"DEF-toe.R", "DEF-foot.R"}};
  for (const auto& [name, parent] : expected) {
    ASSERT_GE(h.character.skeleton.find(name), 0) << name;
    EXPECT_EQ(parentName(h, name), parent) << name;
  }
  EXPECT_EQ(h.character.skeleton.size(), 45u);  // 7 trunk + 2 x 13 arm (two halves each) + 2 x 6 leg
  // The ".001" half starts halfway along the limb: the upper arm is 0.186 x 170 = 31.62 cm.
  EXPECT_NEAR(glm::length(at(h, "DEF-upper_arm.L.001") - at(h, "DEF-upper_arm.L")), 15.81f, 0.01f);
  EXPECT_NEAR(glm::length(at(h, "DEF-forearm.L") - at(h, "DEF-upper_arm.L")), 31.62f, 0.01f);
}

TEST(StandingHumanoid, UnrealVrmHumanIkAndMeaninglessNames) {
  {
    const StandingHumanoid h = buildStandingHumanoid(coarse(HumanoidNames::Unreal));
    for (const auto& [name, parent] : std::vector<std::pair<std::string, std::string>>{
             {"root", ""}, {"pelvis", "root"}, {"spine_01", "pelvis"}, {"spine_03", "spine_02"}, {"neck_01", "spine_03"},
             {"head", "neck_01"}, {"clavicle_l", "spine_03"}, {"upperarm_l", "clavicle_l"}, {"lowerarm_l", "upperarm_l"},
             {"hand_l", "lowerarm_l"}, {"thumb_01_l", "hand_l"}, {"index_01_l", "middle_metacarpal_l"},
             {"thigh_r", "pelvis"}, {"calf_r", "thigh_r"}, {"foot_r", "calf_r"}, {"ball_r", "foot_r"}}) {
      ASSERT_GE(h.character.skeleton.find(name), 0) << name;
      EXPECT_EQ(parentName(h, name), parent) << name;
    }
    EXPECT_EQ(at(h, "root"), glm::vec3(0.0f));  // on the ground
  }
  {
    const StandingHumanoid h = buildStandingHumanoid(coarse(HumanoidNames::Vrm));
    for (const auto& [name, parent] : std::vector<std::pair<std::string, std::string>>{
             {"Root", ""}, {"J_Bip_C_Hips", "Root"}, {"J_Bip_C_Spine", "J_Bip_C_Hips"}, {"J_Bip_C_Chest", "J_Bip_C_Spine"},
             {"J_Bip_C_UpperChest", "J_Bip_C_Chest"}, {"J_Bip_C_Neck", "J_Bip_C_UpperChest"}, {"J_Bip_C_Head", "J_Bip_C_Neck"},
             {"J_Bip_L_Shoulder", "J_Bip_C_UpperChest"}, {"J_Bip_L_UpperArm", "J_Bip_L_Shoulder"},
             {"J_Bip_L_LowerArm", "J_Bip_L_UpperArm"}, {"J_Bip_L_Hand", "J_Bip_L_LowerArm"},
             {"J_Bip_L_UpperLeg", "J_Bip_C_Hips"}, {"J_Bip_L_ToeBase", "J_Bip_L_Foot"}}) {
      ASSERT_GE(h.character.skeleton.find(name), 0) << name;
      EXPECT_EQ(parentName(h, name), parent) << name;
    }
    for (const glm::mat3& a : h.rest_axes) EXPECT_EQ(a, glm::mat3(1.0f));  // VRoid writes no rest rotations
  }
  {
    const StandingHumanoid h = buildStandingHumanoid(coarse(HumanoidNames::HumanIK));
    for (const auto& [name, parent] : std::vector<std::pair<std::string, std::string>>{
             {"Hips", ""}, {"Spine", "Hips"}, {"Spine1", "Spine"}, {"Spine2", "Spine1"}, {"Neck", "Spine2"},
             {"LeftShoulder", "Spine2"}, {"LeftArm", "LeftShoulder"}, {"LeftForeArm", "LeftArm"}, {"LeftHand", "LeftForeArm"},
             {"LeftUpLeg", "Hips"}, {"LeftLeg", "LeftUpLeg"}, {"LeftFoot", "LeftLeg"}, {"LeftToeBase", "LeftFoot"}}) {
      ASSERT_GE(h.character.skeleton.find(name), 0) << name;
      EXPECT_EQ(parentName(h, name), parent) << name;
    }
  }
  {
    const StandingHumanoid h = buildStandingHumanoid(coarse(HumanoidNames::None));
    const Skeleton& s = h.character.skeleton;
    EXPECT_EQ(s.joints[0].name, "Bone");
    EXPECT_EQ(s.joints[1].name, "Bone.001");
    EXPECT_EQ(s.joints[35].name, "Bone.035");
    EXPECT_EQ(s.size(), 36u);
  }
}

// --spine-joints N: N joints on the path from the pelvis to the first neck joint.
TEST(StandingHumanoid, SpineJointsBetweenPelvisAndNeck) {
  for (int n = 1; n <= 8; ++n) {
    StandingHumanoidParams p = coarse(HumanoidNames::HumanIK);
    p.spine_joints = n;
    const StandingHumanoid h = buildStandingHumanoid(p);
    EXPECT_EQ(jointsBetween(h, "Neck", "Hips"), n);
    EXPECT_EQ(countBone(h, HumanoidBone::Spine), n);
  }
  StandingHumanoidParams p = coarse(HumanoidNames::Rigify);
  p.spine_joints = 6;
  p.neck_joints = 1;
  const StandingHumanoid h = buildStandingHumanoid(p);
  EXPECT_EQ(jointsBetween(h, "DEF-spine.007", "DEF-spine"), 6);  // .001 .. .006, then the neck .007
  EXPECT_EQ(parentName(h, "DEF-spine.008"), "DEF-spine.007");   // the head
  p = coarse(HumanoidNames::Mixamo);
  p.spine_joints = 6;
  const StandingHumanoid m = buildStandingHumanoid(p);
  EXPECT_EQ(parentName(m, "mixamorig:Neck"), "mixamorig:Spine5");
  EXPECT_EQ(jointsBetween(m, "mixamorig:Neck", "mixamorig:Hips"), 6);
}

// The spine lies on a curve, not the pelvis-neck chord: z offset from the chord at u = i / (N + 1) is
// 0.27 x 170 x u (1 - u) (0.4 - u) cm. For N = 3 (u = 1/4, 1/2, 3/4): +1.291, -1.148, -3.012; for N = 6
// (u = 1/7 .. 6/7): +1.445, +1.071, -0.321, -1.927, -2.944, -2.569: forward over the lumbar spine
// (lordosis), back over the thoracic (kyphosis). Pelvis (y 93.5, z -1.02), neck base (y 141.95, z -3.4).
TEST(StandingHumanoid, SpineRestCurveHasLordosisAndKyphosis) {
  const std::map<int, std::vector<float>> offsets = {{3, {1.291f, -1.148f, -3.012f}},
                                                     {6, {1.445f, 1.071f, -0.321f, -1.927f, -2.944f, -2.569f}},
                                                     {2, {0.680f, -2.720f}}};
  for (const auto& [n, expected] : offsets) {
    StandingHumanoidParams p = coarse(HumanoidNames::HumanIK);
    p.spine_joints = n;
    const StandingHumanoid h = buildStandingHumanoid(p);
    const glm::vec3 pelvis = at(h, "Hips"), neck = at(h, "Neck");
    EXPECT_NEAR(pelvis.y, 93.5f, 0.01f);
    EXPECT_NEAR(pelvis.z, -1.02f, 0.01f);
    EXPECT_NEAR(neck.y, 141.95f, 0.01f);
    EXPECT_NEAR(neck.z, -3.4f, 0.01f);
    for (int i = 0; i < n; ++i) {
      const glm::vec3 j = at(h, i == 0 ? "Spine" : "Spine" + std::to_string(i));
      const float u = static_cast<float>(i + 1) / static_cast<float>(n + 1);
      EXPECT_NEAR(j.y, pelvis.y + u * (neck.y - pelvis.y), 0.01f);
      EXPECT_NEAR(j.z - (pelvis.z + u * (neck.z - pelvis.z)), expected[i], 0.002f) << "N " << n << " joint " << i;
    }
  }
}

TEST(StandingHumanoid, NeckJoints) {
  StandingHumanoidParams p = coarse(HumanoidNames::Mixamo);
  p.neck_joints = 2;
  const StandingHumanoid h = buildStandingHumanoid(p);
  EXPECT_EQ(parentName(h, "mixamorig:Neck1"), "mixamorig:Neck");
  EXPECT_EQ(parentName(h, "mixamorig:Head"), "mixamorig:Neck1");
  EXPECT_EQ(countBone(h, HumanoidBone::Neck), 2);
  // Neck base 0.835 x 170 = 141.95 cm, head joint 0.90 x 170 = 153 cm: the second neck joint halfway.
  EXPECT_NEAR(at(h, "mixamorig:Neck1").y, 147.475f, 0.01f);
  EXPECT_NEAR(at(h, "mixamorig:Head").y, 153.0f, 0.01f);
}

// Segment lengths from Winter (2009) Fig. 4.1 at 170 cm: upper arm 0.186 H = 31.62, forearm 0.146 H =
// 24.82, thigh 0.245 H = 41.65, shin 0.246 H = 41.82; ankle 0.039 H = 6.63 above the ground.
TEST(StandingHumanoid, BoneLengthsFollowTheHeight) {
  const StandingHumanoid h = buildStandingHumanoid(coarse(HumanoidNames::HumanIK));
  EXPECT_NEAR(glm::length(at(h, "LeftForeArm") - at(h, "LeftArm")), 31.62f, 0.01f);
  EXPECT_NEAR(glm::length(at(h, "LeftHand") - at(h, "LeftForeArm")), 24.82f, 0.01f);
  EXPECT_NEAR(glm::length(at(h, "LeftLeg") - at(h, "LeftUpLeg")), 41.65f, 0.02f);
  EXPECT_NEAR(glm::length(at(h, "LeftFoot") - at(h, "LeftLeg")), 41.82f, 0.02f);
  EXPECT_NEAR(at(h, "LeftFoot").y, 6.63f, 0.01f);
  // Shoulder joints 0.205 H = 34.85 cm apart, 0.798 H = 135.66 cm up; hips 0.105 H = 17.85 apart.
  EXPECT_NEAR(at(h, "LeftArm").x - at(h, "RightArm").x, 34.85f, 0.01f);
  EXPECT_NEAR(at(h, "LeftArm").y, 135.66f, 0.01f);
  EXPECT_NEAR(at(h, "LeftUpLeg").x - at(h, "RightUpLeg").x, 17.85f, 0.01f);
  // Half the height halves every length.
  StandingHumanoidParams p = coarse(HumanoidNames::HumanIK);
  p.height = 200.0f;
  const StandingHumanoid tall = buildStandingHumanoid(p);
  EXPECT_NEAR(glm::length(at(tall, "LeftForeArm") - at(tall, "LeftArm")), 37.2f, 0.01f);  // 0.186 x 200
}

// Shared wrist/hand: the hand joint at the wrist is the whole hand, no joint in the palm.
TEST(StandingHumanoid, SharedWristHandHasNoSeparateHandJoint) {
  StandingHumanoidParams p = coarse(HumanoidNames::Mixamo);
  const StandingHumanoid separate = buildStandingHumanoid(p);
  p.separate_hand = false;
  const StandingHumanoid shared = buildStandingHumanoid(p);
  EXPECT_EQ(countBone(separate, HumanoidBone::Palm), 2);
  EXPECT_EQ(countBone(shared, HumanoidBone::Palm), 0);
  EXPECT_EQ(shared.character.skeleton.find("mixamorig:LeftInHandMiddle"), -1);
  EXPECT_EQ(shared.character.skeleton.size(), separate.character.skeleton.size() - 2);
  EXPECT_EQ(parentName(shared, "mixamorig:LeftHandIndex1"), "mixamorig:LeftHand");
  // In both the hand joint is at the wrist, 24.82 cm past the elbow; the separate one a quarter of
  // the hand (0.108 x 170 / 4 = 4.59 cm) further on.
  EXPECT_NEAR(glm::length(at(shared, "mixamorig:LeftHand") - at(shared, "mixamorig:LeftForeArm")), 24.82f, 0.01f);
  EXPECT_NEAR(glm::length(at(separate, "mixamorig:LeftInHandMiddle") - at(separate, "mixamorig:LeftHand")), 4.59f, 0.01f);
}

TEST(StandingHumanoid, OptionalJoints) {
  StandingHumanoidParams p = coarse(HumanoidNames::Unreal);
  p.toes = false;
  p.clavicles = false;
  p.fingers = false;
  p.ground_root = false;
  const StandingHumanoid h = buildStandingHumanoid(p);
  EXPECT_EQ(h.character.skeleton.find("ball_l"), -1);
  EXPECT_EQ(h.character.skeleton.find("clavicle_l"), -1);
  EXPECT_EQ(h.character.skeleton.find("thumb_01_l"), -1);
  EXPECT_EQ(h.character.skeleton.find("root"), -1);
  EXPECT_EQ(parentName(h, "upperarm_l"), "spine_03");
  EXPECT_EQ(parentName(h, "pelvis"), "");
  // pelvis, 3 spine, neck, head; per side upper arm, lower arm, hand, palm, thigh, calf, foot.
  EXPECT_EQ(h.character.skeleton.size(), 20u);
  p.split_limbs = true;
  const StandingHumanoid split = buildStandingHumanoid(p);
  EXPECT_EQ(parentName(split, "upperarm_twist_01_l"), "upperarm_l");
  EXPECT_EQ(parentName(split, "lowerarm_l"), "upperarm_twist_01_l");
  EXPECT_EQ(parentName(split, "calf_twist_01_r"), "calf_r");
  EXPECT_EQ(split.character.skeleton.size(), 28u);
}

// Rest poses from the joints: T, arms horizontal; A, 45 degrees down; relaxed, 10 degrees out from the
// sides with the forearm bent 15 degrees forward.
TEST(StandingHumanoid, RestPoses) {
  for (HumanoidRestPose pose : {HumanoidRestPose::T, HumanoidRestPose::A, HumanoidRestPose::Relaxed}) {
    StandingHumanoidParams p = coarse(HumanoidNames::HumanIK);
    p.pose = pose;
    const StandingHumanoid h = buildStandingHumanoid(p);
    const glm::vec3 upper = at(h, "LeftForeArm") - at(h, "LeftArm");
    const glm::vec3 fore = at(h, "LeftHand") - at(h, "LeftForeArm");
    const glm::vec3 right_upper = at(h, "RightForeArm") - at(h, "RightArm");
    EXPECT_GT(upper.x, 0.0f);  // the left arm reaches out to +X
    EXPECT_LT(right_upper.x, 0.0f);
    const float down = degreesBelowHorizontal(upper);
    const float bend = std::acos(glm::dot(glm::normalize(upper), glm::normalize(fore))) * kRadToDeg;
    switch (pose) {
      case HumanoidRestPose::T:
        EXPECT_NEAR(down, 0.0f, 0.01f);
        EXPECT_NEAR(bend, 0.0f, 0.05f);
        break;
      case HumanoidRestPose::A:
        EXPECT_NEAR(down, 45.0f, 0.01f);
        EXPECT_NEAR(bend, 0.0f, 0.05f);
        break;
      case HumanoidRestPose::Relaxed:
        EXPECT_NEAR(down, 80.0f, 0.01f);
        EXPECT_NEAR(bend, 15.0f, 0.05f);
        EXPECT_GT(fore.z, 0.0f);  // the forearm comes forward
        break;
    }
    EXPECT_NEAR(degreesBelowHorizontal(right_upper), down, 0.01f);  // symmetric
  }
}

// Bone frames (Blender's way): +Y along the bone to its tail, +Z toward the front.
TEST(StandingHumanoid, BoneAlignedRestAxes) {
  StandingHumanoidParams p = coarse(HumanoidNames::HumanIK);
  p.pose = HumanoidRestPose::T;
  const StandingHumanoid h = buildStandingHumanoid(p);
  const Skeleton& s = h.character.skeleton;
  const auto axes = [&](const std::string& n) { return h.rest_axes[s.require(n)]; };
  const auto expectNear = [](glm::vec3 a, glm::vec3 b, const std::string& what) {
    EXPECT_LT(glm::length(a - b), 1e-3f) << what << ": " << a.x << " " << a.y << " " << a.z;
  };
  expectNear(axes("LeftArm")[1], {1, 0, 0}, "left upper arm +Y");   // T pose: out to the left
  expectNear(axes("LeftArm")[2], {0, 0, 1}, "left upper arm +Z");
  expectNear(axes("RightArm")[1], {-1, 0, 0}, "right upper arm +Y");
  expectNear(axes("Head")[1], {0, 1, 0}, "head +Y");
  expectNear(axes("Head")[2], {0, 0, 1}, "head +Z");
  EXPECT_GT(axes("LeftToeBase")[1].z, 0.99f);  // the toes point forward, +Z rolled up
  EXPECT_GT(axes("LeftToeBase")[2].y, 0.99f);
  EXPECT_LT(axes("LeftUpLeg")[1].y, -0.999f);  // the thigh points down
  for (std::size_t j = 0; j < s.size(); ++j) {
    const glm::mat3& a = h.rest_axes[j];
    EXPECT_NEAR(glm::determinant(a), 1.0f, 1e-4f);  // a rotation
  }
  // The spine's +Y points at the next spine joint.
  const glm::vec3 d = glm::normalize(at(h, "Spine1") - at(h, "Spine"));
  expectNear(axes("Spine")[1], d, "spine +Y");
}

TEST(StandingHumanoid, StandsOnTheGroundFacingPlusZ) {
  const StandingHumanoid h = buildStandingHumanoid(humanoidConventionDefaults(HumanoidNames::Mixamo));
  const SkinnedMesh& m = h.character.mesh;
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& v : m.positions) {
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  EXPECT_NEAR(lo.y, 0.0f, 0.25f);    // soles on the ground
  EXPECT_NEAR(hi.y, 170.0f, 0.5f);   // crown at the height
  // T pose: finger tips at 17.425 + 31.62 + 24.82 + 18.36 = 92.2 cm out.
  EXPECT_NEAR(hi.x, 92.2f, 1.5f);
  EXPECT_NEAR(lo.x, -92.2f, 1.5f);
  // The toes are the front-most part (+Z); above the shoulders the back-most is hair (the ponytail).
  std::size_t front = 0;
  for (std::size_t v = 0; v < m.vertexCount(); ++v)
    if (m.positions[v].z > m.positions[front].z) front = v;
  EXPECT_LT(m.positions[front].y, 8.0f);
  std::uint32_t back = 0;
  bool back_is_hair = false;
  float back_z = 1e9f;
  for (std::size_t i = 0; i < m.indices.size(); ++i) {
    const glm::vec3 pos = m.positions[m.indices[i]];
    if (pos.y > 140.0f && pos.z < back_z) {
      back_z = pos.z;
      back = m.indices[i];
      back_is_hair = i >= h.hair_first_index;
    }
  }
  EXPECT_TRUE(back_is_hair) << m.positions[back].y;
  EXPECT_LT(back_z, -10.0f);
  // The nose is the front-most point of the head, on the midline.
  std::size_t nose = 0;
  float nose_z = -1e9f;
  for (std::size_t v = 0; v < m.vertexCount(); ++v)
    if (m.positions[v].y > 150.0f && m.positions[v].z > nose_z) {
      nose_z = m.positions[v].z;
      nose = v;
    }
  EXPECT_LT(std::abs(m.positions[nose].x), 1.0f);
  EXPECT_NEAR(m.positions[nose].y, 0.936f * 170.0f - 4.0f, 2.0f);  // below the eyes (0.936 H)
}

TEST(StandingHumanoid, SkinnedToItsJoints) {
  StandingHumanoidParams p = humanoidConventionDefaults(HumanoidNames::Mixamo);
  p.spine_joints = 6;
  p.cell = 2.0f;
  const StandingHumanoid h = buildStandingHumanoid(p);
  const Skeleton& s = h.character.skeleton;
  const SkinnedMesh& m = h.character.mesh;
  ASSERT_EQ(m.weights.size(), m.vertexCount());
  std::vector<int> dominant(s.size(), 0);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    float sum = 0.0f;
    int best = 0;
    for (int k = 0; k < kMaxInfluences; ++k) {
      sum += m.weights[v][k];
      if (m.weights[v][k] > 0.0f) {
        ASSERT_LT(m.joints[v][k], s.size());
      }
      if (m.weights[v][k] > m.weights[v][best]) best = k;
    }
    ASSERT_NEAR(sum, 1.0f, 1e-4f);
    ++dominant[m.joints[v][best]];
    // Left and right never mix: a vertex out past the shoulders belongs to its own arm.
    const glm::vec3 pos = m.positions[v];
    if (std::abs(pos.x) > 30.0f) {
      for (int k = 0; k < kMaxInfluences; ++k) {
        if (m.weights[v][k] > 0.0f) {
          EXPECT_GE(s.restPosition(m.joints[v][k]).x * pos.x, 0.0f);  // midline joints allowed
        }
      }
    }
  }
  // Every joint that carries flesh leads some vertices; the unskinned leaves (ends) none.
  for (std::size_t j = 0; j < s.size(); ++j) {
    const HumanoidBone b = h.labels[j].bone;
    const bool end = b == HumanoidBone::HeadEnd || b == HumanoidBone::ToeEnd ||
                     ((b == HumanoidBone::Thumb || b == HumanoidBone::Index) && h.labels[j].index == 3);
    if (end) {
      EXPECT_EQ(dominant[j], 0) << s.joints[j].name;
    } else {
      EXPECT_GT(dominant[j], 3) << s.joints[j].name;
    }
  }
}

// The texture: regions in tiles, seed 0's palette (jacket 28,48,110; breeches 214,200,160; boots
// 58,34,21; skin 230,184,150; hair 60,38,20), each vertex's UV in its region's tile.
TEST(StandingHumanoid, TextureAndCoordinates) {
  StandingHumanoidParams p = humanoidConventionDefaults(HumanoidNames::Mixamo);
  p.cell = 2.0f;
  const StandingHumanoid h = buildStandingHumanoid(p);
  const RgbImage& t = h.texture;
  ASSERT_EQ(t.width, 512);
  ASSERT_EQ(t.height, 256);
  ASSERT_EQ(t.rgb.size(), 512u * 256u * 3u);
  EXPECT_EQ(t.at(5, 5), glm::u8vec3(28, 48, 110));          // jacket tile (0,0), between the tartan bands
  EXPECT_EQ(t.at(128 + 3, 5), glm::u8vec3(214, 200, 160));  // breeches (1,0), between pinstripes
  EXPECT_EQ(t.at(256 + 5, 5), glm::u8vec3(58, 34, 21));     // boots (2,0)
  EXPECT_EQ(t.at(384 + 1, 1), glm::u8vec3(230, 184, 150));  // skin (3,0)
  EXPECT_EQ(t.at(128 + 3, 128 + 5), glm::u8vec3(60, 38, 20)); // hair (1,1)
  EXPECT_NE(t.at(5, 1), t.at(5, 5));                        // the jacket's pattern
  const SkinnedMesh& m = h.character.mesh;
  ASSERT_EQ(h.uvs.size(), m.vertexCount());
  const auto tile = [&](std::size_t v) {
    const glm::vec2 px = h.uvs[v] * glm::vec2(512.0f, 256.0f);
    return static_cast<HumanoidRegion>(static_cast<int>(px.x) / 128 + 4 * (static_cast<int>(px.y) / 128));
  };
  std::map<HumanoidRegion, int> count;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    ASSERT_GE(h.uvs[v].x, 0.0f);
    ASSERT_LE(h.uvs[v].x, 1.0f);
    ASSERT_GE(h.uvs[v].y, 0.0f);
    ASSERT_LE(h.uvs[v].y, 1.0f);
    ++count[tile(v)];
  }
  EXPECT_EQ(count[HumanoidRegion::Unused1] + count[HumanoidRegion::Unused2], 0);
  for (HumanoidRegion r : {HumanoidRegion::Jacket, HumanoidRegion::Breeches, HumanoidRegion::Boots, HumanoidRegion::Skin,
                           HumanoidRegion::Face, HumanoidRegion::Hair})
    EXPECT_GT(count[r], 50) << static_cast<int>(r);
  // Where things are: chest front in the jacket, shins in the boots, thighs in the breeches, the
  // front of the face (triangles facing forward) in the face tile, the hair primitive in the hair tile.
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const glm::vec3 pos = m.positions[v];
    if (std::abs(pos.x) < 5.0f && pos.y > 115.0f && pos.y < 125.0f && pos.z > 8.0f) {
      EXPECT_EQ(tile(v), HumanoidRegion::Jacket);
    }
    if (pos.y > 12.0f && pos.y < 30.0f) {
      EXPECT_EQ(tile(v), HumanoidRegion::Boots);
    }
    if (pos.y > 60.0f && pos.y < 80.0f) {
      EXPECT_EQ(tile(v), HumanoidRegion::Breeches);
    }
  }
  int face_triangles = 0;
  for (std::size_t i = 0; i < h.hair_first_index; i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], c = m.positions[m.indices[i + 2]];
    const glm::vec3 centre = (a + b + c) / 3.0f, n = glm::normalize(glm::cross(b - a, c - a));
    if (std::abs(centre.x) < 3.0f && centre.y > 150.0f && centre.y < 160.0f && n.z > 0.9f) {
      ++face_triangles;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(tile(m.indices[i + k]), HumanoidRegion::Face);
    }
  }
  EXPECT_GT(face_triangles, 5);
  for (std::size_t i = h.hair_first_index; i < m.indices.size(); ++i) EXPECT_EQ(tile(m.indices[i]), HumanoidRegion::Hair);
  for (std::size_t i = 0; i < h.hair_first_index; ++i) EXPECT_NE(tile(m.indices[i]), HumanoidRegion::Hair);
  EXPECT_GT(h.hair_first_index, 0u);
  EXPECT_LT(h.hair_first_index, m.indices.size());
}

TEST(StandingHumanoid, SeedVariesProportionsAndColoursReproducibly) {
  StandingHumanoidParams p = coarse(HumanoidNames::HumanIK);
  const StandingHumanoid base = buildStandingHumanoid(p);
  p.seed = 7;
  const StandingHumanoid a = buildStandingHumanoid(p), b = buildStandingHumanoid(p);
  EXPECT_EQ(a.character.mesh.positions, b.character.mesh.positions);
  EXPECT_EQ(a.texture.rgb, b.texture.rgb);
  const float upper = glm::length(at(a, "LeftForeArm") - at(a, "LeftArm"));
  EXPECT_NE(upper, 31.62f);
  EXPECT_NEAR(upper, 31.62f, 0.04f * 31.62f + 0.01f);
  EXPECT_NEAR(a.character.skeleton.restPosition(0).y, base.character.skeleton.restPosition(0).y, 6.0f);
  EXPECT_NE(a.character.mesh.positions, base.character.mesh.positions);
}

TEST(StandingHumanoid, ParametersOutOfRangeAreErrors) {
  for (int n : {0, 9}) {
    StandingHumanoidParams p = coarse();
    p.spine_joints = n;
    EXPECT_THROW(buildStandingHumanoid(p), InputError);
  }
  StandingHumanoidParams p = coarse();
  p.neck_joints = 3;
  EXPECT_THROW(buildStandingHumanoid(p), InputError);
  p = coarse();
  p.height = 20.0f;
  EXPECT_THROW(buildStandingHumanoid(p), InputError);
}

}  // namespace
}  // namespace stirrup::rig
