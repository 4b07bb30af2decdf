// Which joint of a user's glTF character plays which role of the rig (docs/characters.md), like
// rig/io/gltf_clip.h's ClipMapping does for clips: a JSON file
//
//   {"character": "horse", "scale_cm": 1, "forward": [1, 0, 0], "up": [0, 1, 0], "offset_cm": [0, 0, 0],
//    "roles": {"root": "Hips", "saddle": "Saddle", ...}}
//
// "roles" maps every role of the character kind (requiredRoles) to a joint name in the file; two
// roles may name one joint. scale_cm, forward and up convert the file's units and axes to stirrup's
// (cm, +X travel, +Y up, +Z right); offset_cm is added after (a rider is built in saddle space, with
// the seat centre at the origin). Unknown fields are errors.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

namespace stirrup::rig {

enum class CharacterKind { Horse, Rider };

std::string_view characterKindName(CharacterKind kind);  // "horse" / "rider"

// Every role posing needs, in a stable order: for the horse the root (the hips, its rear pivot), the
// neck's first joint, the head and the four legs (upper, middle, fetlock, hoof; the fetlock may be the
// hoof's joint); for the rider the pelvis, neck, head and both arms (shoulder,
// elbow, wrist) and legs (hip, knee, ankle). Her spine is the chain of joints from the pelvis up to the
// neck, whatever its length (rig/rider_spine.h).
const std::vector<std::string>& requiredRoles(CharacterKind kind);
// Roles a character may name for more: a horse's backMid (where the back arches), chest, withers,
// neck2 (the neck's joints between neck1 and the head are found from the hierarchy anyway), tail1 (the
// tail is tail1 and its descendants; tail2 and tail3 are accepted), its tack (saddle, lStirrup,
// rStirrup, lRein, rRein: all five or none; without them the rig adds its own, rig/characters/horse_tack.h)
// and its leg pivots ("lfPivot".."rbPivot": the scapula's
// pivot, the hip joint) let the whole limb reach (rig/horse_leg.h); without them a leg is solved
// below the elbow or stifle only. A rider's spine controllers (lowerBack, waist, chest: joints of the
// chain or handles of their own) and upperChest (the chain's top, the shoulders' joint), braid1..3 and
// coatTail (swung by the hair and cloth channels), per side Hand (where the hand closes on the rein)
// and Ball (the ball of the foot on the tread), and the generated rider's chain spine0..spine10. A
// missing hand or ball is a point the rig adds (rig/characters/seating.h); a missing braid or coat
// tail is not animated.
const std::vector<std::string>& optionalRoles(CharacterKind kind);

// The numbers a mapping file may hold (our choices): a file unit from 0.01 mm to 1 km, axes with
// components up to a million (only their directions count), an offset within 100 km.
inline constexpr double kMinMappingScaleCm = 1e-3, kMaxMappingScaleCm = 1e5;
inline constexpr double kMaxMappingAxis = 1e6;
inline constexpr double kMaxMappingOffsetCm = 1e7;

// What is wrong with a mapping's axes, as (field, expected): a direction of no length (or all but none:
// 1e-320), or up not at right angles to forward; empty when they make a frame.
std::pair<std::string, std::string> mappingAxesProblem(const std::array<double, 3>& forward, const std::array<double, 3>& up);

struct CharacterMapping {
  std::map<std::string, std::string> roles;  // role -> joint name in the file
  double scale_cm = 1.0;
  std::array<double, 3> forward = {1, 0, 0};
  std::array<double, 3> up = {0, 1, 0};
  std::array<double, 3> offset_cm = {0, 0, 0};
  std::filesystem::path file;  // where the mapping was read from, for messages (empty: built in)
};


// Roles that must lie on one chain of the skeleton, each below another: a rider's elbow below her
// shoulder, wrist below elbow, knee below hip, ..., the neck above the pelvis with a spine joint between,
// the head above the neck; a horse's leg joints in order down to the hoof, the neck and tail in order,
// the head beyond neck1, and tail1 holding neither the root nor neck1 (its swing would turn the body).
// Given role -> joint and every joint's parent (-1 for a root), the first role out of place as
// "roles.lKnee: joint \"LeftLeg\" is not below lHip \"LeftUpLeg\" (expected the knee on the leg's chain
// below the hip; HINT)", or "" when every role is in place. Roles not in `roles` are not checked.
std::string roleChainProblem(CharacterKind kind, const std::map<std::string, int>& roles, const std::vector<int>& parent,
                             const std::vector<std::string>& names, const std::string& hint = "");

// A horse's legs hang from their pivots, as the roles say they do: where a leg names a Pivot that is
// not above its Upper and the top of Upper's chain is a root of the file (`file_root`), that root is
// hung from the Pivot. Blender's deform-bones-only export of a Rigify horse leaves the humerus
// (DEF-upper_arm.L) a root of its own: the bone that held it, ORG-shoulder.L, is not in the file, the
// scapula DEF-shoulder.L is. Returns the joints hung.
std::vector<int> hangLegsFromPivots(const std::map<std::string, int>& roles, std::vector<int>& parent,
                                    const std::vector<char>& file_root);

// The file's space to stirrup's: axes from forward and up (right = forward x up), times scale_cm,
// then offset_cm. Joints and vertices of a mapped character are read through it.
glm::dmat4 mappingToRig(const CharacterMapping& mapping);

}  // namespace stirrup::rig
