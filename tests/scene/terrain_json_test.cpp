// A scene's "terrain" object (scene/terrain_json.cpp): hills by their parameters, a glTF mesh relative
// to the scene's folder, and one-line errors naming the file and the field.
#include "scene/terrain_json.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

std::shared_ptr<const rig::Terrain> parse(const nlohmann::json& j, const fs::path& base = ".") {
  rig::JsonObjectReader r("scenes/x.json", "terrain", j);
  return parseTerrain(r, base);
}
std::string parseError(const nlohmann::json& j, const fs::path& base = ".") {
  return errorOf([&] { parse(j, base); });
}

// A 10 m square of ground 0.5 m up (metres, as glTF has it), two triangles.
void writeShelf(const fs::path& file) {
  const std::vector<float> positions = {0, 0.5f, 0, 10, 0.5f, 0, 10, 0.5f, 10, 0, 0.5f, 10};
  const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
  tinygltf::Model m;
  tinygltf::Buffer b;
  b.data.resize(positions.size() * sizeof(float) + indices.size() * sizeof(std::uint16_t));
  std::memcpy(b.data.data(), positions.data(), positions.size() * sizeof(float));
  std::memcpy(b.data.data() + positions.size() * sizeof(float), indices.data(), indices.size() * sizeof(std::uint16_t));
  m.buffers.push_back(b);
  tinygltf::BufferView pv, iv;
  pv.buffer = iv.buffer = 0;
  pv.byteLength = positions.size() * sizeof(float);
  iv.byteOffset = pv.byteLength;
  iv.byteLength = indices.size() * sizeof(std::uint16_t);
  m.bufferViews = {pv, iv};
  tinygltf::Accessor pa, ia;
  pa.bufferView = 0;
  pa.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pa.type = TINYGLTF_TYPE_VEC3;
  pa.count = 4;
  ia.bufferView = 1;
  ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  ia.type = TINYGLTF_TYPE_SCALAR;
  ia.count = 6;
  m.accessors = {pa, ia};
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = 0;
  prim.indices = 1;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  m.meshes.push_back({});
  m.meshes[0].primitives.push_back(prim);
  tinygltf::Node node;
  node.mesh = 0;
  m.nodes = {node};
  m.scenes.push_back({});
  m.scenes[0].nodes = {0};
  m.defaultScene = 0;
  m.asset.version = "2.0";
  tinygltf::TinyGLTF w;
  ASSERT_TRUE(w.WriteGltfSceneToFile(&m, file.string(), true, true, true, true));
}

TEST(TerrainJson, HillsTakeTheirParameters) {
  const auto flat_hills = parse({{"hills", {{"seed", 3}, {"amplitude_cm", 0}, {"wavelength_cm", 3000}, {"octaves", 2}}}});
  ASSERT_TRUE(flat_hills);
  EXPECT_FALSE(flat_hills->flat());  // hills, if of no height
  for (double x : {0.0, 1234.5, -9000.0}) EXPECT_EQ(flat_hills->height(x, 0.5 * x), 0.0) << x;
  // 80 cm hills: within 80 cm of 0 everywhere, and not level.
  const auto hills = parse({{"hills", {{"seed", 3}, {"amplitude_cm", 80}}}});
  double lo = 0.0, hi = 0.0;
  for (double x = 0.0; x < 20000.0; x += 97.0) {
    const double h = hills->height(x, 3000.0);
    lo = std::min(lo, h), hi = std::max(hi, h);
  }
  EXPECT_GE(lo, -80.0);
  EXPECT_LE(hi, 80.0);
  EXPECT_GT(hi - lo, 20.0);
  // The seed picks the hills.
  const auto other = parse({{"hills", {{"seed", 4}, {"amplitude_cm", 80}}}});
  EXPECT_NE(other->height(1500.0, 2500.0), hills->height(1500.0, 2500.0));
}

TEST(TerrainJson, AFileIsAMeshRelativeToTheScene) {
  const fs::path dir = fs::temp_directory_path() / ("stirrup_terrain_json_test_" + std::to_string(::getpid()));
  fs::create_directories(dir / "ground");
  writeShelf(dir / "ground" / "shelf.glb");
  const auto t = parse({{"file", "ground/shelf.glb"}}, dir);
  ASSERT_TRUE(t->triangles());
  EXPECT_NEAR(t->height(500.0, 500.0), 50.0, 1e-3);  // 0.5 m is 50 cm
  EXPECT_TRUE(t->covers(999.0, 1.0));
  EXPECT_FALSE(t->covers(1001.0, 500.0));
  EXPECT_EQ(parseError({{"file", "ground/none.glb"}}, dir),
            "scenes/x.json: terrain.file: " + (dir / "ground" / "none.glb").string() +
                ": no such file (expected a glTF terrain mesh)");
  fs::remove_all(dir);
}

TEST(TerrainJson, BadObjectsAreOneLineErrorsNamingTheField) {
  EXPECT_EQ(parseError(nlohmann::json::object()),
            "scenes/x.json: terrain.hills: expected \"hills\": {\"seed\", \"amplitude_cm\", \"wavelength_cm\", \"octaves\"} "
            "or \"file\": a glTF mesh");
  EXPECT_EQ(parseError({{"file", "a.glb"}, {"hills", nlohmann::json::object()}}),
            "scenes/x.json: terrain.file: expected either \"file\" or \"hills\", not both");
  EXPECT_EQ(parseError({{"hills", {{"seed", -1}}}}),
            "scenes/x.json: terrain.hills.seed: expected a whole number from 0 to 2147483647, got -1");
  EXPECT_EQ(parseError({{"hills", {{"bumps", 3}}}}), "scenes/x.json: terrain.hills.bumps: unknown field");
  EXPECT_EQ(parseError({{"hills", nlohmann::json::object()}, {"slope", 2}}), "scenes/x.json: terrain.slope: unknown field");
  EXPECT_EQ(parseError({{"hills", {{"octaves", 9}}}}),
            "scenes/x.json: terrain.hills.octaves: expected a whole number from 1 to 6, got 9");
}

}  // namespace
}  // namespace stirrup::scene
