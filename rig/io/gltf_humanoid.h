// Writes a standing humanoid test character (rig/characters/standing_humanoid.h) as a glTF 2.0 binary
// the way other tools write their characters, not the way stirrup writes its own
// (rig/io/gltf_character.h): metres, +Y up, facing +Z with the character's left at +X; the joints
// under an armature node (Blender's "Armature", Rigify's "rig") or, where the convention has a
// ground root joint, at the scene root; joint nodes carrying their rest rotations (along the bones, or
// identity for VRoid-style files) with inverse bind matrices to match; one skinned mesh "Body" with a
// body and a hair primitive, each with its own POSITION, NORMAL, TEXCOORD_0, JOINTS_0 (unsigned bytes
// below 256 joints) and WEIGHTS_0, as Blender's exporter writes them; two materials sharing one base
// colour texture (an embedded PNG in a buffer view), base colour factor white. VRM-named files carry
// the VRMC_vrm extension (spec 1.0: meta and humanoid.humanBones). No stirrup extras, no role table:
// the file stands for one stirrup has never seen. The same humanoid gives the same bytes.
#pragma once

#include <filesystem>
#include <vector>

#include "rig/characters/standing_humanoid.h"

namespace stirrup::rig {

std::vector<unsigned char> humanoidGlb(const StandingHumanoid& humanoid);

// The VRM 1.0 humanoid bone name of a joint ("hips", "leftUpperArm", ...), or "" for a joint that is
// not one (vrm-c/vrm-specification, specification/VRMC_vrm-1.0/humanoid.md).
std::string vrmHumanBoneName(const HumanoidJointLabel& label, int spine_joints);

}  // namespace stirrup::rig
