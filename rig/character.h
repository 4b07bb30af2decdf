// A character: a skeleton, the mesh it moves, and the joints that posing jobs look up by role.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

#include "rig/mesh.h"
#include "rig/skeleton.h"

namespace stirrup::rig {

struct Character {
  std::string name;
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
