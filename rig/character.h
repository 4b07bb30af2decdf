// A character: a skeleton, the mesh it moves, and the joints that posing jobs look up by role.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

#include <glm/mat4x4.hpp>

#include "rig/mesh.h"
#include "rig/skeleton.h"

namespace stirrup::rig {

// Where a character read from a file came from, so what stirrup makes of it can be written back in
// the file's own terms (rig/io/gltf_rider_motion.h).
struct CharacterSource {
  std::string file;               // empty: built by stirrup's generator
  glm::dmat4 to_rig{1.0};         // the file's space (units, axes) to stirrup's: cm, +X forward, +Y up
};

struct Character {
  std::string name;
  CharacterSource source;
  Skeleton skeleton;
  SkinnedMesh mesh;
  // Role name -> joint index, for joints other modules address (the horse's "saddle", the rider's
  // "pelvis", ...). The role names each character provides are listed in its header.
  std::map<std::string, int, std::less<>> roles;

  int role(std::string_view r) const {
    const auto it = roles.find(r);
    if (it == roles.end()) throw std::out_of_range("character " + name + ": no role " + std::string(r));
    return it->second;
  }
};

}  // namespace stirrup::rig
