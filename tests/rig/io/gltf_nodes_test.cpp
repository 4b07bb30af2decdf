#include "rig/io/gltf_nodes.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

tinygltf::Model withChildren(const std::vector<std::vector<int>>& children) {
  tinygltf::Model m;
  for (const auto& c : children) {
    tinygltf::Node n;
    n.children = c;
    m.nodes.push_back(n);
  }
  return m;
}

std::string errorOf(const std::vector<std::vector<int>>& children) {
  return stirrup::test::errorOf([&] { gltfNodeParents(withChildren(children), "x.gltf"); });
}

TEST(GltfNodes, ParentsOfAForest) {
  EXPECT_EQ(gltfNodeParents(withChildren({{1, 2}, {}, {3}, {}, {}}), "x.gltf"), (std::vector<int>{-1, 0, 0, 2, -1}));
  EXPECT_TRUE(gltfNodeParents(withChildren({}), "x.gltf").empty());
}

// Found by fuzzing: a child index past the nodes threw std::out_of_range (tests/fuzz/regressions/
// gltf_clip/child_index_past_nodes.gltf) and a cycle hung the character loader
// (tests/fuzz/regressions/gltf_character/node_cycle).
TEST(GltfNodes, ABrokenHierarchyIsOneLineNamingTheNode) {
  EXPECT_EQ(errorOf({{1}, {8}}), "x.gltf: nodes[1].children[0]: expected a node index 0..1, got 8");
  EXPECT_EQ(errorOf({{-1}}), "x.gltf: nodes[0].children[0]: expected a node index 0..0, got -1");
  EXPECT_EQ(errorOf({{0}}), "x.gltf: nodes[0].children[0]: node 0 is its own child (expected a tree of nodes)");
  EXPECT_EQ(errorOf({{2}, {2}, {}}), "x.gltf: nodes[1].children[0]: node 2 already has parent node 0 (expected a tree of nodes)");
  EXPECT_EQ(errorOf({{}, {2}, {3}, {1}}), "x.gltf: nodes[1]: the node is its own ancestor (expected a tree of nodes)");
}

}  // namespace
}  // namespace stirrup::rig
