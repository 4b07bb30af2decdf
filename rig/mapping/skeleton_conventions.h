// Recognising a character's skeleton by its joint names (rig/mapping/auto_mapping.h's first step), the way
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
// and for a horse:
//   rigify horse  Blender Rigify's horse meta-rig (rigify/metarigs/Animals/horse.py: spine.001..,
//                 neck.001.., head, tail.001.., shoulder/upper_arm/forearm/forefoot/f_toe/f_hoof.L,
//                 thigh/lower_leg/hind_foot/r_toe/r_hoof.L) in two forms: the meta-rig's own names, and
//                 the generated rig's DEF- deform bones (long bones split in segments, the first
//                 segment's head the joint; ORG- and MCH- bones and the controls are never a role)
//   3ds max biped Autodesk 3ds Max's Biped with four leg links (the "horse link"), "Bip01 L Thigh", ...
//   stirrup       as above
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rig/mapping/character_mapping.h"
#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig {

// A joint name as the tables compare it: "mixamorig:LeftForeArm" -> {"forearm", +1, "mixamo"};
// "DEF-upper_arm.L.001" -> {"upperarm001", +1, "rigify"}; "upperarm_twist_01_r" -> {"upperarmtwist01", -1, ""};
// "J_Bip_C_Hips" -> {"hips", 0, "vroid"}.
struct JointName {
  std::string key;   // lower case, no namespace, tool prefix, side or separators
  int side = 0;      // +1 the character's left, -1 its right, 0 none given
  std::string tool;  // the tool its prefix names: "mixamo", "humanik" (Character1_), "rigify" (DEF-, ORG-, MCH-), "vroid"
                     // (J_Bip_/J_Adj_), "biped" (3ds Max's root name, Bip01), ""
  // A tool's helper bone: Rigify's ORG- copies of the meta-rig and MCH- mechanism bones, which deform
  // nothing and play no role (an all-bones export of a generated rig holds them beside the DEF- bones).
  bool helper = false;
};
JointName normalizeJointName(std::string_view name);

// What one convention's names give.
struct NamedRoles {
  std::string convention;                    // "mixamo", "humanik", "unreal", "rigify", "vrm", "stirrup", "rigify horse", "3ds max biped"
  std::string form;                          // which form of the convention: "metarig names", "deform bones", or ""
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
