// One skin's joints in stirrup's world (rig/io/gltf_skin_joints.cpp) on a small file laid out as a
// bake is: two joints under a node scaled 0.01 (glTF metres), bound in centimetres. Each value worked
// out by hand; and the one-line error for a skin bound mirrored.
#include "rig/io/gltf_skin_joints.h"

#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/io/gltf_animation.h"
#include "tests/expect_near.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

// "armature" (scale 0.01) > "root" at (0, 100, 0) > "tip" 50 along +X; the skin binds root at (0, 100, 0)
// cm and tip at (50, 100, 0) cm: its inverse bind matrices are those translations undone.
tinygltf::Model bakeLike() {
  tinygltf::Model m;
  tinygltf::Node armature, root, tip;
  armature.name = "armature";
  armature.scale = {0.01, 0.01, 0.01};
  armature.children = {1};
  root.name = "root";
  root.translation = {0, 100, 0};
  root.children = {2};
  tip.name = "tip";
  tip.translation = {50, 0, 0};
  m.nodes = {armature, root, tip};
  const glm::mat4 ibm[2] = {glm::translate(glm::mat4(1.0f), {0, -100, 0}), glm::translate(glm::mat4(1.0f), {-50, -100, 0})};
  m.buffers.emplace_back();
  m.buffers[0].data.resize(sizeof ibm);
  std::memcpy(m.buffers[0].data.data(), ibm, sizeof ibm);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteLength = sizeof ibm;
  m.bufferViews.push_back(v);
  tinygltf::Accessor a;
  a.bufferView = 0;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_MAT4;
  a.count = 2;
  m.accessors.push_back(a);
  tinygltf::Skin skin;
  skin.joints = {1, 2};
  skin.inverseBindMatrices = 0;
  m.skins.push_back(skin);
  return m;
}

// Centimetres from float keys and matrices.
void expectNear(const glm::dvec3& a, const glm::dvec3& b) { test::expectNear(a, b, 1e-4); }

TEST(GltfSkinJoints, AJointStandsWhereItsNodeIsInCentimetres) {
  tinygltf::Model m = bakeLike();
  // The rest world of root (0.01 x its place) times its inverse bind: a scale of 0.01, the file's world
  // in metres against a mesh in centimetres.
  EXPECT_NEAR(gltfSkinUnits(m, "x.glb", 0, 0, GltfAnimation::together(m, "x.glb")), 0.01, 1e-9);
  const GltfSkinJoints joints(m, "x.glb", 0, glm::dmat4(1.0), 0.01);
  EXPECT_EQ(joints.names(), (std::vector<std::string>{"root", "tip"}));
  EXPECT_FALSE(joints.joint("hoof"));
  const std::optional<GltfFileJoint> tip = joints.joint("tip");
  ASSERT_TRUE(tip);
  EXPECT_EQ(tip->node, 2);
  expectNear(tip->rest, {50, 100, 0});
  // At rest it stands at its bind place, unturned.
  const glm::dmat4 rest = joints.posed(*tip, GltfAnimation::together(m, "x.glb").world(2, std::nullopt));
  expectNear(glm::dvec3(rest[3]), {50, 100, 0});
  expectNear(glm::dvec3(rest[0]), {1, 0, 0});
  // Root turned 90 degrees about +Y: the tip swings from +X to -Z of it, (0, 100, -50) cm, its own +X
  // turned to -Z.
  const double h = std::sqrt(0.5);
  m.nodes[1].rotation = {0, h, 0, h};
  const glm::dmat4 turned = joints.posed(*tip, GltfAnimation::together(m, "x.glb").world(2, std::nullopt));
  expectNear(glm::dvec3(turned[3]), {0, 100, -50});
  expectNear(glm::dvec3(turned[0]), {0, 0, -1});
}

// A file whose mesh is in metres (as Blender writes one: no scaled node) read 100 cm a unit lands in
// the same place.
TEST(GltfSkinJoints, AFileInMetresLandsInTheSamePlace) {
  tinygltf::Model m = bakeLike();
  m.nodes[0].scale.clear();
  m.nodes[1].translation = {0, 1, 0};
  m.nodes[2].translation = {0.5, 0, 0};
  const glm::mat4 ibm[2] = {glm::translate(glm::mat4(1.0f), {0, -1, 0}), glm::translate(glm::mat4(1.0f), {-0.5f, -1, 0})};
  std::memcpy(m.buffers[0].data.data(), ibm, sizeof ibm);
  const double units = gltfSkinUnits(m, "x.glb", 0, 0, GltfAnimation::together(m, "x.glb"));
  EXPECT_NEAR(units, 1.0, 1e-9);
  const GltfSkinJoints joints(m, "x.glb", 0, glm::scale(glm::dmat4(1.0), glm::dvec3(100.0)), units);
  const std::optional<GltfFileJoint> tip = joints.joint("tip");
  ASSERT_TRUE(tip);
  expectNear(tip->rest, {50, 100, 0});
  expectNear(glm::dvec3(joints.posed(*tip, GltfAnimation::together(m, "x.glb").world(2, std::nullopt))[3]), {50, 100, 0});
}

TEST(GltfSkinJoints, AMirroredBindIsAOneLineError) {
  tinygltf::Model m = bakeLike();
  m.nodes[0].scale = {-0.01, 0.01, 0.01};
  EXPECT_EQ(test::errorOf([&] { gltfSkinUnits(m, "x.glb", 0, 0, GltfAnimation::together(m, "x.glb")); }),
            "x.glb: skins[0]: the joint \"root\" is bound with no size or mirrored (its inverse bind matrix and rest transform "
            "multiply to a determinant of -1e-06; expected a positive scale)");
}

}  // namespace
}  // namespace stirrup::rig
