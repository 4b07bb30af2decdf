// A baked shot as one glTF 2.0 file (stirrup bake SCENE -o BAKED.glb): every pair's two characters as
// skinned meshes, their joints' local translation and rotation at every frame (LINEAR samplers, one key
// per frame), and the cameras as glTF cameras on nodes, animated where they move.
//
// Over a terrain the file also holds the ground as a static mesh (node "ground"), so another tool shows
// the hooves on it. Layout (docs/round-trip.md): each character's joints hang under its own root node
// (scale 0.01: stirrup works in centimetres, glTF in metres), which is its skin's `skeleton`, so a DCC
// builds one armature per character: "horse" and "rider" for a scene of one pair; in a crowd each pair's
// "pair03_horse" and "pair03_rider" (BakedPair::name), its meshes and skins named after it too, while
// its joints keep their skeleton's own names ("root", "pelvis": those of the shipped characters' files,
// whether a scene names them or "default"), so one script drives every pair's bones. Camera nodes are roots, in metres, unscaled,
// so no viewer has to decide whether a parent's scale changes an orthographic magnification. One glTF
// animation holds every channel, grouped pair by pair (horse, rider), then the cameras: Blender 3.4
// makes one action per object from it (one per armature and per camera) and plays them all, whereas it
// would mute every animation but the first. Time: a frame's key is at seconds = (frame - 1) / fps, for
// every track.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"
#include "rig/pose.h"
#include "rig/characters/seating.h"

namespace tinygltf {
class Value;
}

namespace stirrup::rig {

struct BakedCamera {
  std::string name;
  bool orthographic = true;
  double fov_deg = 30.0;           // vertical field of view (perspective)
  double ortho_height_cm = 320.0;  // full height of the view (orthographic)
  int width = 640, height = 360;   // the image in pixels; the aspect is width / height
  // Camera to world in centimetres, one per frame: columns right, up, back (the camera looks down
  // its -Z with +Y up, as in glTF) and the position.
  std::vector<glm::dmat4> world;
  std::string view;   // the named view it was framed as (empty: the scene's own camera)
  int hold_frame = 0;  // > 0: stirrup shows this frame's pose at every frame (recorded in extras)
};

// One horse and rider of the shot and their poses.
struct BakedPair {
  std::string name;  // empty for a scene of one pair; else the prefix of its roots, meshes and skins
  const Character* horse = nullptr;
  const Character* rider = nullptr;
  std::vector<MountedPose> poses;  // one per frame: world matrices of both skeletons
  // How the rig seated the rider (the leathers it set): in the scene's extras as "stirrup_seat" for a
  // single pair, on the pair's rider root's extras in a crowd; nothing when the rig left her as built.
  SeatReport seat;
  // The hooves the clip slides on purpose (HorseFrame::hoof_sliding: a sliding stop's hinds), one entry
  // a frame (empty: none does). On the horse root's extras as "stirrup_hoof_sliding": {"lb": [the
  // seconds of the frames it slides], ...}, so `stirrup check` of the file does not count those slides
  // as the scene's check does not (rig/io/gltf_shot.h).
  std::vector<std::array<bool, 4>> hoof_sliding;
};

struct BakedShot {
  std::string name;
  double fps = 24.0;
  std::vector<float> seconds;      // one per frame, strictly increasing: (frame - 1) / fps
  std::vector<BakedPair> pairs;    // at least one
  std::vector<BakedCamera> cameras;
  // The ground the horses walk on (a scene's terrain), world cm, three indices a triangle; empty on
  // flat ground. Written as a static mesh "ground" under its own centimetre root.
  std::vector<glm::vec3> ground_vertices;
  std::vector<std::uint32_t> ground_indices;
};

// Joint locals from world matrices: local[i] = inverse(world[parent]) * world[i].
std::vector<glm::mat4> worldToLocal(const Skeleton& skeleton, const std::vector<glm::mat4>& world);

// The seat's record as glTF extras (an object: leathers, tread, reach, points added), or null when the
// rig left the rider as she was built (the generated pair).
tinygltf::Value seatExtras(const SeatReport& seat);

std::vector<unsigned char> bakedShotGlb(const BakedShot& shot);

}  // namespace stirrup::rig
