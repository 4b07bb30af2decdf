// Mapping a character by itself (rig/mapping/auto_mapping.h). The ground truth for the generated humanoids is
// the generator's own anatomical label on every joint (rig/characters/standing_humanoid.h), never a table
// of the mapper's: each convention's files, in every rest pose, with two, three and six spine joints and
// with the hand one joint with the wrist or not, map every role to the joint the labels say, by their
// names and by topology alone. The axes and units are found in files the generator wrote in metres
// facing +Z, and in files turned to Z-up and written in centimetres or inches. Blender's own Rigify export
// (skipped without Blender), the Khronos Fox as a horse (skipped without the asset) and stirrup's horse
// with its role table stripped map as their own names say. Blender's Rigify horse (skipped without
// Blender), as its meta-rig, its generated rig with every bone and with its deform bones only, maps
// every role to the bone at its anatomical place by names and by shape, one role table whatever its
// mesh weights, and rides a gallop with every bone whole. A character that is not what it is mapped
// as (a horse lying on its side), a role off its chain or a joint not in the file is a one-line error.
#include "rig/io/character_mapping_json.h"
#include "rig/io/gltf_mapping.h"
#include "rig/mapping/auto_mapping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/characters/standing_humanoid.h"
#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_humanoid.h"
#include "rig/mapping/character_mapping.h"
#include "rig/mapping/mapping_skeleton.h"
#include "rig/pose.h"
#include "scene/clip_factory.h"
#include "tests/blender_fixture.h"
#include "tests/input_error.h"
#include "tests/rig/io/stick_horse.h"
#include "tests/rig/user_riders.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
using stirrup::test::errorOf;

fs::path testDir(const std::string& name) {
  const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "test_auto_mapping" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

fs::path writeBytes(const fs::path& file, const std::vector<unsigned char>& bytes) {
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return file;
}

StandingHumanoidParams humanoidParams(HumanoidNames names, HumanoidRestPose pose, int spine, bool shared) {
  StandingHumanoidParams p = humanoidConventionDefaults(names);
  p.pose = pose;
  p.spine_joints = spine;
  p.separate_hand = !shared;
  p.cell = 4.0f;  // coarse: the mapping reads the skeleton and the mesh's height only
  return p;
}

// What each rider role should be, from the generator's labels (tests/rig/user_riders.h), the top spine
// joint included when the clavicles hang from it in the file.
std::map<std::string, std::string> expectedRiderRoles(const StandingHumanoid& h) { return test::labelledRiderRoles(h, true); }

// The humanoid turned by `rotation` and scaled by `scale` (the file's units: 100 makes a file in
// centimetres), everything a file holds moved alike: joints, bone tails and rest frames, vertices, normals.
StandingHumanoid transformed(StandingHumanoid h, const glm::mat3& rotation, float scale) {
  Skeleton moved;
  const Skeleton& s = h.character.skeleton;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int p = s.joints[j].parent;
    const glm::vec3 at = rotation * s.restPosition(static_cast<int>(j)) * scale;
    const glm::vec3 from = p < 0 ? glm::vec3(0.0f) : rotation * s.restPosition(p) * scale;
    moved.addJoint(s.joints[j].name, p, glm::translate(glm::mat4(1.0f), at - from));
  }
  h.character.skeleton = moved;
  for (glm::vec3& v : h.character.mesh.positions) v = rotation * v * scale;
  for (glm::vec3& n : h.character.mesh.normals) n = rotation * n;
  for (glm::vec3& t : h.tails) t = rotation * t * scale;
  for (glm::mat3& a : h.rest_axes) a = rotation * a;
  return h;
}

std::array<double, 3> arr(double x, double y, double z) { return {x, y, z}; }

// ---- Every convention, rest pose, spine length and hand layout.

class AutoMappingConvention : public ::testing::TestWithParam<HumanoidNames> {};

TEST_P(AutoMappingConvention, MapsTheJointsTheGeneratorsLabelsSayByNamesAndByTopology) {
  const HumanoidNames names = GetParam();
  const std::string convention(humanoidNamesName(names));
  const fs::path dir = testDir("convention_" + convention);
  int mapped = 0;
  for (const HumanoidRestPose pose : {HumanoidRestPose::T, HumanoidRestPose::A, HumanoidRestPose::Relaxed})
    for (const int spine : {2, 3, 6})
      for (const bool shared : {false, true}) {
        const StandingHumanoid h = buildStandingHumanoid(humanoidParams(names, pose, spine, shared));
        static const char* const kPose[] = {"T", "A", "relaxed"};
        const std::string variant = convention + ", " + kPose[static_cast<int>(pose)] + " pose, " + std::to_string(spine) +
                                    " spine joints" + (shared ? ", wrist and hand one joint" : "");
        std::string stem = kPose[static_cast<int>(pose)];
        stem += std::to_string(spine);
        if (shared) stem += "_shared";
        const fs::path file = writeBytes(dir / (stem + ".glb"), humanoidGlb(h));
        const std::map<std::string, std::string> expected = expectedRiderRoles(h);
        // 15 required roles, both balls, both grips unless the wrist is the hand, upperChest unless detached.
        ASSERT_EQ(expected.size(), (shared ? 17u : 19u) + (h.params.detached_limbs ? 0u : 1u)) << variant;
        for (const bool use_names : {true, false}) {
          AutoMappingParams params;
          params.use_names = use_names;
          const AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider, params);
          const std::string how = variant + (use_names ? ", by names" : ", by topology");
          EXPECT_EQ(a.report.method, use_names && names != HumanoidNames::None ? convention : "topology") << how;
          EXPECT_EQ(a.mapping.roles, expected) << how;
          EXPECT_EQ(a.mapping.forward, arr(0, 0, 1)) << how;  // the generator faces +Z
          EXPECT_EQ(a.mapping.up, arr(0, 1, 0)) << how;
          EXPECT_EQ(a.mapping.scale_cm, 100.0) << how;        // written in metres
          EXPECT_EQ(a.report.unit, "metres") << how;
          EXPECT_EQ(a.mapping.offset_cm, arr(0, 0, 0)) << how;
          EXPECT_TRUE(a.report.not_mapped.empty()) << how;
          // The spine controllers, the braid and the coat tail are never guessed.
          for (const char* role : {"lowerBack", "waist", "chest", "braid1", "coatTail"}) EXPECT_FALSE(a.mapping.roles.count(role)) << how;
          ++mapped;
        }
      }
  EXPECT_EQ(mapped, 3 * 3 * 2 * 2);  // poses x spines x hands x (names, topology)
}

INSTANTIATE_TEST_SUITE_P(Conventions, AutoMappingConvention,
                         ::testing::Values(HumanoidNames::Mixamo, HumanoidNames::Rigify, HumanoidNames::Unreal, HumanoidNames::Vrm,
                                           HumanoidNames::HumanIK, HumanoidNames::None),
                         [](const ::testing::TestParamInfo<HumanoidNames>& info) { return std::string(humanoidNamesName(info.param)); });

// ---- Axes and units.

TEST(AutoMapping, FindsAZUpFileInCentimetres) {
  // Blender's own axes: Z up, the character facing -Y. Turned +90 degrees about X: +Y -> +Z, +Z -> -Y.
  const glm::mat3 to_z_up(glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, -1, 0));
  const StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::Mixamo, HumanoidRestPose::A, 3, false));
  const fs::path file = writeBytes(testDir("z_up") / "z_up_cm.glb", humanoidGlb(transformed(h, to_z_up, 100.0f)));
  for (const bool use_names : {true, false}) {
    AutoMappingParams params;
    params.use_names = use_names;
    const AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider, params);
    EXPECT_EQ(a.mapping.up, arr(0, 0, 1));
    EXPECT_EQ(a.mapping.forward, arr(0, -1, 0));
    EXPECT_EQ(a.mapping.scale_cm, 1.0);
    EXPECT_EQ(a.report.unit, "centimetres");
    EXPECT_EQ(a.mapping.roles, expectedRiderRoles(h));
  }
  // It loads: in stirrup's axes her head is above her ankles by Winter's heights, her left side at -Z.
  const Character c = loadCharacterGltf(file, CharacterKind::Rider);
  const Skeleton& s = c.skeleton;
  EXPECT_NEAR(s.restPosition(c.role("head")).y - s.restPosition(c.role("lAnkle")).y, (0.90f - 0.039f) * 170.0f, 0.01f);
  EXPECT_LT(s.restPosition(c.role("lHip")).z, -5.0f);
  EXPECT_GT(s.restPosition(c.role("rHip")).z, 5.0f);
  EXPECT_GT(s.restPosition(c.role("lBall")).x - s.restPosition(c.role("lAnkle")).x, 10.0f);  // toes ahead: +X
}

TEST(AutoMapping, FindsAFileInInchesFacingX) {
  // Turned -90 degrees about Y: +Z (her front) -> +X; written in inches (1 / 2.54 of the centimetres).
  const glm::mat3 face_x(glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0));
  const StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::None, HumanoidRestPose::T, 3, true));
  const fs::path file = writeBytes(testDir("inches") / "inches.glb", humanoidGlb(transformed(h, face_x, 100.0f / 2.54f)));
  const AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider);
  EXPECT_EQ(a.mapping.up, arr(0, 1, 0));
  EXPECT_EQ(a.mapping.forward, arr(1, 0, 0));
  EXPECT_EQ(a.mapping.scale_cm, 2.54);
  EXPECT_EQ(a.report.unit, "inches");
  EXPECT_EQ(a.mapping.roles, expectedRiderRoles(h));
}

TEST(AutoMapping, ATinyFileIsScaledToANominalHeightAndSaysSo) {
  // 170 cm written as 1.7 mm: no common unit makes a 100-230 cm rider (as metres 0.17 cm, as feet 5.2 cm).
  const StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::Mixamo, HumanoidRestPose::T, 3, false));
  const fs::path file = writeBytes(testDir("tiny") / "tiny.glb", humanoidGlb(transformed(h, glm::mat3(1.0f), 0.001f)));
  const AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider);
  EXPECT_EQ(a.report.unit, "");
  EXPECT_NEAR(a.mapping.scale_cm * a.report.height_file, kRiderNominalCm, 1e-9);
  ASSERT_EQ(a.report.warnings.size(), 1u);
  EXPECT_EQ(a.report.warnings[0], "no common unit gives a plausible height: scaled to 170 cm");
}

// ---- Files other tools made.

TEST(AutoMapping, BlendersOwnRigifyExportMapsByItsNames) {
  if (!stirrup::test::blenderInstalled())
    GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy): Blender's Rigify rider is not made";
  stirrup::test::BlenderMade made;
  const fs::path file = stirrup::test::blenderRigifyRider(&made);
  ASSERT_TRUE(made.ok) << made.log;
  const AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider);
  // Rigify's human meta-rig (Blender 3.x): DEF-spine the pelvis, spine.004-.005 the neck, spine.006 the
  // head; upper_arm and forearm, thigh and shin in two halves (the first half is the joint); palm.02
  // the middle metacarpal; toe the ball of the foot.
  const std::map<std::string, std::string> rigify = {
      {"pelvis", "DEF-spine"},         {"neck", "DEF-spine.004"},     {"head", "DEF-spine.006"},
      {"lShoulder", "DEF-upper_arm.L"}, {"lElbow", "DEF-forearm.L"},  {"lWrist", "DEF-hand.L"},  {"lHand", "DEF-palm.02.L"},
      {"lHip", "DEF-thigh.L"},         {"lKnee", "DEF-shin.L"},       {"lAnkle", "DEF-foot.L"},  {"lBall", "DEF-toe.L"},
      {"rShoulder", "DEF-upper_arm.R"}, {"rElbow", "DEF-forearm.R"},  {"rWrist", "DEF-hand.R"},  {"rHand", "DEF-palm.02.R"},
      {"rHip", "DEF-thigh.R"},         {"rKnee", "DEF-shin.R"},       {"rAnkle", "DEF-foot.R"},  {"rBall", "DEF-toe.R"}};
  EXPECT_EQ(a.report.method, "rigify");
  EXPECT_EQ(a.mapping.roles, rigify);
  EXPECT_EQ(a.mapping.up, arr(0, 1, 0));       // exported +Y up
  EXPECT_EQ(a.mapping.forward, arr(0, 0, 1));  // the meta-rig faces -Y in Blender: +Z in glTF
  EXPECT_EQ(a.report.unit, "metres");
  // By its shape alone (the limbs and face bones are separate roots in the file), the same required roles.
  AutoMappingParams shape;
  shape.use_names = false;
  const AutoMapping t = autoMapCharacterFile(file, CharacterKind::Rider, shape);
  for (const std::string& role : requiredRoles(CharacterKind::Rider)) EXPECT_EQ(t.mapping.roles.at(role), rigify.at(role)) << role;
  // And the importer reads it through the mapping it gets by itself.
  const Character c = loadCharacterGltf(file, CharacterKind::Rider);
  EXPECT_EQ(c.skeleton.joints[c.role("lElbow")].name, "DEF-forearm.L");
}

TEST(AutoMapping, TheFoxMapsAsAHorseAndLoadsWithTheRigsTack) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  const AutoMapping a = autoMapCharacterFile(fox, CharacterKind::Horse);
  EXPECT_EQ(a.report.method, "topology");
  // The Fox's own joint names say what each is; its left is +X (it faces +Z, +Y up).
  const std::map<std::string, std::string> fox_roles = {
      {"root", "b_Hip_01"},         {"backMid", "b_Spine01_02"},     {"chest", "b_Spine02_03"},
      {"neck1", "b_Neck_04"},       {"neck2", "b_Neck_04"},          {"head", "b_Head_05"},
      {"tail1", "b_Tail01_012"},    {"tail2", "b_Tail02_013"},       {"tail3", "b_Tail03_014"},
      {"lfUpper", "b_LeftUpperArm_09"}, {"lfMiddle", "b_LeftForeArm_010"}, {"lfFetlock", "b_LeftHand_011"}, {"lfHoof", "b_LeftHand_011"},
      {"rfUpper", "b_RightUpperArm_06"}, {"rfMiddle", "b_RightForeArm_07"}, {"rfFetlock", "b_RightHand_08"}, {"rfHoof", "b_RightHand_08"},
      {"lbUpper", "b_LeftLeg01_015"},  {"lbMiddle", "b_LeftLeg02_016"},  {"lbFetlock", "b_LeftFoot01_017"}, {"lbHoof", "b_LeftFoot02_018"},
      {"rbUpper", "b_RightLeg01_019"}, {"rbMiddle", "b_RightLeg02_020"}, {"rbFetlock", "b_RightFoot01_021"}, {"rbHoof", "b_RightFoot02_022"}};
  EXPECT_EQ(a.mapping.roles, fox_roles);
  EXPECT_TRUE(a.report.not_mapped.empty());  // the withers and the tack are optional: the rig adds the tack
  EXPECT_EQ(a.report.optional_not_mapped, (std::vector<std::string>{"lfPivot", "rfPivot", "lbPivot", "rbPivot"}));
  EXPECT_EQ(a.mapping.up, arr(0, 1, 0));
  EXPECT_EQ(a.mapping.forward, arr(0, 0, 1));
  // 79 units from its paws to its ears: as inches a 201 cm horse, as centimetres a fox.
  EXPECT_EQ(a.report.unit, "inches");
  EXPECT_NEAR(a.report.height_file, 79.03, 0.01);
  EXPECT_NEAR(a.mapping.offset_cm[1], 0.1217 * 2.54, 0.001);  // its lowest vertex, 0.12 units below 0, put on the ground
  // The importer loads it through that mapping, with the rig's own tack (rig/characters/horse_tack.h).
  const Character c = loadCharacterGltf(fox, CharacterKind::Horse);
  for (const char* role : {"saddle", "lStirrup", "rStirrup", "lRein", "rRein"}) EXPECT_TRUE(c.skeleton.joints[c.role(role)].rig_point) << role;
}

// ---- Horses we did not make: Blender's Rigify horse.

// tests/blender/rigify-horse's files, each vertex weighted wholly to its nearest bone of the body's, so
// that which joints a file weights is known (one Blender run of six horses, under 10 s, made once for
// every test process of a run: tests/blender_fixture.h): the meta-rig with a thin body (legs, trunk,
// neck, head and tail weighted), a full body (every bone weighted: the mane, ears, jaw, eyes, nostrils,
// breast and pelvis bones too) and the thin body with only the spine weighted; the generated rig with
// every bone, and with its deform bones only (thin and full bodies). "" without Blender.
const std::string& rigifyHorses() {
  static const std::string dir = []() -> std::string {
    if (!stirrup::test::blenderInstalled()) return "";
    const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "test_blender_horses" / "mapping";
    const fs::path script = STIRRUP_SOURCE_DIR "/tests/blender/rigify-horse";
    const std::string command = "'" + script.string() + "' --batch '" + d.string() + "'" +
                                " 'metarig-thin:--form metarig --weights nearest'"
                                " 'metarig-full:--form metarig --body full --weights nearest'"
                                " 'metarig-trunk:--form metarig --body trunk --weights nearest'"
                                " 'generated-all:--form generated --bones all --weights nearest'"
                                " 'generated-deform:--form generated --bones deform --weights nearest'"
                                " 'generated-deform-full:--form generated --bones deform --body full --weights nearest'";
    if (!stirrup::test::madeByBlender(d, script, command).ok) return "failed";
    return d.string();
  }();
  return dir;
}

#define RIGIFY_HORSES_OR_SKIP()                                                                                           \
  do {                                                                                                                    \
    if (rigifyHorses().empty())                                                                                           \
      GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy): Blender's Rigify horse is not made"; \
    ASSERT_NE(rigifyHorses(), "failed") << "tests/blender/rigify-horse failed";                                         \
  } while (0)

AutoMapping mapRigifyHorse(const std::string& form, bool use_names) {
  AutoMappingParams params;
  params.use_names = use_names;
  return autoMapCharacterFile(fs::path(rigifyHorses()) / (form + ".glb"), CharacterKind::Horse, params);
}

// The Rigify horse's roles at their anatomical places (character-notes section 4; docs/characters.md,
// "Mapping by itself"), bone names with `prefix` ("DEF-" for the generated rig): a bone's head is its
// joint. The thighs hang from the pelvis bones, so the hips are the back's joint whose bone passes
// over the hip joints, spine.001 (from spine.001's head over the croup to spine.002's); the chest
// spine.005, which the scapulae hang from in the meta-rig; backMid the middle of spine.001..spine.005;
// the withers spine.006, the back's joint nearest the scapulae's tops; neck.001..neck.004 the neck,
// neck2 its middle (neck.003); the tail spread over tail.001..tail.005 (tail.001, .003, .004); per leg
// the scapula's pivot (shoulder) or hip joint (thigh), the elbow (forearm) or stifle (lower_leg), the
// knee (forefoot) or hock (hind_foot), the fetlock (f_toe, r_toe) and the hoof: never a ".001".
std::map<std::string, std::string> rigifyHorseRoles(const std::string& prefix) {
  std::map<std::string, std::string> r = {{"root", "spine.001"}, {"backMid", "spine.003"}, {"chest", "spine.005"}, {"withers", "spine.006"},
                                          {"neck1", "neck.001"}, {"neck2", "neck.003"},    {"head", "head"},       {"tail1", "tail.001"},
                                          {"tail2", "tail.003"}, {"tail3", "tail.004"}};
  for (const auto& [l, side] : {std::pair<std::string, std::string>{"l", ".L"}, {"r", ".R"}})
    for (const auto& [part, bone] : std::vector<std::pair<std::string, std::string>>{
             {"fPivot", "shoulder"}, {"fUpper", "forearm"}, {"fMiddle", "forefoot"}, {"fFetlock", "f_toe"}, {"fHoof", "f_hoof"},
             {"bPivot", "thigh"}, {"bUpper", "lower_leg"}, {"bMiddle", "hind_foot"}, {"bFetlock", "r_toe"}, {"bHoof", "r_hoof"}})
      r[l + part] = bone + side;
  for (auto& [role, bone] : r) bone = prefix + bone;
  return r;
}

TEST(AutoMappingRigifyHorse, TheMetarigMapsEveryRoleByNameAndByShape) {
  RIGIFY_HORSES_OR_SKIP();
  const AutoMapping named = mapRigifyHorse("metarig-thin", true);
  EXPECT_EQ(named.report.method, "rigify horse");
  EXPECT_EQ(named.report.method_form, "metarig names");
  EXPECT_EQ(named.mapping.roles, rigifyHorseRoles(""));
  EXPECT_EQ(named.mapping.up, arr(0, 1, 0));       // exported +Y up
  EXPECT_EQ(named.mapping.forward, arr(0, 0, 1));  // the horse faces -Y in Blender: +Z in glTF
  EXPECT_EQ(named.report.unit, "metres");
  EXPECT_TRUE(named.report.warnings.empty());
  // By its shape alone, the same joints; the withers are found by name only.
  std::map<std::string, std::string> shape = rigifyHorseRoles("");
  shape.erase("withers");
  const AutoMapping t = mapRigifyHorse("metarig-thin", false);
  EXPECT_EQ(t.report.method, "topology");
  EXPECT_EQ(t.mapping.roles, shape);
  EXPECT_EQ(t.mapping.forward, arr(0, 0, 1));
}

TEST(AutoMappingRigifyHorse, TheSameSkeletonMapsTheSameWhateverItsMeshWeights) {
  // One skeleton, three bodies: thin (legs, trunk, neck, head, tail weighted), full (every bone
  // weighted: the mane, ears, jaw, eyes, nostrils, breast and pelvis bones too, the mane reaching above
  // the head), and the trunk alone weighted (legs, neck, head and tail carry no weight): one role
  // table, by names and by shape. Likewise the generated rig's deform bones under a thin and a full body.
  RIGIFY_HORSES_OR_SKIP();
  // The files weight exactly those joints.
  const auto weighted = [](const std::string& form) {
    const fs::path file = fs::path(rigifyHorses()) / (form + ".glb");
    const MappingSkeleton s = mappingSkeletonFromGltf(readGltfFile(file, file.string()), file.string());
    std::set<std::string> w;
    for (std::size_t j = 0; j < s.names.size(); ++j)
      if (s.weighted[j]) w.insert(s.names[j]);
    return w;
  };
  // The thin body's bones, the spine, neck, head, tail and legs (in the generated rig each long leg bone
  // in two segments).
  const auto thinBones = [](const std::string& prefix, bool split) {
    std::set<std::string> w;
    for (const char* b : {"spine.001", "spine.002", "spine.003", "spine.004", "spine.005", "spine.006", "neck.001", "neck.002", "neck.003",
                          "neck.004", "head", "tail.001", "tail.002", "tail.003", "tail.004", "tail.005"})
      w.insert(prefix + b);
    for (const std::string side : {".L", ".R"}) {
      for (const char* b : {"shoulder", "f_toe", "f_hoof", "r_toe", "r_hoof"}) w.insert(prefix + b + side);
      for (const char* b : {"upper_arm", "forearm", "forefoot", "thigh", "lower_leg", "hind_foot"}) {
        w.insert(prefix + b + side);
        if (split) w.insert(prefix + b + side + ".001");
      }
    }
    return w;
  };
  EXPECT_EQ(weighted("metarig-thin"), thinBones("", false));
  EXPECT_EQ(weighted("metarig-trunk"), (std::set<std::string>{"spine.001", "spine.002", "spine.003", "spine.004", "spine.005", "spine.006"}));
  EXPECT_EQ(weighted("metarig-full").size(), 70u);  // every bone
  EXPECT_EQ(weighted("generated-deform"), thinBones("DEF-", true));
  EXPECT_EQ(weighted("generated-deform-full").size(), 80u);  // every deform bone
  for (const bool use_names : {true, false}) {
    const AutoMapping thin = mapRigifyHorse("metarig-thin", use_names);
    for (const char* body : {"metarig-full", "metarig-trunk"})
      EXPECT_EQ(mapRigifyHorse(body, use_names).mapping.roles, thin.mapping.roles) << body << (use_names ? ", by names" : ", by shape");
    EXPECT_EQ(mapRigifyHorse("generated-deform-full", use_names).mapping.roles, mapRigifyHorse("generated-deform", use_names).mapping.roles)
        << (use_names ? "by names" : "by shape");
  }
}

TEST(AutoMappingRigifyHorse, TheGeneratedRigsDeformBonesMapByNameAndByShape) {
  RIGIFY_HORSES_OR_SKIP();
  // Exported with its deform bones only, the limbs, tail and face bones are roots (their parents are
  // ORG- bones, not in the file): each hangs beside the trunk's bone it lies against.
  const fs::path file = fs::path(rigifyHorses()) / "generated-deform.glb";
  const MappingSkeleton s = mappingSkeletonFromGltf(readGltfFile(file, file.string()), file.string());
  const auto parentOf = [&](const char* j) { return s.names[s.parent[s.find(j)]]; };
  EXPECT_EQ(parentOf("DEF-thigh.L"), "DEF-spine.001");
  EXPECT_EQ(parentOf("DEF-tail.001"), "DEF-spine.001");
  EXPECT_EQ(parentOf("DEF-shoulder.L"), "DEF-spine.006");   // nearer DEF-neck.001's joint than DEF-spine.006's, along spine.006's bone
  EXPECT_EQ(parentOf("DEF-upper_arm.L"), "DEF-spine.006");
  EXPECT_EQ(parentOf("DEF-skull"), "DEF-head");
  // By names: the scapulae were loose, so the chest is the back's joint whose bone passes nearest
  // them, DEF-spine.006 (the meta-rig hangs them from spine.005).
  std::map<std::string, std::string> expected = rigifyHorseRoles("DEF-");
  expected["chest"] = "DEF-spine.006";
  const AutoMapping named = mapRigifyHorse("generated-deform", true);
  EXPECT_EQ(named.report.method, "rigify horse");
  EXPECT_EQ(named.report.method_form, "deform bones");
  EXPECT_EQ(named.mapping.roles, expected);
  // `stirrup character map` and a scene naming the file alone say which convention and form matched.
  EXPECT_EQ(autoMappingReportText(named).rfind(file.string() + " as a horse: rigify horse (deform bones)\n", 0), 0u);
  EXPECT_EQ(autoMappingSummary(named).rfind(file.string() + ": no role table: mapped as a horse by rigify horse (deform bones); up +Y", 0), 0u)
      << autoMappingSummary(named);
  // By shape, two roles differ: the fore legs' pivots are DEF-upper_arm.L/.R, the humerus's head, for
  // the scapula DEF-shoulder.L is a lone root beside the limb's chain (nothing in the file says it
  // carries the humerus: its parent, ORG-shoulder.L, is not exported); and the withers are not guessed.
  expected["lfPivot"] = "DEF-upper_arm.L";
  expected["rfPivot"] = "DEF-upper_arm.R";
  expected.erase("withers");
  EXPECT_EQ(mapRigifyHorse("generated-deform", false).mapping.roles, expected);
}

TEST(AutoMappingRigifyHorse, TheGeneratedRigWithEveryBoneMapsByItsDeformBones) {
  RIGIFY_HORSES_OR_SKIP();
  // Its 454 bones: the ORG- copies, MCH- mechanism and controls ("head", "shoulder.L", "thigh_ik.L") are
  // never a role. DEF-shoulder.L hangs from DEF-spine.005 as its original does (rigifyDeformParents).
  const AutoMapping named = mapRigifyHorse("generated-all", true);
  EXPECT_EQ(named.report.method_form, "deform bones");
  EXPECT_EQ(named.mapping.roles, rigifyHorseRoles("DEF-"));
  // By shape alone it cannot be mapped: every limb is there five times over, deform, original, FK, IK
  // and tweak bones at one place, which no skeleton rule tells apart; the error says where it stopped.
  const fs::path file = fs::path(rigifyHorses()) / "generated-all.glb";
  EXPECT_EQ(errorOf([&] { mapRigifyHorse("generated-all", false); }),
            file.string() + ": cannot map as a horse by topology: both pairs of legs branch from joint \"ORG-spine.002\" (expected the "
                            "hind legs at the hips and the fore legs at the chest) (write a mapping file: docs/characters.md, \"Mapping by itself\")");
}

// The angle (degrees) a joint turns the line of bones through it: from its parent's bone to its child's.
double turnAt(const std::vector<glm::mat4>& w, int parent, int j, int child) {
  const glm::dvec3 in = glm::dvec3(w[j][3]) - glm::dvec3(w[parent][3]), out = glm::dvec3(w[child][3]) - glm::dvec3(w[j][3]);
  return std::acos(std::clamp(glm::dot(glm::normalize(in), glm::normalize(out)), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

TEST(AutoMappingRigifyHorse, EveryFormRidesAGallopWithEveryBoneWholeAndItsLength) {
  // Loaded through the mapping it gets by itself and posed through a gallop stride (the legs reach
  // farthest): no bone of the file changes length, and a split bone stays one straight bone (the joint
  // between its segments, DEF-forearm.L.001, never bends: the leg bends at the anatomical joints); the
  // humerus of the deform-bones-only export hangs from its scapula (the lfPivot role).
  RIGIFY_HORSES_OR_SKIP();
  for (const char* form : {"metarig-full", "generated-all", "generated-deform"}) {
    const Character horse = loadCharacterGltf(fs::path(rigifyHorses()) / (std::string(form) + ".glb"), CharacterKind::Horse);
    const Skeleton& s = horse.skeleton;
    EXPECT_FALSE(s.pathFrom(horse.role("lfPivot"), horse.role("lfUpper")).empty()) << form << ": the humerus hangs from the scapula";
    // Bones in line at rest through a joint "X.001" under "X": Rigify's split segments (and its ears'
    // second bones), with the child the bone runs on to.
    std::vector<std::array<int, 3>> splits;  // parent, segment, child
    const std::vector<glm::mat4> rest = restWorlds(s);
    for (std::size_t j = 0; j < s.size(); ++j) {
      const int p = s.joints[j].parent;
      if (p < 0 || s.joints[j].name != s.joints[p].name + ".001") continue;
      for (std::size_t c = 0; c < s.size(); ++c)
        if (s.joints[c].parent == int(j) && turnAt(rest, p, int(j), int(c)) < 0.1) splits.push_back({p, int(j), int(c)});
    }
    if (std::string(form) != "metarig-full") {  // the leg's three split bones each, DEF-forearm.L.001 among them
      EXPECT_TRUE(std::any_of(splits.begin(), splits.end(), [&](const std::array<int, 3>& x) { return s.joints[x[1]].name == "DEF-forearm.L.001"; }))
          << form;
    }
    scene::ClipSpec spec;
    spec.generator = "gallop";
    spec.source = "test";
    const auto clip = scene::makeClip(spec, horse);
    double worst = 0.0, worst_turn = 0.0;
    std::string worst_bone, worst_split;
    for (int i = 0; i < 24; ++i) {
      const std::vector<glm::mat4> w = poseHorse(horse, clip->sample(clip->duration() * i / 24.0));
      for (std::size_t j = 0; j < s.size(); ++j) {
        const int p = s.joints[j].parent;
        if (p < 0 || s.joints[j].rig_point) continue;
        const double rest = glm::length(s.restPosition(int(j)) - s.restPosition(p));
        const double off = std::abs(glm::length(glm::vec3(w[j][3]) - glm::vec3(w[p][3])) - rest);
        if (off > worst) worst = off, worst_bone = s.joints[j].name;
      }
      for (const auto& [p, j, c] : splits)
        if (const double turn = turnAt(w, p, j, c); turn > worst_turn) worst_turn = turn, worst_split = s.joints[j].name;
    }
    EXPECT_LE(worst, 0.02) << form << ": bone " << worst_bone << " changes length";
    EXPECT_LE(worst_turn, 0.5) << form << ": the split bone at " << worst_split << " bends";
  }
}

// stirrup's own horse with its role table lost on the way (re-exported by a tool that drops extras).
struct StrippedHorse {
  fs::path named, unnamed;
  std::map<std::string, std::string> roles;          // the file's role table: role -> joint name
  std::map<std::string, std::string> roles_unnamed;  // the same joints under their new names
};

StrippedHorse stripHorse(const fs::path& dir) {
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  std::string err, warn;
  EXPECT_TRUE(gltf.LoadBinaryFromFile(&model, &err, &warn, STIRRUP_SOURCE_DIR "/scenes/characters/horse.glb")) << err;
  StrippedHorse out;
  const tinygltf::Skin& skin = model.skins.at(0);
  for (tinygltf::Node& n : model.nodes)
    if (n.extras.IsObject() && n.extras.Has("stirrup_roles")) {
      const tinygltf::Value& t = n.extras.Get("stirrup_roles");
      for (const std::string& role : t.Keys()) {
        const int j = t.Get(role).Get<int>();
        out.roles[role] = model.nodes.at(skin.joints.at(j)).name;
        out.roles_unnamed[role] = "bone" + std::to_string(j);
      }
      n.extras = tinygltf::Value();
    }
  out.named = dir / "horse-no-roles.glb";
  EXPECT_TRUE(gltf.WriteGltfSceneToFile(&model, out.named.string(), true, true, false, true));
  for (std::size_t j = 0; j < skin.joints.size(); ++j) model.nodes.at(skin.joints[j]).name = "bone" + std::to_string(j);
  out.unnamed = dir / "horse-unnamed.glb";
  EXPECT_TRUE(gltf.WriteGltfSceneToFile(&model, out.unnamed.string(), true, true, false, true));
  return out;
}

TEST(AutoMapping, StirrupsHorseWithoutItsRoleTableMapsByNamesAndByTopology) {
  const StrippedHorse h = stripHorse(testDir("horse"));
  const AutoMapping named = autoMapCharacterFile(h.named, CharacterKind::Horse);
  EXPECT_EQ(named.report.method, "stirrup");
  EXPECT_EQ(named.mapping.roles, h.roles);
  EXPECT_EQ(named.mapping.forward, arr(1, 0, 0));
  EXPECT_EQ(named.mapping.up, arr(0, 1, 0));
  EXPECT_EQ(named.mapping.scale_cm, 1.0);  // its bind space is centimetres (the file's stirrup_cm node makes metres of them)
  EXPECT_TRUE(named.report.not_mapped.empty());
  // Unnamed, by its shape: every role the shape shows; the withers and the tack (optional) are not among them.
  const AutoMapping shaped = autoMapCharacterFile(h.unnamed, CharacterKind::Horse);
  EXPECT_EQ(shaped.report.method, "topology");
  std::map<std::string, std::string> expected = h.roles_unnamed;
  for (const char* role : {"withers", "saddle", "lStirrup", "rStirrup", "lRein", "rRein"}) expected.erase(role);
  EXPECT_EQ(shaped.mapping.roles, expected);
  EXPECT_TRUE(shaped.report.not_mapped.empty());  // all optional: the rig adds tack where none is named
}

// ---- Loading through the mapping.

TEST(AutoMapping, TheImporterMapsAFileWithoutARoleTableByItself) {
  const StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::Unreal, HumanoidRestPose::Relaxed, 3, false));
  const fs::path file = writeBytes(testDir("importer") / "unreal.glb", humanoidGlb(h));
  AutoMapping a;
  const Character c = loadCharacterGltf(file, CharacterKind::Rider, nullptr, &a);
  EXPECT_EQ(a.report.method, "unreal");
  for (const auto& [role, joint] : expectedRiderRoles(h)) EXPECT_EQ(c.skeleton.joints[c.role(role)].name, joint) << role;
  EXPECT_EQ(c.source.to_rig, mappingToRig(a.mapping));
  // In stirrup's axes and centimetres: the head 153 cm up, the left hip at -Z.
  EXPECT_NEAR(c.skeleton.restPosition(c.role("head")).y, 0.9f * 170.0f, 1e-3f);
  EXPECT_NEAR(c.skeleton.restPosition(c.role("lHip")).z, -0.5f * 0.105f * 170.0f, 1e-3f);
}

TEST(AutoMapping, TheMappingFileItWritesLoadsBackTheSame) {
  const StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::Vrm, HumanoidRestPose::A, 6, true));
  const fs::path dir = testDir("file");
  const fs::path file = writeBytes(dir / "vrm.glb", humanoidGlb(h));
  const AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider);
  std::ofstream(dir / "vrm.json") << autoMappingJson(a).dump(2);
  const CharacterMapping back = loadCharacterMapping(dir / "vrm.json", CharacterKind::Rider);
  EXPECT_EQ(back.roles, a.mapping.roles);
  EXPECT_EQ(back.scale_cm, a.mapping.scale_cm);
  EXPECT_EQ(back.forward, a.mapping.forward);
  EXPECT_EQ(back.up, a.mapping.up);
  EXPECT_EQ(back.offset_cm, a.mapping.offset_cm);
  const nlohmann::ordered_json j = autoMappingJson(a);
  EXPECT_EQ(j.begin().key(), "comment");
  EXPECT_EQ(j["roles"].begin().key(), "pelvis");  // in role order
  EXPECT_NE(j["comment"].get<std::string>().find("vrm joint names; up +Y: from the ankles up to the head; forward +Z: the toes "
                                                 "point ahead of the ankles"),
            std::string::npos)
      << j["comment"];
}

TEST(AutoMapping, AMirroredFileHasItsSidesSwappedWithAWarning) {
  // Left and right names exchanged (a file mirrored after naming): the limbs called "Left" are on her right.
  StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::HumanIK, HumanoidRestPose::T, 3, false));
  for (Joint& j : h.character.skeleton.joints) {
    std::string& n = j.name;
    if (n.rfind("Left", 0) == 0) n = "Right" + n.substr(4);
    else if (n.rfind("Right", 0) == 0) n = "Left" + n.substr(5);
  }
  const AutoMapping a = autoMapCharacterFile(writeBytes(testDir("mirrored") / "m.glb", humanoidGlb(h)), CharacterKind::Rider);
  EXPECT_EQ(a.mapping.roles.at("lShoulder"), "RightArm");  // the joint on her left, whatever it is called
  EXPECT_EQ(a.mapping.roles.at("lHip"), "RightUpLeg");
  ASSERT_EQ(a.report.warnings.size(), 2u);
  EXPECT_EQ(a.report.warnings[0], "the humanik names put the Shoulder called left on the character's right (a mirrored file?): sides swapped");
}

// ---- Errors.

TEST(AutoMapping, AStandingHumanIsNotAHorse) {
  const StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::Mixamo, HumanoidRestPose::T, 3, false));
  const fs::path file = writeBytes(testDir("not_a_horse") / "h.glb", humanoidGlb(h));
  EXPECT_EQ(errorOf([&] { autoMapCharacterFile(file, CharacterKind::Horse); }),
            file.string() + ": cannot map as a horse by topology: the limb from \"mixamorig:LeftShoulder\" ends at "
                            "\"mixamorig:LeftHandIndex3\", 80% of the height above the ground (expected four legs reaching the "
                            "ground; a two-legged character? try --as rider) (write a mapping file: docs/characters.md, \"Mapping by itself\")");
}

TEST(AutoMapping, AFoxIsNotARider) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  EXPECT_EQ(errorOf([&] { autoMapCharacterFile(fox, CharacterKind::Rider); }),
            fox.string() + ": cannot map as a rider by topology: cannot tell the legs from the arms: neither limb pair (from "
                           "\"b_Hip_01\" and \"b_Spine02_03\") hangs away from the other (a four-legged character? try --as horse) "
                           "(write a mapping file: docs/characters.md, \"Mapping by itself\")");
}

TEST(AutoMapping, WhenTheShapeSaysNothingTheErrorSaysWhatTheNamesNearlySaid) {
  // Mixamo names with the left thigh renamed (the names give every role but lHip), and the right hand's
  // joint 12 cm out along the arm (no mirror image of the left arm: the shape finds only the legs).
  StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::Mixamo, HumanoidRestPose::T, 3, false));
  Skeleton moved;
  const Skeleton& s = h.character.skeleton;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const auto at = [&](int k) {
      return s.restPosition(k) + (s.joints[k].name == "mixamorig:RightHand" ? glm::vec3(-12.0f, 0.0f, 0.0f) : glm::vec3(0.0f));
    };
    const int p = s.joints[j].parent;
    std::string name = s.joints[j].name == "mixamorig:LeftUpLeg" ? "mixamorig:LeftThigh" : s.joints[j].name;
    moved.addJoint(name, p, glm::translate(glm::mat4(1.0f), at(static_cast<int>(j)) - (p < 0 ? glm::vec3(0.0f) : at(p))));
  }
  h.character.skeleton = moved;
  const fs::path file = writeBytes(testDir("names_nearly") / "m.glb", humanoidGlb(h));
  EXPECT_EQ(errorOf([&] { autoMapCharacterFile(file, CharacterKind::Rider); }),
            file.string() + ": cannot map as a rider by topology: found 1 mirror-image limb pair among 43 joints (expected two: "
                            "arms and legs) (write a mapping file: docs/characters.md, \"Mapping by itself\"); its joint names look like "
                            "mixamo but name no lHip");
}

// The stick horse (tests/rig/io/stick_horse.h) turned by `rotation`: joints and mesh alike.
MappingSkeleton turnedHorse(const glm::dmat3& rotation) {
  MappingSkeleton s = test::stickHorse();
  for (glm::dvec3& p : s.position) p = rotation * p;
  for (glm::dvec3& v : s.vertices) v = rotation * v;
  return s;
}

TEST(AutoMapping, AHorseMustStandOnItsHooves) {
  // Upright in a Z-up file (turned +90 degrees about X: +Y -> +Z, +Z -> -Y): mapped, with its up.
  const glm::dmat3 z_up(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, -1, 0));
  const AutoMapping a = autoMapCharacter(turnedHorse(z_up), CharacterKind::Horse);
  EXPECT_EQ(a.mapping.up, arr(0, 0, 1));
  EXPECT_EQ(a.mapping.forward, arr(0, -1, 0));
  std::map<std::string, std::string> expected = test::stickHorseRoles();
  expected["saddle"] = "saddle";  // tack by its name
  EXPECT_EQ(a.mapping.roles, expected);
  // Lying on its side (turned +90 degrees about its forward axis, Z: +Y -> -X), its legs pointing
  // sideways: refused, saying which way they point.
  const glm::dmat3 on_its_side(glm::dvec3(0, 1, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, 1));
  const std::string lying = "horse.glb: cannot map as a horse: its rest pose does not stand on its hooves: its legs reach from the "
                            "back (\"spine1\") to the hooves (\"foreHoofL\", ...) toward +X (expected down, -Y in glTF or -Z in a "
                            "Z-up file: turn the horse upright in its file, standing on its hooves, and export it again)";
  EXPECT_EQ(errorOf([&] { autoMapCharacter(turnedHorse(on_its_side), CharacterKind::Horse); }), lying);
  // Upside down (turned 180 degrees about Z): likewise, its legs toward +Y.
  const glm::dmat3 upside_down(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
  EXPECT_NE(errorOf([&] { autoMapCharacter(turnedHorse(upside_down), CharacterKind::Horse); }).find("does not stand on its hooves"),
            std::string::npos);
}

TEST(AutoMapping, AHorsesMappingNamingAJointNotInTheFileSaysWhichFileAndJoint) {
  const fs::path dir = testDir("horse_missing_joint");
  const StrippedHorse h = stripHorse(dir);
  nlohmann::ordered_json j = autoMappingJson(autoMapCharacterFile(h.named, CharacterKind::Horse));
  j["roles"]["lfUpper"] = "lfElbow.001";
  std::ofstream(dir / "map.json") << j.dump(2);
  const CharacterMapping m = loadCharacterMapping(dir / "map.json", CharacterKind::Horse);
  EXPECT_EQ(errorOf([&] { loadCharacterGltf(h.named, CharacterKind::Horse, &m); }),
            (dir / "map.json").string() + ": roles.lfUpper: no joint named \"lfElbow.001\" in " + h.named.string() +
                " (change it to one of the file's joints: stirrup character map " + h.named.string() +
                " --as horse lists them with the roles they seem to play)");
}

TEST(AutoMapping, ARoleOffItsChainIsAOneLineErrorNamingTheRoleAndTheJoint) {
  const StandingHumanoid h = buildStandingHumanoid(humanoidParams(HumanoidNames::Mixamo, HumanoidRestPose::T, 3, false));
  const fs::path dir = testDir("off_chain");
  const fs::path file = writeBytes(dir / "m.glb", humanoidGlb(h));
  AutoMapping a = autoMapCharacterFile(file, CharacterKind::Rider);
  nlohmann::ordered_json j = autoMappingJson(a);
  j["roles"]["lKnee"] = "mixamorig:LeftArm";
  std::ofstream(dir / "m.json") << j.dump(2);
  const CharacterMapping m = loadCharacterMapping(dir / "m.json", CharacterKind::Rider);
  EXPECT_EQ(errorOf([&] { loadCharacterGltf(file, CharacterKind::Rider, &m); }),
            (dir / "m.json").string() + ": roles.lKnee: joint \"mixamorig:LeftArm\" is not below lHip \"mixamorig:LeftUpLeg\" "
                                        "(expected the knee on the leg's chain below the hip; change it in the mapping file)");
  j["roles"]["lKnee"] = "mixamorig:LeftLeg";
  j["roles"]["neck"] = "mixamorig:Spine";
  std::ofstream(dir / "m.json") << j.dump(2);
  const CharacterMapping m2 = loadCharacterMapping(dir / "m.json", CharacterKind::Rider);
  EXPECT_EQ(errorOf([&] { loadCharacterGltf(file, CharacterKind::Rider, &m2); }),
            (dir / "m.json").string() + ": roles.neck: joint \"mixamorig:Spine\" is not above pelvis \"mixamorig:Hips\" with a "
                                        "spine joint between them (expected the neck on the chain that runs up from the pelvis; change "
                                        "it in the mapping file)");
}

}  // namespace
}  // namespace stirrup::rig
