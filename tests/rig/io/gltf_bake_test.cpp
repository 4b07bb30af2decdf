// The baked-shot glTF writer (rig/io/gltf_bake.cpp) on small hand-made shots, read back with tinygltf:
// joint locals from world matrices, the seat's extras, the layout (a centimetre root per character,
// cameras, the ground), and which nodes are animated. `stirrup bake` end to end (round trip of a real
// shot, the Khronos validator, Blender) is tests/cli/bake_*_test.cpp.
#include "rig/io/gltf_bake.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/io/gltf_animation.h"
#include "rig/tack_part.h"
#include "tests/rig/default_characters.h"
#include "tests/rig/io/baked_trot.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

using test::defaultHorse;
using test::defaultRider;

void expectMatNear(const glm::mat4& a, const glm::mat4& b, float tol) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << "column " << c << " row " << r;
}

TEST(GltfBake, WorldToLocalTakesOffTheParent) {
  Skeleton s;
  s.addJoint("root", -1, glm::mat4(1.0f));
  s.addJoint("child", 0, glm::mat4(1.0f));
  const glm::mat4 root = glm::rotate(glm::translate(glm::mat4(1.0f), {1, 2, 3}), glm::radians(90.0f), {0, 1, 0});
  const glm::mat4 child_local = glm::translate(glm::mat4(1.0f), {10, 0, 0});
  const std::vector<glm::mat4> local = worldToLocal(s, {root, root * child_local});
  expectMatNear(local[0], root, 0.0f);  // a root's local is its world
  expectMatNear(local[1], child_local, 1e-5f);
  // By hand: the root turned 90° about y takes the child's +x to -z: world (1, 2, 3 - 10).
  EXPECT_NEAR((root * child_local)[3].z, -7.0f, 1e-5f);
  EXPECT_THROW(worldToLocal(s, {root}), std::invalid_argument);
}

TEST(GltfBake, TheSeatIsRecordedOnlyWhenTheRigChangedSomething) {
  EXPECT_FALSE(seatExtras(SeatReport{}).IsObject());
  SeatReport seated;
  seated.seated_by_rig = true;
  seated.stirrup_holes_up = 2.0f;
  seated.added_points = {"lGrip", "rGrip"};
  const tinygltf::Value v = seatExtras(seated);
  ASSERT_TRUE(v.IsObject());
  EXPECT_TRUE(v.Get("seated_by_rig").Get<bool>());
  EXPECT_EQ(v.Get("stirrup_holes_up").GetNumberAsDouble(), 2.0);
  ASSERT_EQ(v.Get("added_points").ArrayLen(), 2u);
  EXPECT_EQ(v.Get("added_points").Get(1).Get<std::string>(), "rGrip");
  SeatReport points_only;
  points_only.added_points = {"lSole"};
  const tinygltf::Value p = seatExtras(points_only);
  ASSERT_TRUE(p.IsObject());
  EXPECT_FALSE(p.Get("seated_by_rig").Get<bool>());
  EXPECT_FALSE(p.Has("stirrup_holes_up"));  // the leathers were not set
}

// Two frames at 24 fps: both characters at rest, except the horse's root joint 50 cm further along x in
// the second frame (its other joints stay where they were); one orthographic camera moving 100 cm along
// x; a flat 2-triangle ground.
BakedShot twoFrameShot() {
  BakedShot shot;
  shot.name = "tiny";
  shot.fps = 24.0;
  shot.seconds = {0.0f, 1.0f / 24.0f};
  MountedPose rest{restWorlds(defaultHorse().skeleton), restWorlds(defaultRider().skeleton), {}, {}};
  MountedPose moved = rest;
  moved.horse[0] = glm::translate(glm::mat4(1.0f), {50, 0, 0}) * moved.horse[0];  // joints are parents first: 0 is a root
  BakedPair pair;
  pair.horse = &defaultHorse();
  pair.rider = &defaultRider();
  pair.poses = {rest, moved};
  shot.pairs = {pair};
  BakedCamera cam;
  cam.name = "side";
  cam.orthographic = true;
  cam.ortho_height_cm = 320.0;
  cam.width = 640;
  cam.height = 360;
  cam.world = {glm::dmat4(1.0), glm::translate(glm::dmat4(1.0), {100, 0, 0})};
  shot.cameras = {cam};
  shot.ground_vertices = {{-100, 0, -100}, {100, 0, -100}, {100, 0, 100}, {-100, 0, 100}};
  shot.ground_indices = {0, 1, 2, 0, 2, 3};
  return shot;
}

std::vector<float> floats(const tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor& a = m.accessors[std::size_t(accessor)];
  const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
  std::vector<float> out(a.count * std::size_t(tinygltf::GetNumComponentsInType(a.type)));
  std::memcpy(out.data(), m.buffers[std::size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset, out.size() * 4);
  return out;
}

int nodeNamed(const tinygltf::Model& m, const std::string& name) {
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes[i].name == name) return int(i);
  return -1;
}

TEST(GltfBake, AShotIsOneRootPerCharacterCamerasAndTheGround) {
  const tinygltf::Model m = stirrup::test::glbModel(bakedShotGlb(twoFrameShot()));
  ASSERT_EQ(m.skins.size(), 2u);
  for (const char* root : {"horse", "rider", "ground"}) {
    const int n = nodeNamed(m, root);
    ASSERT_GE(n, 0) << root;
    EXPECT_EQ(m.nodes[std::size_t(n)].scale, (std::vector<double>{0.01, 0.01, 0.01})) << root;  // cm in a metre world
  }
  EXPECT_EQ(m.skins[0].skeleton, nodeNamed(m, "horse"));
  EXPECT_EQ(m.skins[1].skeleton, nodeNamed(m, "rider"));
  EXPECT_EQ(m.scenes.at(0).extras.Get("fps").GetNumberAsDouble(), 24.0);

  // The camera: half the 320 cm view in metres, 1.6, and that times 640 / 360 across.
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_EQ(m.cameras[0].type, "orthographic");
  EXPECT_NEAR(m.cameras[0].orthographic.ymag, 1.6, 1e-12);
  EXPECT_NEAR(m.cameras[0].orthographic.xmag, 1.6 * 640.0 / 360.0, 1e-12);
  const int cam = nodeNamed(m, "camera:side");
  ASSERT_GE(cam, 0);
  EXPECT_EQ(m.nodes[std::size_t(cam)].extras.Get("width").GetNumberAsInt(), 640);

  // One animation: the horse's root joint and the camera move (translation and rotation each); the
  // rider stands still and has no channels. Times are (frame - 1) / fps.
  ASSERT_EQ(m.animations.size(), 1u);
  const tinygltf::Animation& a = m.animations[0];
  EXPECT_EQ(floats(m, a.samplers.at(0).input), (std::vector<float>{0.0f, 1.0f / 24.0f}));
  const int horse_root = m.skins[0].joints.at(0);
  const std::vector<int>& rider_joints = m.skins[1].joints;
  int root_channels = 0, camera_channels = 0;
  for (const tinygltf::AnimationChannel& ch : a.channels) {
    EXPECT_EQ(std::count(rider_joints.begin(), rider_joints.end(), ch.target_node), 0) << "a rider joint is animated";
    const std::vector<float> out = floats(m, a.samplers[std::size_t(ch.sampler)].output);
    if (ch.target_node == cam) {
      ++camera_channels;
      if (ch.target_path == "translation") {  // 100 cm is 1 m: camera nodes are in metres
        ASSERT_EQ(out.size(), 6u);
        for (int k = 0; k < 6; ++k) EXPECT_NEAR(out[std::size_t(k)], k == 3 ? 1.0f : 0.0f, 1e-6f) << k;
      }
    } else if (ch.target_node == horse_root) {
      ++root_channels;
      if (ch.target_path == "translation") {
        EXPECT_NEAR(out[3] - out[0], 50.0f, 1e-3f);  // joint locals in cm
      }
    }
  }
  EXPECT_EQ(root_channels, 2);
  EXPECT_EQ(camera_channels, 2);

  // The ground: its four corners, normals straight up.
  const tinygltf::Primitive& ground = m.meshes.at(std::size_t(m.nodes[std::size_t(nodeNamed(m, "ground_mesh"))].mesh)).primitives.at(0);
  EXPECT_EQ(floats(m, ground.attributes.at("NORMAL")), (std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}));
}

TEST(GltfBake, OneFrameIsStillAndInconsistentShotsAreRefused) {
  BakedShot one = twoFrameShot();
  one.seconds.resize(1);
  one.pairs[0].poses.resize(1);
  one.cameras[0].world.resize(1);
  EXPECT_TRUE(stirrup::test::glbModel(bakedShotGlb(one)).animations.empty());

  BakedShot bad = twoFrameShot();
  bad.pairs[0].poses.pop_back();
  EXPECT_THROW(bakedShotGlb(bad), std::invalid_argument);
  bad = twoFrameShot();
  bad.seconds = {0.5f, 0.5f};
  EXPECT_THROW(bakedShotGlb(bad), std::invalid_argument);
  bad = twoFrameShot();
  bad.cameras[0].world.pop_back();
  EXPECT_THROW(bakedShotGlb(bad), std::invalid_argument);
  bad = twoFrameShot();
  bad.cameras[0].height = 0;
  EXPECT_THROW(bakedShotGlb(bad), std::invalid_argument);
}

// The horse's tack beside its body: a node a part, named as the part, skinned by the horse's skin, its
// extras saying what it is and which horse it fits, its materials named after it in the colours stirrup
// renders it in; in a crowd each pair's prefixed by the pair's name, as its body's are.
TEST(GltfBake, TheTackIsANodeAPartOfTheHorsesSkin) {
  const HorseParams hp;
  for (const std::string pair_name : {"", "pair03"}) {
    BakedShot shot = twoFrameShot();
    shot.pairs[0].name = pair_name;
    const tinygltf::Model m = stirrup::test::glbModel(bakedShotGlb(shot));
    const std::string named = pair_name.empty() ? "" : pair_name + "_";
    for (const TackPart part : kTackParts) {
      const std::string name(tackPartName(part));
      int n = -1;  // the mesh node (the saddle's rig point is a joint node "saddle" too)
      for (std::size_t i = 0; i < m.nodes.size(); ++i)
        if (m.nodes[i].name == named + name && m.nodes[i].mesh >= 0) n = int(i);
      ASSERT_GE(n, 0) << named + name;
      const tinygltf::Node& node = m.nodes[std::size_t(n)];
      EXPECT_EQ(node.skin, 0) << name;
      EXPECT_EQ(node.extras.Get("stirrup_tack").Get<std::string>(), name);
      EXPECT_EQ(node.extras.Get("stirrup_fits").Get<std::string>(), named + "horse");
      EXPECT_FALSE(node.extras.Has("stirrup_fits_file")) << "the generated horse comes from no file";
      const tinygltf::Mesh& mesh = m.meshes.at(std::size_t(node.mesh));
      EXPECT_EQ(mesh.name, named + name);
      ASSERT_FALSE(mesh.primitives.empty());
      EXPECT_EQ(m.materials.at(std::size_t(mesh.primitives[0].material)).name, named + name);
      // Its colours, one primitive each in the order its triangles first show them: the pad's navy and
      // the flaps' leather for the pad, metal for the bit and irons, leather for the rest.
      const bool metal = part == TackPart::Bit || part == TackPart::StirrupIronL || part == TackPart::StirrupIronR;
      const std::set<std::array<float, 3>> want = part == TackPart::SaddlePad ? std::set<std::array<float, 3>>{{hp.pad.x, hp.pad.y, hp.pad.z}, {hp.leather.x, hp.leather.y, hp.leather.z}}
                                                  : metal ? std::set<std::array<float, 3>>{{hp.metal.x, hp.metal.y, hp.metal.z}}
                                                          : std::set<std::array<float, 3>>{{hp.leather.x, hp.leather.y, hp.leather.z}};
      std::set<std::array<float, 3>> got;
      for (const tinygltf::Primitive& prim : mesh.primitives) {
        const std::vector<double>& c = m.materials.at(std::size_t(prim.material)).pbrMetallicRoughness.baseColorFactor;
        got.insert({float(c[0]), float(c[1]), float(c[2])});
      }
      EXPECT_EQ(got, want) << name;
      EXPECT_EQ(mesh.primitives.size(), want.size()) << name << ": one primitive a colour";
      if (part == TackPart::SaddlePad) {
        EXPECT_EQ(m.materials.at(std::size_t(mesh.primitives[1].material)).name, named + name + ".001");
      }
      const std::vector<int>& in_scene = m.scenes.at(0).nodes;
      EXPECT_EQ(std::count(in_scene.begin(), in_scene.end(), n), 1) << name;
    }
  }
}

// The tack's rig points are joints of the horse's skin, keyed at every frame where stirrup poses them:
// the bake of the default pair's trot has each rein's hand end in her hand and each tread at the ball of
// her foot (rig::placeReins, rig::placeStirrups), within what the foot's leg solve leaves.
TEST(GltfBake, TheTackJointsAreKeyedInHerHandsAndAtHerFeet) {
  const tinygltf::Model m = stirrup::test::readGlbModel(test::bakedTrot().file);
  const GltfAnimation animation = GltfAnimation::together(m, "trot.glb");
  const auto joint = [&](int skin, const std::string& name) {
    for (const int j : m.skins.at(std::size_t(skin)).joints)
      if (m.nodes[std::size_t(j)].name == name) return j;
    ADD_FAILURE() << "no joint " << name << " in skins[" << skin << "]";
    return 0;
  };
  std::size_t keyed = 0;
  for (const char* tack : {"saddle", "lStirrup", "rStirrup", "lRein", "rRein"}) keyed += animation.animates(joint(0, tack));
  EXPECT_EQ(keyed, 5u) << "every tack joint moves with the trot";
  double hands = 0.0, feet = 0.0;
  for (int f = 0; f < test::kFrames; ++f) {
    const std::vector<glm::dmat4> w = animation.worlds(f / test::kFps);
    const auto at = [&](int node) { return glm::dvec3(w[std::size_t(node)][3]) * 100.0; };  // metres to cm
    for (const char* side : {"l", "r"}) {
      hands = std::max(hands, glm::length(at(joint(0, std::string(side) + "Rein")) - at(joint(1, std::string(side) + "Hand"))));
      feet = std::max(feet, glm::length(at(joint(0, std::string(side) + "Stirrup")) - at(joint(1, std::string(side) + "Ball"))));
    }
  }
  EXPECT_LT(hands, 1e-3) << "cm";
  EXPECT_LT(feet, 1.0) << "cm";
  std::printf("the trot's tack joints: rein ends within %.5f cm of her hands, treads within %.3f cm of her balls\n", hands, feet);
}

}  // namespace
}  // namespace stirrup::rig
