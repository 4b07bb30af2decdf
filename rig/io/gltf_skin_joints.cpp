#include "rig/io/gltf_skin_joints.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_mapping.h"
#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig {

double gltfSkinUnits(const tinygltf::Model& model, const std::string& file, int skin, int joint, const GltfAnimation& animation) {
  const tinygltf::Skin& s = checkedSkin(model, file, "character", skin);
  const std::vector<glm::mat4> ibm = gltfInverseBinds(model, file, skin);
  const std::size_t k = std::size_t(joint);
  const double det = glm::determinant(glm::dmat3(animation.world(s.joints.at(k), std::nullopt) * glm::dmat4(ibm.at(k))));
  const double units = std::cbrt(det);
  if (!(units > 0.0) || !std::isfinite(units))
    throw InputError(file + ": skins[" + std::to_string(skin) + "]: the joint \"" + gltfJointNames(model, skin).at(k) +
                     "\" is bound with no size or mirrored (its inverse bind matrix and rest transform multiply to a determinant of " +
                     numberText(det) + "; expected a positive scale)");
  return units;
}

GltfSkinJoints::GltfSkinJoints(const tinygltf::Model& model, const std::string& file, int skin, const glm::dmat4& to_rig, double units)
    : names_(gltfJointNames(model, skin)),
      nodes_(checkedSkin(model, file, "character", skin).joints),
      to_rig_(to_rig),
      world_to_rig_(to_rig * glm::scale(glm::dmat4(1.0), glm::dvec3(1.0 / units))) {
  for (const glm::mat4& m : gltfInverseBinds(model, file, skin)) ibm_.emplace_back(m);
}

std::optional<GltfFileJoint> GltfSkinJoints::joint(const std::string& name, const glm::dmat4* rest_world) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) return std::nullopt;
  const std::size_t k = std::size_t(it - names_.begin());
  GltfFileJoint j;
  j.node = nodes_[k];
  j.rest = glm::dvec3(to_rig_ * glm::inverse(ibm_[k])[3]);
  j.bind_to_rest = ibm_[k] * glm::inverse(to_rig_) * (rest_world ? *rest_world : glm::translate(glm::dmat4(1.0), j.rest));
  return j;
}

}  // namespace stirrup::rig
