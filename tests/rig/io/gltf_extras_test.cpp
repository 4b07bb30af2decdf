// glTF extras written as stirrup holds them (rig/io/gltf_extras.cpp): tinygltf alone writes an empty list
// or object as null; through glbBytes (every GLB stirrup writes) they stay [] and {}, the rest of the file
// as tinygltf wrote it, and a file without empty extras is tinygltf's to the byte.
#include "rig/io/gltf_extras.h"

#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_writer.h"
#include "rig/characters/seating.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

// A model of one node holding `extras` and a 4-byte buffer.
tinygltf::Model modelWith(const tinygltf::Value& extras) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  tinygltf::Node node;
  node.name = "n";
  node.extras = extras;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

nlohmann::json jsonChunk(const std::vector<unsigned char>& glb) {
  std::uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + length);
}

std::vector<unsigned char> tinygltfBytes(tinygltf::Model model, const std::vector<unsigned char>& bin) {
  tinygltf::Buffer buffer;
  buffer.data = bin;
  model.buffers = {buffer};
  tinygltf::TinyGLTF gltf;
  std::ostringstream os;
  gltf.WriteGltfSceneToStream(&model, os, false, true);
  const std::string s = os.str();
  return {s.begin(), s.end()};
}

TEST(GltfExtras, EmptyListsAndObjectsStayEmptyListsAndObjects) {
  tinygltf::Value::Object extras;
  extras["added_points"] = tinygltf::Value(tinygltf::Value::Array{});
  extras["settings"] = tinygltf::Value(tinygltf::Value::Object{});
  extras["nested"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(1), tinygltf::Value(tinygltf::Value::Array{})});
  extras["name"] = tinygltf::Value(std::string("x"));
  tinygltf::Model model = modelWith(tinygltf::Value(extras));
  const std::vector<unsigned char> bin = {1, 2, 3, 4};
  // tinygltf alone: null (what a seat record with no notes used to say).
  EXPECT_TRUE(jsonChunk(tinygltfBytes(model, bin))["nodes"][0]["extras"]["added_points"].is_null());
  const std::vector<unsigned char> glb = glbBytes(model, bin);
  const nlohmann::json j = jsonChunk(glb);
  const nlohmann::json& e = j["nodes"][0]["extras"];
  EXPECT_EQ(e["added_points"], nlohmann::json::array());
  EXPECT_EQ(e["settings"], nlohmann::json::object());
  EXPECT_EQ(e["nested"], nlohmann::json::parse("[1, []]"));
  EXPECT_EQ(e["name"], "x");
  // The rest of the file is whole: tinygltf reads it, its buffer the bytes written.
  const tinygltf::Model back = stirrup::test::glbModel(glb);
  ASSERT_EQ(back.buffers.size(), 1u);
  EXPECT_EQ(back.buffers[0].data, bin);
  EXPECT_EQ(back.nodes[0].name, "n");
  std::uint32_t total = 0;
  std::memcpy(&total, glb.data() + 8, 4);
  EXPECT_EQ(total, glb.size());
}

TEST(GltfExtras, AFileWithoutEmptyExtrasIsTinygltfsToTheByte) {
  tinygltf::Value::Object extras;
  extras["fps"] = tinygltf::Value(24.0);
  extras["points"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(std::string("lGrip"))});
  tinygltf::Model model = modelWith(tinygltf::Value(extras));
  const std::vector<unsigned char> bin = {9, 8, 7, 6};
  EXPECT_EQ(glbBytes(model, bin), tinygltfBytes(model, bin));
}

// The seat record a bake writes for a rider the rig fitted: its lists as lists, empty or not.
TEST(GltfExtras, ASeatRecordsEmptyListsAreLists) {
  SeatReport fitted;
  fitted.fitted_to_horse = true;
  tinygltf::Value::Object extras;
  extras["stirrup_seat"] = seatExtras(fitted);
  tinygltf::Model model = modelWith(tinygltf::Value(extras));
  const nlohmann::json seat = jsonChunk(glbBytes(model, {0, 0, 0, 0}))["nodes"][0]["extras"]["stirrup_seat"];
  EXPECT_EQ(seat["added_points"], nlohmann::json::array());
  EXPECT_EQ(seat["notes"], nlohmann::json::array());
  EXPECT_EQ(seat["fitted_to_horse"], true);
}

}  // namespace
}  // namespace stirrup::rig
