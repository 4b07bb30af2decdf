// A character file's skeleton as the automatic mapping reads it (rig/mapping/auto_mapping.h): a skin's
// joints with the names, hierarchy and bind places the importer (rig/io/gltf_character.h) gives them
// (read from a file by rig/io/gltf_mapping.h), which joints carry skin weight, the bind-pose mesh, and a VRM file's own humanoid bone table.
// Everything stays in the file's own space and units; finding the axes and scale is the mapping's job.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace stirrup::rig {

// A direction measured on the skeleton (up, forward) within this angle of one of the file's axes is
// taken to be that axis: files are modelled along their axes, and a rest pose's toes or a standing
// horse's back are not exactly square to them.
inline constexpr double kAxisSnapDeg = 25.0;

struct MappingSkeleton {
  std::string file;                      // for messages
  std::vector<std::string> names;        // as the importer names the joints (unnamed: "jointN", N its skin index)
  std::vector<int> parent;               // the nearest joint above in the file; further roots hung from the trunk
  std::vector<char> hung;                // a root of the file hung from the trunk's joint nearest to it
  std::vector<glm::dvec3> position;      // bind places (from the inverse bind matrices)
  std::vector<char> weighted;            // some vertex weighs on the joint itself
  std::vector<glm::dvec3> vertices;      // the skinned mesh's bind-pose vertices
  std::vector<int> vertex_joint;         // the joint each vertex weighs on most
  // A VRM file's humanoid bone table (VRMC_vrm 1.0's humanoid.humanBones, or VRM 0.x's): bone name
  // ("hips", "leftUpperArm", ...) -> joint. `vrm_table` names the extension it came from ("" for none).
  std::map<std::string, int> vrm_bones;
  std::string vrm_table;

  // Derived by finish(): children, and each joint's span in a depth-first walk (for ancestry tests).
  std::vector<std::vector<int>> children;
  std::vector<int> enter, leave, depth;

  int size() const { return static_cast<int>(names.size()); }
  // Fills the derived fields; parent must form a forest (every joint reaches a root).
  void finish();
  // True when `a` is `j` or above it.
  bool contains(int a, int j) const { return enter[a] <= enter[j] && leave[j] <= leave[a]; }
  bool above(int a, int j) const { return a != j && contains(a, j); }
  // The joints from `ancestor` (exclusive) down to `j` (inclusive); empty unless ancestor is above j.
  std::vector<int> pathDown(int ancestor, int j) const;
  int find(const std::string& name) const;  // -1 when there is none
};

// The hierarchy of a Rigify rig's deform bones as Rigify means it, where the file holds its other bones
// too (Blender's glTF exporter writes every bone by default): Rigify hangs each DEF- bone from the
// ORG- copy of its meta-rig bone's parent, or from mechanism and control bones that follow the ORG-
// bones only through constraints, which a file does not carry. Posing those parents would leave the
// deform bones behind (the generated horse's skull under ORG-head, beside the DEF- neck the rig
// turns). So a DEF- bone whose nearest DEF- or ORG- ancestor is ORG-X hangs from DEF-X (or, where X is
// the bone's own original, from DEF-Y of ORG-X's own nearest ORG- ancestor ORG-Y): DEF-upper_arm.L
// under DEF-shoulder.L, DEF-skull under DEF-head, DEF-thigh.L under DEF-pelvis.L. Other joints keep
// their parents. `parent` is one per joint, -1 for a root.
void rigifyDeformParents(std::vector<int>& parent, const std::vector<std::string>& names);

// A skin of several roots (Blender's Rigify exported with its deform bones only: the limbs and the
// face are roots) made one tree for finding roles: every further root hangs from the joint of the
// trunk's tree whose bone passes nearest it (nearestBoneJoint). The trunk's tree is, of the trees with
// a bone and no mirror image (a pair of loose limbs is mirrored; a lone joint, like Rigify's DEF-chest,
// has no bone), the one whose bones pass nearest the middle of the mesh: a horse's thighs can pass
// nearer its barrel's middle than its spine does. Unlike the importer's hangLooseRoots (which hangs
// each root from the body built so far), a mirror-image pair of loose limbs then hangs from one joint,
// never one from the other, as the topology's rules expect; the roles found lie on the same chains in
// either tree (a limb keeps its own hierarchy).
void hangFromTrunk(std::vector<int>& parent, const std::vector<glm::dvec3>& position, const glm::dvec3& middle,
                   std::vector<char>& hung);

}  // namespace stirrup::rig
