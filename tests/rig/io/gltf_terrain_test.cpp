#include "rig/io/gltf_terrain.h"

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

fs::path dir() {
  const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "test-out" / "gltf_terrain";
  fs::create_directories(d);
  return d;
}

// A glTF as another tool writes it: metres, one mesh of the given positions and indices under a node
// moved by `translation` (metres) and scaled by `scale`.
fs::path writeGltf(const std::string& name, const std::vector<float>& positions, const std::vector<std::uint16_t>& indices,
                   std::vector<double> translation = {0, 0, 0}, std::vector<double> scale = {1, 1, 1}, int mode = 4) {
  tinygltf::Model m;
  tinygltf::Buffer b;
  const auto* p = reinterpret_cast<const unsigned char*>(positions.data());
  b.data.assign(p, p + positions.size() * sizeof(float));
  const std::size_t index_offset = b.data.size();
  const auto* q = reinterpret_cast<const unsigned char*>(indices.data());
  b.data.insert(b.data.end(), q, q + indices.size() * sizeof(std::uint16_t));
  m.buffers.push_back(b);
  tinygltf::BufferView pv, iv;
  pv.buffer = iv.buffer = 0;
  pv.byteLength = index_offset;
  iv.byteOffset = index_offset;
  iv.byteLength = indices.size() * sizeof(std::uint16_t);
  m.bufferViews = {pv, iv};
  tinygltf::Accessor pa, ia;
  pa.bufferView = 0;
  pa.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pa.type = TINYGLTF_TYPE_VEC3;
  pa.count = positions.size() / 3;
  ia.bufferView = 1;
  ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  ia.type = TINYGLTF_TYPE_SCALAR;
  ia.count = indices.size();
  m.accessors = {pa, ia};
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = 0;
  prim.indices = 1;
  prim.mode = mode;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node root, child;
  root.children = {1};
  root.translation = translation;
  child.mesh = 0;
  child.scale = scale;
  m.nodes = {root, child};
  tinygltf::Scene s;
  s.nodes = {0};
  m.scenes.push_back(s);
  m.defaultScene = 0;
  m.asset.version = "2.0";
  const fs::path f = dir() / name;
  tinygltf::TinyGLTF w;
  EXPECT_TRUE(w.WriteGltfSceneToFile(&m, f.string(), true, true, true, true));
  return f;
}

std::string errorOf(const fs::path& f) {
  return stirrup::test::errorOf([&] { (void)loadTerrainGltf(f, "scene.json: terrain.file"); }, "");
}

// Metres to centimetres, through the nodes' transforms: a 20 m square ramp rising 2 m, scaled by 2
// and moved 1 m up.
TEST(GltfTerrain, ReadsTrianglesInCentimetresThroughTheNodes) {
  const fs::path f = writeGltf("ramp.glb", {0, 0, 0, 10, 1, 0, 10, 1, 10, 0, 0, 10}, {0, 1, 2, 0, 2, 3}, {0, 1, 0}, {2, 2, 2});
  const auto mesh = loadTerrainGltf(f, "scene.json: terrain.file");
  EXPECT_EQ(mesh->triangleCount(), 2u);
  EXPECT_NEAR(mesh->upper().x, 2000.0, 1e-3);
  EXPECT_NEAR(mesh->upper().y, 2000.0, 1e-3);
  EXPECT_NEAR(mesh->at(1000, 500)->height_cm, 100.0 + 100.0, 1e-3);  // 1 m up, plus half the 2 m rise
  EXPECT_NEAR(mesh->at(0, 500)->height_cm, 100.0, 1e-3);
}

TEST(GltfTerrain, BadFilesAreOneLineErrors) {
  const fs::path missing = dir() / "absent.glb";
  EXPECT_EQ(errorOf(missing), "scene.json: terrain.file: " + missing.string() + ": no such file (expected a glTF terrain mesh)");
  const fs::path points = writeGltf("points.glb", {0, 0, 0, 1, 0, 0, 0, 0, 1}, {0, 1, 2}, {0, 0, 0}, {1, 1, 1}, 0);
  EXPECT_EQ(errorOf(points), "scene.json: terrain.file: " + points.string() + ": expected triangles to stand on, found none");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const fs::path bad = writeGltf("nan.glb", {0, 0, 0, 1, nan, 0, 0, 0, 1}, {0, 1, 2});
  EXPECT_EQ(errorOf(bad), "scene.json: terrain.file: " + bad.string() + ": meshes[0].primitives[0].POSITION: vertex 1: expected finite coordinates, got (1, nan, 0) m");
  const fs::path junk = dir() / "junk.glb";
  std::ofstream(junk) << "not a glb";
  EXPECT_EQ(errorOf(junk).rfind("scene.json: terrain.file: " + junk.string() + ": not a readable glTF file", 0), 0u) << errorOf(junk);
  const fs::path past = writeGltf("past.glb", {0, 0, 0, 1, 0, 0, 0, 0, 1}, {0, 1, 7});
  EXPECT_NE(errorOf(past).find("indices: expected vertex indices below 3, got 7"), std::string::npos) << errorOf(past);
}

}  // namespace
}  // namespace stirrup::rig

namespace stirrup::rig {
namespace {

// A shot's ground is named so (issue 60): "ground", or "ground" then "_", "." or "-", any case.
TEST(GltfGround, NamedGroundOrGroundAndASeparator) {
  for (const char* name : {"ground", "Ground", "GROUND", "ground_mesh", "Ground.001", "ground-hills"})
    EXPECT_TRUE(isGroundNodeName(name)) << name;
  for (const char* name : {"groundhog", "playground", "grounds", "", "terrain", "ground mesh"})
    EXPECT_FALSE(isGroundNodeName(name)) << name;
}

}  // namespace
}  // namespace stirrup::rig
