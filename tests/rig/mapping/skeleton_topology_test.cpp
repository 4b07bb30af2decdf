// Roles from a skeleton's shape alone, on stick figures laid out by hand (centimetres, +Y up, facing
// +Z, left at +X): mirror-image limb pairs and where they branch, the biped's roles along them, the
// spine joint the shoulders hang from, and what is said when a skeleton is not a biped. A horse shaped
// like Blender's Rigify horse (tests/rig/io/stick_horse.h) maps to the joints its anatomy gives
// whatever its mesh weights, with its leg bones split in segments or not, and a horse with three legs
// is an error naming the leg without a partner.
#include "rig/mapping/skeleton_topology.h"

#include <cmath>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"
#include "tests/rig/io/stick_horse.h"

namespace stirrup::rig {
namespace {

using stirrup::test::errorOf;

struct Figure {
  MappingSkeleton s;
  int add(const std::string& name, int parent, glm::dvec3 at) {
    s.names.push_back(name);
    s.parent.push_back(parent);
    s.position.push_back(at);
    s.weighted.push_back(1);
    s.hung.push_back(0);
    return static_cast<int>(s.names.size()) - 1;
  }
  MappingSkeleton done() {
    s.file = "figure.glb";
    // The mesh: a point at every joint, the crown and the soles.
    for (const glm::dvec3& p : s.position) s.vertices.push_back(p), s.vertex_joint.push_back(0);
    s.vertices.push_back({0, 170, 0});
    s.vertices.push_back({0, 0, 0});
    s.vertex_joint.push_back(0);
    s.vertex_joint.push_back(0);
    s.finish();
    return s;
  }
};

// A 170 cm figure in a T pose with Winter's segment lengths (rounded): upper arm 32, forearm 25, thigh
// 42, shin 42 cm; a clavicle, a palm joint carrying a three-joint finger, a thumb, and toes.
Figure biped(bool clavicles = true) {
  Figure f;
  const int pelvis = f.add("pelvis", -1, {0, 96, 0});
  const int spine = f.add("spine", pelvis, {0, 115, 0});
  const int chest = f.add("chest", spine, {0, 132, 0});
  const int neck = f.add("neck", chest, {0, 142, 0});
  f.add("head", neck, {0, 153, 0});
  for (const double side : {1.0, -1.0}) {
    const std::string n = side > 0 ? "L" : "R";
    const int clavicle = clavicles ? f.add("clavicle" + n, chest, {side * 3, 136, 0}) : chest;
    const int shoulder = f.add("shoulder" + n, clavicle, {side * 17, 136, 0});
    const int elbow = f.add("elbow" + n, shoulder, {side * 49, 136, 0});
    const int wrist = f.add("wrist" + n, elbow, {side * 74, 136, 0});
    const int palm = f.add("palm" + n, wrist, {side * 79, 136, 0});
    int k = f.add("finger1" + n, palm, {side * 83, 136, 0});
    k = f.add("finger2" + n, k, {side * 87, 136, 0});
    f.add("finger3" + n, k, {side * 90, 136, 0});
    k = f.add("thumb1" + n, wrist, {side * 76, 136, 2});
    k = f.add("thumb2" + n, k, {side * 78, 136, 4});
    f.add("thumb3" + n, k, {side * 80, 136, 6});
    const int hip = f.add("hip" + n, pelvis, {side * 9, 92, 0});
    const int knee = f.add("knee" + n, hip, {side * 9, 50, 1});
    const int ankle = f.add("ankle" + n, knee, {side * 9, 7, 0});
    f.add("ball" + n, ankle, {side * 9, 2, 14});
  }
  return f;
}

int joint(const MappingSkeleton& s, const std::string& name) { return s.find(name); }

TEST(SkeletonTopology, FindsTheTwoMirrorImageLimbPairsAndWhereTheyBranch) {
  const MappingSkeleton s = biped().done();
  const std::vector<LimbPair> pairs = mirroredLimbs(s);
  ASSERT_EQ(pairs.size(), 2u);
  // Longest first: the legs (hip to toes, 91 cm) before the arms (clavicle to finger tip, 87 cm).
  const LimbPair& legs = pairs[0];
  const LimbPair& arms = pairs[1];
  EXPECT_NEAR(legs.reach, std::sqrt(90.0 * 90.0 + 14.0 * 14.0), 1e-9);
  EXPECT_NEAR(arms.reach, 87.0, 1e-9);
  EXPECT_EQ(legs.branch, joint(s, "pelvis"));
  EXPECT_EQ(arms.branch, joint(s, "chest"));
  EXPECT_EQ(std::min(legs.a, legs.b), joint(s, "hipL"));
  EXPECT_EQ(std::min(arms.a, arms.b), joint(s, "clavicleL"));
  // The chain follows the child reaching farthest: past the palm into the finger, not the thumb.
  const std::vector<int> chain = limbChain(s, joint(s, "clavicleL"));
  std::vector<std::string> names;
  for (int j : chain) names.push_back(s.names[j]);
  EXPECT_EQ(names, (std::vector<std::string>{"clavicleL", "shoulderL", "elbowL", "wristL", "palmL", "finger1L", "finger2L", "finger3L"}));
}

TEST(SkeletonTopology, MapsABipedsRolesPassingOverTheClavicle) {
  const MappingSkeleton s = biped().done();
  const TopologyRoles t = riderByTopology(s);
  std::map<std::string, std::string> roles;
  for (const auto& [role, j] : t.roles) roles[role] = s.names[j];
  EXPECT_EQ(roles, (std::map<std::string, std::string>{
                       {"pelvis", "pelvis"},    {"neck", "neck"},        {"head", "head"},
                       {"lShoulder", "shoulderL"}, {"lElbow", "elbowL"}, {"lWrist", "wristL"}, {"lHand", "palmL"},
                       {"lHip", "hipL"},        {"lKnee", "kneeL"},      {"lAnkle", "ankleL"}, {"lBall", "ballL"},
                       {"rShoulder", "shoulderR"}, {"rElbow", "elbowR"}, {"rWrist", "wristR"}, {"rHand", "palmR"},
                       {"rHip", "hipR"},        {"rKnee", "kneeR"},      {"rAnkle", "ankleR"}, {"rBall", "ballR"}}));
  EXPECT_TRUE(t.warnings.empty());
  EXPECT_EQ(upperChestJoint(s, t.roles), joint(s, "chest"));
}

TEST(SkeletonTopology, WithoutClaviclesTheArmsRootIsTheShoulder) {
  const MappingSkeleton s = biped(false).done();
  const TopologyRoles t = riderByTopology(s);
  EXPECT_EQ(t.roles.at("lShoulder"), joint(s, "shoulderL"));
  EXPECT_EQ(t.roles.at("lElbow"), joint(s, "elbowL"));
}

TEST(SkeletonTopology, TheShouldersMustMeetOnTheSpineInTheFilesOwnHierarchy) {
  MappingSkeleton s = biped().done();
  const TopologyRoles t = riderByTopology(s);
  s.hung[joint(s, "clavicleR")] = 1;  // as if the file had it loose and the mapping hung it
  EXPECT_EQ(upperChestJoint(s, t.roles), -1);
}

TEST(SkeletonTopology, AChainIsNoBiped) {
  Figure f;
  int j = f.add("a", -1, {0, 0, 0});
  for (int i = 1; i < 6; ++i) j = f.add(std::string("b").append(std::to_string(i)), j, {0, 30.0 * i, 0});
  const MappingSkeleton s = f.done();
  EXPECT_TRUE(mirroredLimbs(s).empty());
  EXPECT_EQ(errorOf([&] { riderByTopology(s); }),
            "figure.glb: cannot map as a rider by topology: found 0 mirror-image limb pairs among 6 joints (expected two: arms "
            "and legs) (write a mapping file: docs/characters.md, \"Mapping by itself\")");
  EXPECT_EQ(errorOf([&] { horseByTopology(s); }),
            "figure.glb: cannot map as a horse by topology: found 0 mirror-image limb pairs among 6 joints (expected two pairs "
            "of legs) (write a mapping file: docs/characters.md, \"Mapping by itself\")");
}

TEST(SkeletonTopology, AnArmLongerOnOneSideIsNoMirrorImage) {
  Figure f = biped();
  f.s.position[static_cast<std::size_t>(f.s.find("wristR"))].x -= 12.0;  // a forearm 12 cm longer on the right
  const MappingSkeleton s = f.done();
  const std::vector<LimbPair> pairs = mirroredLimbs(s);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].branch, joint(s, "pelvis"));
}

// ---- A horse.

std::map<std::string, std::string> namedRoles(const MappingSkeleton& s, const TopologyRoles& t) {
  std::map<std::string, std::string> out;
  for (const auto& [role, j] : t.roles) out[role] = s.names[j];
  return out;
}

TEST(SkeletonTopology, AHorsesRolesDoNotDependOnWhatItsMeshWeights) {
  // The mane ends higher than the head, the ears and nostrils branch from the head, the thighs hang
  // from pelvis wings (a mirror pair of their own), the tail from the back joint behind the hips, a
  // saddle joint from the back: none of it takes a trunk, neck, head or tail role, whether the mesh
  // weights it (full), not (thin), or weights the back alone (trunk: legs, neck and tail unweighted).
  using W = test::StickHorseOptions::Weights;
  for (const W w : {W::Thin, W::Full, W::Trunk}) {
    test::StickHorseOptions o;
    o.weights = w;
    const MappingSkeleton s = test::stickHorse(o);
    const TopologyRoles t = horseByTopology(s);
    EXPECT_EQ(namedRoles(s, t), test::stickHorseRoles()) << "weights " << static_cast<int>(w);
    EXPECT_TRUE(t.warnings.empty()) << t.warnings.front();
  }
}

TEST(SkeletonTopology, ASplitBonesSegmentsArePassedOver) {
  // Every leg bone in two equal segments in line, as Rigify's deform bones: the roles stay on the
  // joints at the anatomical places (the first segments), never a ".001".
  test::StickHorseOptions o;
  o.split_legs = true;
  const MappingSkeleton s = test::stickHorse(o);
  const TopologyRoles t = horseByTopology(s);
  EXPECT_EQ(namedRoles(s, t), test::stickHorseRoles());
  EXPECT_EQ(t.why.at("lfUpper"), "topology: the leg's fourth joint from the ground (a split bone's segments passed over)");
}

TEST(SkeletonTopology, AHorseWithThreeLegsSaysWhichLegHasNoPartner) {
  test::StickHorseOptions o;
  o.three_legs = true;
  const MappingSkeleton s = test::stickHorse(o);
  EXPECT_EQ(errorOf([&] { horseByTopology(s); }),
            "horse.glb: cannot map as a horse by topology: the leg from \"pelvisL\" down to \"hindHoofL\" has no mirror image on "
            "the other side (found one pair of legs, from \"scapulaL\" and \"scapulaR\"; expected two pairs: a horse with four "
            "legs, each the mirror image of its partner) (write a mapping file: docs/characters.md, \"Mapping by itself\")");
}

}  // namespace
}  // namespace stirrup::rig
