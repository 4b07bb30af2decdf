// A joint hierarchy with its rest (bind) pose. Joints are stored parents first, so one forward pass
// turns local transforms into world transforms without recursion.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace stirrup::rig {

struct Joint {
  std::string name;
  int parent = -1;                // index of the parent joint (always lower than this joint's), -1 for a root
  glm::mat4 rest_local{1.0f};     // rest transform relative to the parent
  glm::mat4 inverse_bind{1.0f};   // inverse of the rest world transform: rest -> joint space
  // The rigid motion carrying the mesh's bind pose of this joint to its rest. Identity when the mesh
  // was bound at rest (every generated character). A user's standing rider seated by the rig
  // (rig/characters/seating.h) keeps the mesh as the file bound it and its seating here, so skinning
  // (world * inverse_bind * bind_offset) shows the file's own mesh in the seated rest.
  glm::mat4 bind_offset{1.0f};
  // A point the rig added (a hand's grip, a sole's contact with the tread), not a joint of the file
  // the character came from: no vertex is bound to it, and exports to the user's own skeleton leave
  // it out.
  bool rig_point = false;
  // A root of the file it came from that the loader hung from the nearest joint of the body (a skin
  // exported without the bones that held it, like Blender's Rigify deform bones): exports to the
  // user's own skeleton write it as the file has it, a root.
  bool file_root = false;
};

struct Skeleton {
  std::vector<Joint> joints;

  // Appends a joint and returns its index. Throws std::invalid_argument on a bad parent or a
  // duplicate name: a malformed character is a programming error, not user input.
  int addJoint(std::string name, int parent, const glm::mat4& rest_local);
  // Index of the joint called name, or -1.
  int find(std::string_view name) const;
  // Index of the joint called name; throws std::out_of_range when there is none.
  int require(std::string_view name) const;
  std::size_t size() const { return joints.size(); }

  glm::mat4 restWorld(int joint) const { return glm::inverse(joints[joint].inverse_bind); }
  glm::vec3 restPosition(int joint) const { return glm::vec3(restWorld(joint)[3]); }
  // The skinning bind of a joint (what a glTF skin's inverse bind matrix holds): inverse_bind * bind_offset.
  // (Exactly inverse_bind where there is no offset: a product with the identity can turn -0 into +0.)
  glm::mat4 skinBind(int joint) const {
    const Joint& j = joints[joint];
    return j.bind_offset == glm::mat4(1.0f) ? j.inverse_bind : j.inverse_bind * j.bind_offset;
  }
  // The joints on the way from `ancestor` (exclusive) down to `joint` (inclusive), ancestor's child
  // first; empty when `ancestor` is not an ancestor of `joint`.
  std::vector<int> pathFrom(int ancestor, int joint) const;
};

// The joint whose bone passes nearest `p`, among the joints `usable` marks (-1 when there are none). A
// bone runs from a joint to each of its usable children: a point along it belongs to its upper joint
// (the one it turns with, as a Blender bone spans its head to its tail), a point past either end to the
// joint there; a joint without usable children is a point. A loose root is hung beside the bone it lies
// against, not from whichever joint is nearest: a horse's scapula lies along the withers' bone nearer
// the neck's first joint than the withers' own. `distance` gets how far the bone passes.
int nearestBoneJoint(const glm::dvec3& p, const std::vector<int>& parent, const std::vector<glm::dvec3>& position,
                     const std::vector<char>& usable, double* distance = nullptr);

// A joint forest made one body: `parent` (-1 for a root, any order) gets each further root hung from the
// joint whose bone passes nearest it (nearestBoneJoint, by `position`) in the body built so far, so
// every joint moves with the body. The body
// starts from the tree holding `core` (a rider's pelvis, a horse's root), or with none (-1) from the
// tree holding the joint nearest the middle of all joints (the trunk, not a limb that happens to have
// more joints). Blender's Rigify exported with its deform bones only is such a forest: the limbs' and
// the face's parents are mechanism bones left out of the file. Returns which joints were roots and now
// hang from another.
std::vector<char> hangLooseRoots(std::vector<int>& parent, const std::vector<glm::vec3>& position, int core = -1);

// Rest local transforms, one per joint: the starting point of every posing job.
std::vector<glm::mat4> restLocals(const Skeleton& skeleton);
// Rest world transforms, one per joint.
std::vector<glm::mat4> restWorlds(const Skeleton& skeleton);
// world[i] = world[parent] * local[i]; roots take their local as world. Spans are one per joint.
void localToWorld(const Skeleton& skeleton, std::span<const glm::mat4> local, std::span<glm::mat4> world);

}  // namespace stirrup::rig
