// The node hierarchy of a glTF file a user gives us, checked before anything walks it. glTF 2.0
// (section 3.5.3) requires the nodes to form disjoint trees: every child index names a node of the
// file, no node has two parents and no node is its own ancestor. tinygltf does not check this, and a
// walk up a cycle never ends (found by fuzzing: tests/fuzz/regressions/gltf_clip, gltf_character).
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

namespace tinygltf {
class Model;
class Node;
}

namespace stirrup::rig {

// The parent of every node (-1 for a root). A broken hierarchy is a one-line InputError naming `file`
// and the node: "FILE: nodes[3].children[0]: expected a node index 0..7, got 12".
std::vector<int> gltfNodeParents(const tinygltf::Model& model, const std::string& file);

// A node's local transform: its matrix, or translation * rotation * scale (glTF 2.0, section 5.25).
glm::dmat4 gltfNodeLocal(const tinygltf::Node& node);

}  // namespace stirrup::rig
