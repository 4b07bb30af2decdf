// One skin's joints of a glTF file in stirrup's world, exactly as the file's nodes place them: the piece
// the readers of keyed motion share (a horse playing its own animation, rig/io/keyed_horse_clip.h; a
// baked shot read back, rig/io/gltf_shot.h).
//
//   input:  the file's skin (names, inverse binds), the file's space to stirrup's (to_rig, as the
//           character was loaded with), the units of its world (gltfSkinUnits)
//   output: each joint posed at a time: world_to_rig * world(node, t) * bind_to_rest, where
//             world(node, t)  the node's world transform in the file (rig/io/gltf_animation.h);
//             bind_to_rest    inverse bind * from_rig * the joint's rest world in the rig (a loaded
//                             character's rest is translation-only, at its bind place);
//             world_to_rig    to_rig after the units of the file's world against its mesh's.
//           Its rotation is the joint's turn from its rest, so skinning the loaded character with it
//           gives the file's own skinning (glTF: world(node) * inverse bind) in stirrup's world.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

class GltfAnimation;

// A joint of the file: its node, and what takes the node's world to the joint's posed place.
struct GltfFileJoint {
  int node = -1;
  glm::dmat4 bind_to_rest{1.0};  // inverse bind * from_rig * rest world
  glm::dvec3 rest{0.0};          // its bind place, rig space
};

// The units the file's world is in against its mesh's: the cube root of the determinant of joint
// `joint`'s (index into skins[skin].joints) rest world times its inverse bind. 1 where the rest is the
// bind, as Blender writes; 0.01 for stirrup's own files, whose joints hang under a metre node and bind in
// centimetres. Only the scale: a rest that differs from the bind by a motion (a bake's rest is its
// first frame) is the animation's own. A joint bound with no size or mirrored is an InputError naming
// `file`, the skin and the joint.
double gltfSkinUnits(const tinygltf::Model& model, const std::string& file, int skin, int joint, const GltfAnimation& animation);

class GltfSkinJoints {
 public:
  // Skin `skin` of `model` (checked: rig/mapping/mapping_skeleton.h checkedSkin); `to_rig` the file's space
  // to stirrup's (mappingToRig), `units` gltfSkinUnits's.
  GltfSkinJoints(const tinygltf::Model& model, const std::string& file, int skin, const glm::dmat4& to_rig, double units);

  // The joints' names as the importer gives them (rig/mapping/mapping_skeleton.h gltfJointNames).
  const std::vector<std::string>& names() const { return names_; }
  const glm::dmat4& worldToRig() const { return world_to_rig_; }
  // The joint named `name` (nullopt: the skin has none), posed about `rest_world` (its rest in rig
  // space; null: a translation to its bind place).
  std::optional<GltfFileJoint> joint(const std::string& name, const glm::dmat4* rest_world = nullptr) const;
  // The joint posed where its node's world is `node_world` (the file's space), in stirrup's world.
  glm::dmat4 posed(const GltfFileJoint& j, const glm::dmat4& node_world) const { return world_to_rig_ * node_world * j.bind_to_rest; }

 private:
  std::vector<std::string> names_;
  std::vector<int> nodes_;
  std::vector<glm::dmat4> ibm_;
  glm::dmat4 to_rig_{1.0}, world_to_rig_{1.0};
};

}  // namespace stirrup::rig
