// A horse's tack in glTF (docs/round-trip.md, "The tack"): which of a character's triangles and vertices
// each mesh node of the file holds, and the part a node or vertex read back belongs to.
//
// Written two ways (rig/io/gltf_character.h appendCharacterGltf):
//   - one mesh node a part (the full bake, rig/io/gltf_bake.h): the horse's body mesh without the tack's
//     triangles, and beside it a node and mesh per part named as the part is ("saddle", "saddle pad",
//     "bridle", "bit", "stirrup leather.L", "stirrup leather.R", "stirrup iron.L", "stirrup iron.R",
//     "reins"; rig/tack_part.h), skinned by the horse's skin, each holding only the vertices its triangles
//     use, its materials named after it ("saddle pad", "saddle pad.001" for its second colour) with the
//     base colour stirrup renders it in, and on the node the extras {"stirrup_tack": PART, "stirrup_fits":
//     the horse's armature, "stirrup_fits_file": the horse's own file (a user's horse only)};
//   - in one mesh (a character file, `stirrup character make`): the part of each vertex as the attribute
//     "_TACK_PART" (a float a vertex: the part's index in rig::TackPart, 0 the body), so the file reads back
//     as the very mesh that was written.
// Read (rig/io/gltf_character.h loadCharacterGltf): a primitive's "_TACK_PART", else its node's extras
// "stirrup_tack" (or its mesh's), label its vertices; others are the body. An unknown part is a one-line
// InputError naming the file, the node and the parts there are.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rig/mesh.h"

namespace tinygltf {
class Model;
class Node;
class Value;
}  // namespace tinygltf

namespace stirrup::rig {

// One mesh of a character as the file holds it: the body (part None) or one part of its tack.
struct GltfMeshPiece {
  TackPart part = TackPart::None;
  std::vector<std::uint32_t> triangles;  // the mesh's triangles in it, in their order
  std::vector<std::uint32_t> vertices;   // the vertices it holds, ascending; empty: every vertex of the mesh
};

// The pieces of `mesh`: with `split_tack` the body (every vertex that is no tack's, and those its
// triangles use) and then each part it has in kTackParts order (the vertices its triangles use); else
// the whole mesh as one piece.
std::vector<GltfMeshPiece> gltfMeshPieces(const SkinnedMesh& mesh, bool split_tack);

// The extras of a part's node: {"stirrup_tack", "stirrup_fits", and "stirrup_fits_file" unless `file` is empty}.
tinygltf::Value tackNodeExtras(TackPart part, const std::string& fits, const std::string& file);

// The part a node holds, by its extras' (else its mesh's) "stirrup_tack": None without one. `where`
// names the node for errors.
TackPart gltfNodeTackPart(const tinygltf::Model& model, const tinygltf::Node& node, const std::string& where);
// A primitive's "_TACK_PART" values as parts (`count` of them, one a vertex); a value that is no part's
// index is an InputError naming `where`.
std::vector<TackPart> tackPartsOf(const std::vector<float>& values, std::size_t count, const std::string& where);

}  // namespace stirrup::rig
