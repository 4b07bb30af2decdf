// The rider's motion alone, for the user's own rider rig (stirrup bake SCENE --rider-only -o FILE.glb).
//
// The file holds the rider's joints (with a skin, so a DCC builds an armature, but no mesh) and one
// animation keying every joint's local translation and rotation at every frame, at seconds =
// (frame - 1) / fps. When the rider is a user's glTF character read through a mapping, everything is
// in the user's file: its joint names, its units and axes (the mapping's scale_cm, forward, up and
// offset undone), its joints' own rest orientations and inverse bind matrices, and the root joint
// hanging from a node holding the rest transform of its parent in the user's file. Keys are the user's
// joint locals that skin the user's mesh as stirrup's pose skins stirrup's copy of it, so the action
// applies to the user's rig by joint name. Nodes between two joints in the user's file are folded into
// the child joint's local. The built-in rider is written in metres with stirrup's axes.
//
// The scene's extras hold `fps` and `frame_time` (as the whole shot's do, so a DCC sets its frame
// rate before it imports), `stirrup_forward` and `stirrup_up` (stirrup's +X and +Y, the way the horse
// travels and up, as unit vectors in the file's space: where a script puts a side camera) and, for a
// seated rider, `stirrup_seat`.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"
#include "rig/characters/seating.h"

namespace stirrup::rig {

struct RiderMotion {
  std::string name;                           // the animation's name
  double fps = 24.0;                          // the scene's frame rate: seconds = (frame - 1) / fps
  std::vector<float> seconds;                 // one per frame, strictly increasing
  std::vector<std::vector<glm::mat4>> world;  // one per frame: the rider's joint world matrices (posing)
  SeatReport seat;                            // how the rig seated her (the scene's extras, "stirrup_seat")
};

// `rider` is the character as the scene resolved it (its `source` says which file it came from, and
// how that file's space maps to stirrup's; none for the built-in rider). Joints the rig added
// (Joint::rig_point) are left out: they are not the user's.
std::vector<unsigned char> riderMotionGlb(const Character& rider, const RiderMotion& motion);

}  // namespace stirrup::rig
