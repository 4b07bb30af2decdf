// Files the tests write and read: a fresh folder a test, and glTF binaries read and written again, as a
// test rewrites a file the way another tool (or a user's edit) would.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

namespace stirrup::test {

// STIRRUP_BINARY_DIR/GROUP/NAME, emptied: each test clears only its own folder (CTest runs the tests in
// parallel).
inline std::filesystem::path freshTestDir(const std::string& group, const std::string& name) {
  const std::filesystem::path d = std::filesystem::path(STIRRUP_BINARY_DIR) / group / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline tinygltf::Model readGlbModel(const std::filesystem::path& file) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
  return model;
}

// A .glb held in memory (a writer's bytes), read as a file of it would be.
inline tinygltf::Model glbModel(const std::vector<unsigned char>& glb) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), static_cast<unsigned>(glb.size()))) << err;
  return model;
}

inline void writeGlbModel(tinygltf::Model& model, const std::filesystem::path& file) {
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, file.string(), true, true, true, true));
}

}  // namespace stirrup::test
