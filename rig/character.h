// A character: a skeleton, the mesh it moves, and the joints that posing jobs look up by role.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

#include "rig/mesh.h"
#include "rig/skeleton.h"

namespace stirrup::rig {

// A horse's four hoof roles, in the channels' leg order (left fore, right fore, left hind, right hind).
inline constexpr std::array<const char*, 4> kHoofRoles = {"lfHoof", "rfHoof", "lbHoof", "rbHoof"};

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
  // A rider the rig seated (rig/characters/seating.h) carries the horse's side where her legs lie, so the
  // rider channels (knee and foot movements, a leg swinging back) never press her knees and calves into
  // it: posing turns a knee out about its hip-ankle line as far as that needs (rig/rider_pose.h). Empty: no
  // guard (the generated rider, built against the generated horse).
  struct LegGuard {
    // The horse's half-width (largest |z|, cm) in saddle space, in cells of cell_cm from (x0, y0): nx
    // cells forward, ny up; -inf where the horse has no surface.
    float x0 = 0.0f, y0 = 0.0f, cell_cm = 2.0f;
    int nx = 0, ny = 0;
    std::vector<float> half_width;
    float knee_radius_cm = 0.0f, calf_radius_cm = 0.0f;  // her leg's surface around the knee and the calf
    float room_cm = 0.5f;                                  // kept between her surface and the horse's
    bool empty() const { return half_width.empty(); }
    // The widest the horse is within one cell of (x, y) (-inf outside the table).
    float widthNear(float x, float y) const;
  } leg_guard;
  // A rider the rig seated on a horse (scene/ridden_pair.h) keeps her head and trunk out of the
  // horse's neck and head as she folds forward (a tall rider in a rear meets the poll): sample points
  // of her upper body and of the horse's neck and head, each rigid on its joint, and the room posing
  // keeps between them (rig/rider_pose.h). Empty: no guard (a rider modelled seated, the generated one among them).
  struct FoldGuard {
    std::vector<int> rider_joint, horse_joint;
    std::vector<glm::vec3> rider_local, horse_local;  // each point in its joint's frame
    float room_cm = 3.0f;
    bool empty() const { return rider_joint.empty() || horse_joint.empty(); }
  } fold_guard;
  // A rider seated by the rig: how much more (or less) her spine's chain bends for the curve spine's
  // controllers than it would by their angles alone, so her trunk (pelvis to neck) leans for the rider
  // channels as the generated rider's does (her chain starts higher above the pelvis, or ends lower
  // below the neck, than the thesis rig's). 1 for the generated rider.
  float spine_bend_gain = 1.0f;
  // A rider seated by the rig: the height of her trunk's centre of mass above her hips that the balance
  // stage's support lean uses (rig/balance.h), in proportion to her legs as the generated rider's is
  // (rig/characters/seating.h); 0: measured from her skeleton (trunkComHeight).
  float balance_com_height_cm = 0.0f;

  int role(std::string_view r) const {
    const auto it = roles.find(r);
    if (it == roles.end()) throw std::out_of_range("character " + name + ": no role " + std::string(r));
    return it->second;
  }
};

}  // namespace stirrup::rig
