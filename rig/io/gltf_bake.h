// A baked shot as one glTF 2.0 file (stirrup bake SCENE -o BAKED.glb): both characters as skinned
// meshes, their joints' local translation and rotation at every frame (LINEAR samplers, one key per
// frame), and the scene's cameras as glTF cameras on nodes, animated where they move. Everything hangs
// under "stirrup_cm" (scale 0.01), so the file opens at true size in metres.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"
#include "rig/pose.h"

namespace stirrup::rig {

struct BakedCamera {
  std::string name;
  bool orthographic = true;
  double fov_deg = 30.0;           // vertical (perspective)
  double ortho_height_cm = 320.0;  // (orthographic)
  double aspect = 16.0 / 9.0;      // width / height
  // Camera to world, one per frame (the camera looks down its -Z with +Y up, as in glTF).
  std::vector<glm::mat4> world;
};

struct BakedShot {
  std::string name;
  std::vector<float> seconds;      // one per frame, strictly increasing
  std::vector<MountedPose> poses;  // one per frame: world matrices of both skeletons
  std::vector<BakedCamera> cameras;
};

// Camera-to-world of a camera at `position` looking at `target`, +Y up.
glm::mat4 lookAtWorld(glm::dvec3 position, glm::dvec3 target);

// Joint locals from world matrices: local[i] = inverse(world[parent]) * world[i].
std::vector<glm::mat4> worldToLocal(const Skeleton& skeleton, const std::vector<glm::mat4>& world);

std::vector<unsigned char> bakedShotGlb(const Character& horse, const Character& rider, const BakedShot& shot);

}  // namespace stirrup::rig
