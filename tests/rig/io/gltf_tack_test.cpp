// A horse's tack in glTF (rig/io/gltf_tack.h): the generated horse's mesh split into its body and a piece a
// part, written one mesh node a part (the full bake) or in one mesh with "_TACK_PART" (a character file),
// and read back to the same triangles, vertices and labels; bad labels are one-line errors. The bake's
// layout (names, extras, materials, the tack joints keyed) is tests/rig/io/gltf_bake_test.cpp; a bake of a
// user's horse read back and checked, tests/cli/bake_user_characters_test.cpp.
#include "rig/io/gltf_tack.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/mapping/character_mapping.h"
#include "rig/skeleton.h"
#include "tests/input_error.h"
#include "tests/rig/default_characters.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

using test::defaultHorse;
using test::defaultRider;

// Every triangle as its three corners' positions and its part, sorted: the same for a mesh whatever the
// order of its triangles and vertices, or vertices written twice.
std::vector<std::tuple<std::array<float, 9>, TackPart>> triangleSet(const SkinnedMesh& m) {
  std::vector<std::tuple<std::array<float, 9>, TackPart>> out;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    std::array<float, 9> corners{};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) corners[std::size_t(k * 3 + c)] = m.positions[m.indices[t * 3 + std::size_t(k)]][c];
    out.emplace_back(corners, m.triangleTackPart(t));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The generated horse splits into its body and its nine parts: every triangle in exactly one piece, the
// piece of its first vertex's part; a part's piece holds the vertices its triangles use and no other; the
// body keeps every vertex of no part. A mesh without tack, or not split, is one piece of every vertex.
TEST(GltfTack, TheGeneratedHorseSplitsIntoItsBodyAndOnePieceAPart) {
  const SkinnedMesh& m = defaultHorse().mesh;
  const std::vector<GltfMeshPiece> pieces = gltfMeshPieces(m, true);
  ASSERT_EQ(pieces.size(), 1 + kTackParts.size());
  EXPECT_EQ(pieces[0].part, TackPart::None);
  std::vector<int> seen(m.triangleCount(), 0);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const GltfMeshPiece& piece = pieces[k];
    if (k > 0) {
      EXPECT_EQ(piece.part, kTackParts[k - 1]);
    }
    EXPECT_TRUE(std::is_sorted(piece.triangles.begin(), piece.triangles.end()));
    std::set<std::uint32_t> used;
    for (const std::uint32_t t : piece.triangles) {
      ++seen[t];
      EXPECT_EQ(m.triangleTackPart(t), piece.part) << "triangle " << t;
      for (int c = 0; c < 3; ++c) used.insert(m.indices[std::size_t(t) * 3 + std::size_t(c)]);
    }
    ASSERT_FALSE(piece.vertices.empty()) << k;
    EXPECT_TRUE(std::is_sorted(piece.vertices.begin(), piece.vertices.end()));
    for (const std::uint32_t v : piece.vertices)
      EXPECT_TRUE(used.count(v) || (k == 0 && m.tackPart(v) == TackPart::None)) << "piece " << k << " vertex " << v;
    for (const std::uint32_t v : used) EXPECT_TRUE(std::binary_search(piece.vertices.begin(), piece.vertices.end(), v)) << v;
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(m.triangleCount()));
  for (const bool split : {false, true}) {
    const std::vector<GltfMeshPiece> whole = gltfMeshPieces(split ? defaultRider().mesh : m, split);
    ASSERT_EQ(whole.size(), 1u);
    EXPECT_TRUE(whole[0].vertices.empty());
    EXPECT_EQ(whole[0].triangles.size(), (split ? defaultRider().mesh : m).triangleCount());
  }
}

// A character file holds the tack's parts in "_TACK_PART" and reads back the very mesh written, labels
// included; a mesh without tack (the rider) writes no such attribute.
TEST(GltfTack, ACharacterFileKeepsItsTackPartsVertexForVertex) {
  const tinygltf::Model model = stirrup::test::glbModel(characterGlb(defaultHorse()));
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_TRUE(model.meshes[0].primitives.at(0).attributes.count("_TACK_PART"));
  GltfImageBytes images;
  const Character back = loadCharacterGltf(GltfSkinSource{&model, &images, "horse.glb", 0}, CharacterKind::Horse);
  EXPECT_EQ(back.mesh.tack_parts, defaultHorse().mesh.tack_parts);
  EXPECT_EQ(back.mesh.indices, defaultHorse().mesh.indices);
  EXPECT_EQ(back.mesh.positions, defaultHorse().mesh.positions);
  const tinygltf::Model rider = stirrup::test::glbModel(characterGlb(defaultRider()));
  EXPECT_FALSE(rider.meshes.at(0).primitives.at(0).attributes.count("_TACK_PART"));
}

// The full bake's horse, its tack a node a part, reads back whole: the same triangles at the same places,
// each in its part, the body's node holding none of the tack's.
TEST(GltfTack, ABakesTackNodesReadBackAsTheWholeHorse) {
  BakedShot shot;
  shot.seconds = {0.0f};
  BakedPair pair;
  pair.horse = &defaultHorse();
  pair.rider = &defaultRider();
  pair.poses = {MountedPose{restWorlds(defaultHorse().skeleton), restWorlds(defaultRider().skeleton), {}, {}}};
  shot.pairs = {pair};
  const tinygltf::Model model = stirrup::test::glbModel(bakedShotGlb(shot));
  std::size_t tack_nodes = 0;
  for (const tinygltf::Node& node : model.nodes) {
    if (node.skin != 0) continue;
    const TackPart part = gltfNodeTackPart(model, node, node.name);
    tack_nodes += part != TackPart::None;
    EXPECT_EQ(node.name, part == TackPart::None ? "horse:horse_mesh" : std::string(tackPartName(part)));
  }
  EXPECT_EQ(tack_nodes, kTackParts.size());
  GltfImageBytes images;
  const Character back = loadCharacterGltf(GltfSkinSource{&model, &images, "shot.glb", 0}, CharacterKind::Horse);
  EXPECT_EQ(triangleSet(back.mesh), triangleSet(defaultHorse().mesh));
  EXPECT_EQ(back.roles, defaultHorse().roles);
  // The body's mesh alone: no triangle of the tack's colours' parts.
  const tinygltf::Mesh& body = model.meshes.at(std::size_t(model.nodes.at(std::size_t([&] {
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (model.nodes[i].name == "horse:horse_mesh") return int(i);
    return -1;
  }())).mesh));
  for (const tinygltf::Primitive& prim : body.primitives) {
    const std::vector<double>& c = model.materials.at(std::size_t(prim.material)).pbrMetallicRoughness.baseColorFactor;
    const HorseParams p;
    for (const glm::vec3 tack : {p.leather, p.pad, p.metal})
      EXPECT_FALSE(float(c[0]) == tack.x && float(c[1]) == tack.y && float(c[2]) == tack.z) << model.materials[std::size_t(prim.material)].name;
  }
}

TEST(GltfTack, BadPartsAreOneLineErrors) {
  EXPECT_EQ(stirrup::test::errorOf([] { tackPartsOf({0.0f, 3.0f, 12.0f}, 3, "x.glb: meshes[0].primitives[0]"); }),
            "x.glb: meshes[0].primitives[0]._TACK_PART: vertex 2: expected a tack part's index 0 to 9 (0 the body)");
  EXPECT_EQ(stirrup::test::errorOf([] { tackPartsOf({0.5f}, 1, "x.glb: p"); }), "x.glb: p._TACK_PART: vertex 0: expected a tack part's index 0 to 9 (0 the body)");
  EXPECT_EQ(stirrup::test::errorOf([] { tackPartsOf({0.0f}, 2, "x.glb: p"); }), "x.glb: p._TACK_PART: expected one part a vertex");
  tinygltf::Model model;
  tinygltf::Node node;
  EXPECT_EQ(gltfNodeTackPart(model, node, "x.glb: nodes[3]"), TackPart::None);
  tinygltf::Value::Object extras;
  extras["stirrup_tack"] = tinygltf::Value(std::string("martingale"));
  node.extras = tinygltf::Value(extras);
  EXPECT_EQ(stirrup::test::errorOf([&] { gltfNodeTackPart(model, node, "x.glb: nodes[3]"); }),
            "x.glb: nodes[3].extras.stirrup_tack: expected one of the tack's parts, \"saddle\", \"saddle pad\", \"bridle\", \"bit\", "
            "\"stirrup leather.L\", \"stirrup leather.R\", \"stirrup iron.L\", \"stirrup iron.R\", \"reins\", got \"martingale\"");
  extras["stirrup_tack"] = tinygltf::Value(std::string("stirrup iron.L"));
  node.extras = tinygltf::Value(extras);
  EXPECT_EQ(gltfNodeTackPart(model, node, "x.glb: nodes[3]"), TackPart::StirrupIronL);
  for (TackPart p : kTackParts) EXPECT_EQ(tackPartNamed(tackPartName(p)), p);
  EXPECT_EQ(tackPartNamed(""), std::nullopt);
}

}  // namespace
}  // namespace stirrup::rig
