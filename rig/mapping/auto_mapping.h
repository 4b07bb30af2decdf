// Mapping a user's character by itself (offline, once a file): which joint of a skinned glTF plays
// which rig role, and the file's axes and units, found from the file alone, so a scene can name the
// file with no mapping file (docs/characters.md, "Mapping by itself"). `stirrup character map` prints
// what it finds and writes it as a mapping file (rig/mapping/character_mapping.h) a user can correct.
//
//   input:  the file's skeleton (rig/mapping/mapping_skeleton.h) and the kind (rider or horse)
//   output: a CharacterMapping, and a report: the convention recognised ("mixamo", "rigify", "unreal",
//           "vrm", "humanik", "stirrup", "rigify horse" with its form) or "topology", per role the joint chosen and why, the axes and
//           scale found and how, the roles not found, warnings.
//
// Steps: (1) the joint names, when one convention names every required role and its chains hang
// together (rig/mapping/skeleton_conventions.h); otherwise (2) the skeleton's shape
// (rig/mapping/skeleton_topology.h). Then for a rider upperChest, where the file's hierarchy shows the
// spine joint the shoulders hang from. (3) Axes from the rest pose: up from the feet toward the head
// (a horse: from the hooves toward the back), forward the way the toes point from the ankles (else
// the feet's vertices, else the chest's front; a horse: from the hips toward the chest), each snapped to
// the file's nearest axis within kAxisSnapDeg. Sides follow from them (right = forward x up).
// (4) Scale: the mesh's height along up read in the common units (metres, centimetres, millimetres,
// inches, feet), the one giving the most plausible height; a horse's lowest point is put on the ground.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/mapping/character_mapping.h"
#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig {

// Plausible heights, sole to crown for a rider (adult riders: a 100 cm child on a pony to a 230 cm
// giant), ground to the top of the head for a horse (a Shetland's 100 to a Shire's 260 cm); the
// nominal heights (the default characters', rig/characters) decide between units that both fit.
inline constexpr double kRiderHeightMinCm = 100.0, kRiderHeightMaxCm = 230.0, kRiderNominalCm = 170.0;
inline constexpr double kHorseHeightMinCm = 100.0, kHorseHeightMaxCm = 260.0, kHorseNominalCm = 190.0;
// A rider's spine (pelvis to neck) leans at most this far from up: a character standing upright, not
// one on all fours mapped as a rider [E].
inline constexpr double kMaxSpineTiltDeg = 50.0;
// A horse's rest pose stands on its hooves: the way from its hooves up to its back lies within this of
// the file's up (glTF's +Y, or +Z in a Z-up file) [E: a standing rest pose is square to the ground; 45
// degrees is halfway to a horse lying on its side].
inline constexpr double kMaxHorseTiltDeg = 45.0;
// A skeleton larger than this is not mapped by itself (the topology compares every pair of joints).
inline constexpr int kMaxAutoMappedJoints = 2000;

struct AutoMappingParams {
  bool use_names = true;  // false: the skeleton's shape only (what the names would have said is still noted)
};

struct RoleChoice {
  std::string role, joint, why;
};

struct AutoMappingReport {
  std::string file;
  CharacterKind kind = CharacterKind::Rider;
  std::string method;          // "mixamo", "humanik", "unreal", "rigify", "vrm", "stirrup", "rigify horse" or "topology"
  std::string method_form;     // the convention's form, when it has several: "metarig names", "deform bones"
  std::string method_note;     // why the names did not decide, when they did not
  std::vector<RoleChoice> roles;  // required roles first, then optional, in requiredRoles/optionalRoles order
  std::string up, forward;     // "+Y", "-Z", or a measured direction
  std::string up_how, forward_how, scale_how, offset_how;
  double height_file = 0.0;    // the mesh's height along up, file units
  std::string unit;            // "metres", "centimetres", ... or "" (scaled to a nominal height)
  std::vector<std::string> not_mapped;           // required roles not found
  std::vector<std::string> optional_not_mapped;  // optional roles looked for and not found
  std::vector<std::string> left_to_rig;          // optional roles never guessed (spine controllers, hair, coat)
  std::vector<std::string> warnings;
};

struct AutoMapping {
  CharacterMapping mapping;  // mapping.file empty: made here
  AutoMappingReport report;
};

// The job. Throws a one-line InputError naming the file when the character cannot be mapped at all
// (saying what it found). Roles it cannot find are listed, not guessed.
AutoMapping autoMapCharacter(const MappingSkeleton& skeleton, CharacterKind kind, const AutoMappingParams& params = {});

// The mapping file: the fields loadCharacterMapping reads, roles in role order, the report's gist in
// "comment".
nlohmann::ordered_json autoMappingJson(const AutoMapping& mapped);
// The mapping file's text: autoMappingJson laid out one field (and one role) a line.
std::string autoMappingFileText(const AutoMapping& mapped);
// The full report `stirrup character map` prints (several lines, each role on its own).
std::string autoMappingReportText(const AutoMapping& mapped);
// A short summary (two or three lines) for a scene that names the file alone.
std::string autoMappingSummary(const AutoMapping& mapped);

}  // namespace stirrup::rig
