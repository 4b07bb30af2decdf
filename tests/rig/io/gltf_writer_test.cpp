// The one glTF writer (rig/io/gltf_writer.cpp): aligned buffer views, accessors with per-component
// bounds, animation channels, and files that tinygltf reads back as written, binary and text.
#include "rig/io/gltf_writer.h"

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

namespace stirrup::rig {
namespace {

// A model of one node and one animation sliding it, written through the writer.
tinygltf::Model slidingNode(std::vector<unsigned char>& bin) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  tinygltf::Node node;
  node.name = "slider";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  tinygltf::Animation anim;
  anim.name = "slide";
  const int input = appendFloatAccessor(model, bin, {0.0f, 0.5f, 1.0f}, 1, true);
  appendLinearChannel(model, bin, anim, input, 0, "translation", {0, 0, 0, 1, 2, 0, 2, 4, 0}, 3);
  model.animations.push_back(anim);
  return model;
}

std::vector<float> floatsOf(const tinygltf::Model& model, int accessor) {
  const tinygltf::Accessor& a = model.accessors[std::size_t(accessor)];
  const tinygltf::BufferView& v = model.bufferViews[std::size_t(a.bufferView)];
  const auto* p = reinterpret_cast<const float*>(model.buffers[std::size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset);
  return std::vector<float>(p, p + v.byteLength / sizeof(float));
}

TEST(GltfWriter, BufferViewsStartFourByteAligned) {
  tinygltf::Model model;
  std::vector<unsigned char> bin;
  const unsigned char three[3] = {1, 2, 3};
  EXPECT_EQ(appendBytes(model, bin, three, 3, 0), 0);
  EXPECT_EQ(appendBytes(model, bin, three, 3, TINYGLTF_TARGET_ARRAY_BUFFER), 1);
  EXPECT_EQ(model.bufferViews[1].byteOffset, 4u);
  EXPECT_EQ(model.bufferViews[1].target, TINYGLTF_TARGET_ARRAY_BUFFER);
  EXPECT_EQ(bin.size(), 7u);
  EXPECT_EQ(bin[3], 0);  // the padding
}

TEST(GltfWriter, FloatAccessorsCarryEachComponentsBounds) {
  tinygltf::Model model;
  std::vector<unsigned char> bin;
  const int a = appendFloatAccessor(model, bin, {1, -2, 3, -4, 5, -6}, 3, true);
  const tinygltf::Accessor& acc = model.accessors[std::size_t(a)];
  EXPECT_EQ(acc.type, TINYGLTF_TYPE_VEC3);
  EXPECT_EQ(acc.count, 2u);
  EXPECT_EQ(acc.minValues, (std::vector<double>{-4, -2, -6}));
  EXPECT_EQ(acc.maxValues, (std::vector<double>{1, 5, 3}));
  const int b = appendFloatAccessor(model, bin, std::vector<float>(16, 1.0f), 16, false);
  EXPECT_EQ(model.accessors[std::size_t(b)].type, TINYGLTF_TYPE_MAT4);
  EXPECT_TRUE(model.accessors[std::size_t(b)].minValues.empty());
  EXPECT_THROW(appendFloatAccessor(model, bin, {1, 2, 3, 4, 5}, 5, false), std::invalid_argument);
}

TEST(GltfWriter, IntegerAccessorsKeepTheirWidth) {
  tinygltf::Model model;
  std::vector<unsigned char> bin;
  const int joints = appendIntegerAccessor(model, bin, std::vector<std::uint8_t>{0, 1, 2, 3, 4, 5, 6, 7},
                                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER);
  EXPECT_EQ(model.accessors[std::size_t(joints)].count, 2u);
  EXPECT_EQ(model.bufferViews[std::size_t(model.accessors[std::size_t(joints)].bufferView)].byteLength, 8u);
  const int indices = appendIndexAccessor(model, bin, {0, 1, 2});
  EXPECT_EQ(model.accessors[std::size_t(indices)].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  EXPECT_EQ(model.accessors[std::size_t(indices)].count, 3u);
  EXPECT_EQ(model.bufferViews[std::size_t(model.accessors[std::size_t(indices)].bufferView)].target,
            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
}

TEST(GltfWriter, TheCentimetreRootScalesToMetres) {
  tinygltf::Model model;
  const int root = addCentimetreRoot(model, "horse");
  EXPECT_EQ(model.nodes[std::size_t(root)].name, "horse");
  EXPECT_EQ(model.nodes[std::size_t(root)].scale, (std::vector<double>{0.01, 0.01, 0.01}));
}

// Both file forms load back in tinygltf with the animation's keys as written.
TEST(GltfWriter, GlbAndTextFilesReadBackAsWritten) {
  for (const bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "glb" : "gltf");
    std::vector<unsigned char> bin;
    tinygltf::Model written = slidingNode(bin);
    const std::vector<unsigned char> bytes = binary ? glbBytes(written, bin) : gltfTextBytes(written, bin);
    ASSERT_GE(bytes.size(), 4u);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), binary ? "glTF" : "{\n  ");
    tinygltf::TinyGLTF loader;
    tinygltf::Model read;
    std::string err, warn;
    const bool ok = binary ? loader.LoadBinaryFromMemory(&read, &err, &warn, bytes.data(), unsigned(bytes.size()))
                           : loader.LoadASCIIFromString(&read, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                        unsigned(bytes.size()), "");
    ASSERT_TRUE(ok) << err;
    ASSERT_EQ(read.animations.size(), 1u);
    const tinygltf::AnimationChannel& ch = read.animations[0].channels.at(0);
    EXPECT_EQ(ch.target_node, 0);
    EXPECT_EQ(ch.target_path, "translation");
    const tinygltf::AnimationSampler& s = read.animations[0].samplers.at(std::size_t(ch.sampler));
    EXPECT_EQ(s.interpolation, "LINEAR");
    EXPECT_EQ(floatsOf(read, s.input), (std::vector<float>{0.0f, 0.5f, 1.0f}));
    EXPECT_EQ(floatsOf(read, s.output), (std::vector<float>{0, 0, 0, 1, 2, 0, 2, 4, 0}));
    EXPECT_EQ(read.accessors[std::size_t(s.input)].maxValues, (std::vector<double>{1.0}));
  }
}

}  // namespace
}  // namespace stirrup::rig
