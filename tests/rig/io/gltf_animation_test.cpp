// One glTF animation sampled (rig/io/gltf_animation.h) on small models written here: a parent that
// slides and a child that turns, each value worked out by hand; STEP and CUBICSPLINE keys; a node given
// as a matrix; and one-line errors naming the file, the animation and the sampler or channel.
#include "rig/io/gltf_animation.h"

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "tests/expect_near.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

using test::errorOf;

// Appends floats as a view and accessor of `type`; returns the accessor.
int addFloats(tinygltf::Model& m, const std::vector<float>& values, int type) {
  if (m.buffers.empty()) m.buffers.emplace_back();
  std::vector<unsigned char>& data = m.buffers[0].data;
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = data.size();
  v.byteLength = values.size() * 4;
  data.resize(data.size() + v.byteLength);
  std::memcpy(data.data() + v.byteOffset, values.data(), v.byteLength);
  m.bufferViews.push_back(v);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = type;
  a.count = values.size() / static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

void addChannel(tinygltf::Model& m, tinygltf::Animation& a, int node, const char* path, const std::vector<float>& times,
                const std::vector<float>& values, const char* interpolation = "LINEAR") {
  tinygltf::AnimationSampler s;
  s.input = addFloats(m, times, TINYGLTF_TYPE_SCALAR);
  s.output = addFloats(m, values, std::string(path) == "rotation" ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3);
  s.interpolation = interpolation;
  a.samplers.push_back(s);
  tinygltf::AnimationChannel c;
  c.sampler = static_cast<int>(a.samplers.size()) - 1;
  c.target_node = node;
  c.target_path = path;
  a.channels.push_back(c);
}

// A parent at (1, 0, 0) sliding to (3, 0, 0) over 2 s; its child 1 along +X, turning 90 degrees about +Y
// over the same 2 s; a second animation named "Other".
tinygltf::Model slideAndTurn() {
  tinygltf::Model m;
  tinygltf::Node parent, child;
  parent.name = "parent";
  parent.translation = {1, 0, 0};
  parent.children = {1};
  child.name = "child";
  child.translation = {1, 0, 0};
  m.nodes = {parent, child};
  tinygltf::Animation a;
  a.name = "Slide";
  addChannel(m, a, 0, "translation", {0, 2}, {1, 0, 0, 3, 0, 0});
  const float h = float(std::sqrt(0.5));
  addChannel(m, a, 1, "rotation", {0, 2}, {0, 0, 0, 1, 0, h, 0, h});
  m.animations.push_back(a);
  tinygltf::Animation other;
  other.name = "Other";
  m.animations.push_back(other);
  return m;
}

using test::expectNear;

TEST(GltfAnimation, NodesMoveAsTheirKeysSay) {
  const GltfAnimation a(slideAndTurn(), "x.glb", "");
  EXPECT_EQ(a.name(), "Slide");
  EXPECT_DOUBLE_EQ(a.duration(), 2.0);
  EXPECT_TRUE(a.animates(0));
  // Halfway: the parent at x = 2; the child turned 45 degrees about +Y, its own origin 1 ahead of the parent's.
  expectNear(glm::dvec3(a.world(0, 1.0)[3]), {2, 0, 0});
  expectNear(glm::dvec3(a.world(1, 1.0)[3]), {3, 0, 0});
  // The child's +X after a 45-degree turn about +Y points to (cos 45, 0, -sin 45).
  const glm::dvec3 x_axis = glm::dvec3(a.world(1, 1.0) * glm::dvec4(1, 0, 0, 0));
  expectNear(x_axis, {std::sqrt(0.5), 0, -std::sqrt(0.5)});
  // Before the first key and after the last, the ends hold; with no time, the rest.
  expectNear(glm::dvec3(a.world(0, -1.0)[3]), {1, 0, 0});
  expectNear(glm::dvec3(a.world(0, 9.0)[3]), {3, 0, 0});
  expectNear(glm::dvec3(a.world(1, std::nullopt)[3]), {2, 0, 0});
  // worlds() gives the same as world() for every node.
  const std::vector<glm::dmat4> all = a.worlds(1.5);
  for (int n = 0; n < 2; ++n) expectNear(glm::dvec3(all[std::size_t(n)][3]), glm::dvec3(a.world(n, 1.5)[3]));
}

TEST(GltfAnimation, StepAndCubicKeys) {
  tinygltf::Model m;
  m.nodes.resize(2);
  tinygltf::Animation a;
  addChannel(m, a, 0, "translation", {0, 1}, {0, 0, 0, 4, 0, 0}, "STEP");
  // Hermite from 0 to 1 over 1 s with zero tangents: 0.5 at the middle, 0.15625 at a quarter (3u^2 - 2u^3).
  addChannel(m, a, 1, "translation", {0, 1}, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0}, "CUBICSPLINE");
  m.animations.push_back(a);
  const GltfAnimation anim(m, "x.glb", "");
  EXPECT_DOUBLE_EQ(anim.world(0, 0.99)[3].x, 0.0);
  EXPECT_DOUBLE_EQ(anim.world(0, 1.0)[3].x, 4.0);
  EXPECT_NEAR(anim.world(1, 0.5)[3].y, 0.5, 1e-6);
  EXPECT_NEAR(anim.world(1, 0.25)[3].y, 0.15625, 1e-6);
  EXPECT_DOUBLE_EQ(anim.start(), 0.0);
}

// Blender's exporter keys frame F at F / fps: an animation of frames 1-48 starts at 1/24 s.
TEST(GltfAnimation, ItStartsAtItsFirstKey) {
  tinygltf::Model m;
  m.nodes.resize(2);
  tinygltf::Animation a;
  addChannel(m, a, 0, "translation", {1.0f / 24, 2.0f}, {0, 0, 0, 1, 0, 0});
  addChannel(m, a, 1, "translation", {0.5f, 1.0f}, {0, 0, 0, 1, 0, 0});
  m.animations.push_back(a);
  const GltfAnimation anim(m, "x.glb", "");
  EXPECT_FLOAT_EQ(float(anim.start()), 1.0f / 24);
  EXPECT_DOUBLE_EQ(anim.duration(), 2.0);
}

TEST(GltfAnimation, AnAnimationByName) {
  EXPECT_EQ(GltfAnimation(slideAndTurn(), "x.glb", "Other").name(), "Other");
  EXPECT_EQ(GltfAnimation(slideAndTurn(), "x.glb", "Other").duration(), 0.0);
  EXPECT_EQ(errorOf([] { GltfAnimation(slideAndTurn(), "x.glb", "Walk"); }),
            "x.glb: no animation named \"Walk\" (the file has \"Slide\", \"Other\")");
  tinygltf::Model none = slideAndTurn();
  none.animations.clear();
  EXPECT_EQ(errorOf([&] { GltfAnimation(none, "x.glb", ""); }), "x.glb: the file has no animation");
}

// A shot Blender split into one animation an armature plays together: "Slide" keys the parent, "Turn"
// (from 1/24 s to 3 s) the child; "Retake" keys the parent again and is left out as another take.
TEST(GltfAnimation, AnimationsKeyingTheirOwnNodesPlayTogether) {
  tinygltf::Model m;
  tinygltf::Node parent, child;
  parent.translation = {1, 0, 0};
  parent.children = {1};
  child.translation = {1, 0, 0};
  m.nodes = {parent, child};
  tinygltf::Animation slide, turn, retake;
  slide.name = "Slide";
  addChannel(m, slide, 0, "translation", {0, 2}, {1, 0, 0, 3, 0, 0});
  turn.name = "Turn";
  const float h = float(std::sqrt(0.5));
  addChannel(m, turn, 1, "rotation", {1.0f / 24, 3}, {0, 0, 0, 1, 0, h, 0, h});
  retake.name = "Retake";
  addChannel(m, retake, 0, "translation", {0, 1}, {0, 0, 0, 0, 9, 0});
  m.animations = {slide, turn, retake};
  const GltfAnimation a = GltfAnimation::together(m, "x.glb");
  EXPECT_EQ(a.name(), "Slide + Turn");
  EXPECT_EQ(a.played(), (std::vector<std::string>{"Slide", "Turn"}));
  EXPECT_EQ(a.leftOut(), (std::vector<std::string>{"Retake"}));
  EXPECT_DOUBLE_EQ(a.start(), 0.0);
  EXPECT_DOUBLE_EQ(a.duration(), 3.0);
  // At 3 s: the parent held at its last key, x = 3 (not Retake's y = 9); the child turned 90 degrees
  // about +Y, its +X now -Z.
  expectNear(glm::dvec3(a.world(0, 3.0)[3]), {3, 0, 0});
  expectNear(glm::dvec3(a.world(1, 3.0) * glm::dvec4(1, 0, 0, 0)), {0, 0, -1});
  // A file without animations rests.
  m.animations.clear();
  const GltfAnimation still = GltfAnimation::together(m, "x.glb");
  EXPECT_EQ(still.name(), "");
  EXPECT_DOUBLE_EQ(still.duration(), 0.0);
  expectNear(glm::dvec3(still.world(1, 1.0)[3]), {2, 0, 0});
}

TEST(GltfAnimation, BadChannelsAndSamplersAreOneLineErrors) {
  const auto broken = [](auto change) {
    tinygltf::Model m = slideAndTurn();
    change(m);
    return errorOf([&] { GltfAnimation(m, "x.glb", ""); });
  };
  EXPECT_EQ(broken([](tinygltf::Model& m) { m.animations[0].samplers[0].interpolation = "BEZIER"; }),
            "x.glb: animation \"Slide\": sampler 0: interpolation: expected LINEAR, STEP or CUBICSPLINE, got \"BEZIER\"");
  EXPECT_EQ(broken([](tinygltf::Model& m) { m.animations[0].channels[1].target_node = 7; }),
            "x.glb: animation \"Slide\": channels[1].target.node: expected a node index 0..1, got 7");
  EXPECT_EQ(broken([](tinygltf::Model& m) { m.animations[0].channels[0].sampler = 5; }),
            "x.glb: animation \"Slide\": channels[0].sampler: expected a sampler index 0..1, got 5");
  EXPECT_EQ(broken([](tinygltf::Model& m) { m.animations[0].samplers[0].output = 40; }),
            "x.glb: animation \"Slide\": sampler 0: output: accessor 40: no such accessor (the file has 4)");
  // Key times that go back.
  EXPECT_EQ(broken([](tinygltf::Model& m) {
              const float back[2] = {0.0f, -1.0f};
              std::memcpy(m.buffers[0].data.data(), back, 8);
            }),
            "x.glb: animation \"Slide\": sampler 0: input: key times must increase (key 1)");
  // Three keys of output for two times.
  EXPECT_EQ(broken([](tinygltf::Model& m) { m.accessors[1].count = 1; }),
            "x.glb: animation \"Slide\": sampler 0: output: expected 2 elements for 2 keys, got 1");
}

}  // namespace
}  // namespace stirrup::rig
