// Recognising a character's skeleton by its joint names (rig/io/auto_mapping.h's first step), the way
// the Unreal auto-characterizer and Blender's retargeting add-ons do: each joint name is normalised
// (tool prefixes and namespaces dropped, the side taken out, case and separators ignored), looked up in
// each convention's table of names per rig role, and the convention that names the most roles wins.
//
// Conventions (docs/characters.md, "Mapping by itself", lists the names and their sources):
//   mixamo   Adobe Mixamo's "mixamorig:" HumanIK names (mixamorig:Hips, mixamorig:LeftArm, ...)
//   humanik  Autodesk HumanIK / FBX character names, bare or MotionBuilder's "Character1_" (Hips, LeftArm)
//   unreal   the UE4/UE5 mannequin (pelvis, upperarm_l, lowerarm_l, thigh_l, calf_l, ball_l, ...)
//   rigify   Blender Rigify's deform bones (DEF-spine, DEF-upper_arm.L, DEF-forearm.L, DEF-thigh.L, ...)
//   vrm      a VRM file's own humanoid bone table (VRMC_vrm / VRM), else VRoid Studio's J_Bip_ names
//   stirrup  stirrup's own role names as joint names (a stirrup file whose role table was lost)
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rig/io/character_mapping.h"
#include "rig/io/mapping_skeleton.h"

namespace stirrup::rig {

// A joint name as the tables compare it: "mixamorig:LeftForeArm" -> {"forearm", +1, "mixamo"};
// "DEF-upper_arm.L.001" -> {"upperarm001", +1, "rigify"}; "upperarm_twist_01_r" -> {"upperarmtwist01", -1, ""};
// "J_Bip_C_Hips" -> {"hips", 0, "vroid"}.
struct JointName {
  std::string key;   // lower case, no namespace, tool prefix, side or separators
  int side = 0;      // +1 the character's left, -1 its right, 0 none given
  std::string tool;  // the tool its prefix names: "mixamo", "humanik" (Character1_), "rigify" (DEF-), "vroid" (J_Bip_/J_Adj_), ""
};
JointName normalizeJointName(std::string_view name);

// What one convention's names give.
struct NamedRoles {
  std::string convention;                    // "mixamo", "humanik", "unreal", "rigify", "vrm", "stirrup"
  std::map<std::string, int> roles;          // role -> joint
  std::map<std::string, std::string> why;    // role -> how the name decided it
  std::vector<std::string> missing;          // required roles its names do not give
  int score = 0;                             // roles found (required and optional)
};

// Every convention that names at least one role, best first (most roles; ties in the order above).
std::vector<NamedRoles> rolesByNames(const MappingSkeleton& skeleton, CharacterKind kind);

// The joint whose normalised name is `key` with `side` (0: no side), or -1.
int jointByKey(const MappingSkeleton& skeleton, std::string_view key, int side);

}  // namespace stirrup::rig
