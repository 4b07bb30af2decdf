// Finding a character's rig roles from the shape of its skeleton alone (rig/mapping/auto_mapping.h's
// fallback when the joint names say nothing): joints may be unnamed, and the file's axes and units are
// unknown, so every rule below compares joints with each other, never with fixed directions.
//
//  * Limbs come in mirror-image pairs: two subtrees whose joints reflect onto each other through one
//    plane, the joint they branch from lying on it. The pairs kept are the largest (a pair whose
//    parents are themselves a mirror pair is part of a bigger limb), longest first.
//  * A rider (biped): two pairs. The legs point away from where the other pair branches, the arms
//    sideways or down toward it; the pelvis is where the legs branch. The spine runs up from the pelvis
//    to where the arms branch and on to the head: the longest chain of the file's own joints (never
//    those hung from the body by hangLooseRoots, like Rigify's detached face bones) on the midline,
//    going up. The neck is the joint above the arms' branch (when the arms hang from it in the file),
//    or the first joint of the chain above the shoulders. Along each limb (following at every joint the
//    child that reaches farthest): the ankle is the first joint in the foot (within kAnkleBand of the
//    ground), the wrist the first joint the fingers branch from; shoulder and elbow, hip and knee are
//    the joints whose bone lengths and spacing fit human proportions best (Winter 2009), so a clavicle,
//    a breast bone or the second half of a split bone (Rigify's ".001") is passed over.
//  * A horse (quadruped): two pairs of legs reaching the ground, read from the skeleton alone: every
//    joint counts whatever the mesh weights (JointCount::Skeleton), so a mane skinned in one file and
//    not in another, or legs left unweighted, change nothing. From each pair's branch a walk leaves
//    the trunk the other way, at each joint into the neighbour whose joints reach farthest that way
//    (horseEndWalk): the front one (the file's own joints, down the hierarchy) reaches the head, the
//    rear one the tail. The fore pair's end is the one whose walk rises higher. Side branches (a mane,
//    ears, a jaw, eyes, a nose, the breast, the pelvis's wings, a saddle joint) never take a trunk,
//    neck, head or tail role: the walk passes them by (they reach less far forward or back than the
//    chain that holds the head or the tail's tip), and it stops at the head, the joint a mirror-image
//    pair (ears, eyes) branches from, or the chain's end. The neck starts at the walk's first joint
//    ahead of the fore legs' roots (Rigify's withers bone, spine.006, lies behind them). Each leg is
//    counted from the ground up, a split bone's segments passed over: its lowest joint the hoof, then
//    the fetlock, the middle (knee or hock) and the upper (elbow or stifle) joints, its root the pivot
//    when there are five or more. The trunk's roles follow from the chains (horseTrunkRoles).
// Sides are provisional here (the first of each pair is "l"): the mapping settles them once it knows
// which way the character faces.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig {

// Rules' constants (fractions of the character's height H unless said otherwise).
// Human segment lengths from D. A. Winter, "Biomechanics and Motor Control of Human Movement" (4th ed.,
// Wiley 2009), Fig. 4.1 (after Drillis & Contini 1966); the joint spacings are our estimates [E].
inline constexpr double kUpperArmLength = 0.186;   // shoulder to elbow (Winter)
inline constexpr double kForearmLength = 0.146;    // elbow to wrist (Winter)
inline constexpr double kHandLength = 0.108;       // wrist to finger tip (Winter)
inline constexpr double kThighLength = 0.245;      // hip to knee (Winter)
inline constexpr double kShinLength = 0.246;       // knee to ankle (Winter)
inline constexpr double kShoulderSpacing = 0.205;  // between the glenohumeral joints [E]
inline constexpr double kHipSpacing = 0.105;       // between the hip joint centres [E]
// A leg joint this close to the ground is in the foot: Winter's ankle is 0.039 H up, the knee 0.285 H.
inline constexpr double kAnkleBand = 0.1;
// Mirror images: a reflected joint may miss its partner by this fraction of the skeleton's size (its
// largest extent); a limb reaches at least kMinLimbReach of it; the two roots of a pair stand at least
// kMinPairSeparation apart (Rigify's DEF-pelvis.L/.R sit on the midline: not a pair).
inline constexpr double kMirrorTolerance = 0.05;
inline constexpr double kMinLimbReach = 0.15;
inline constexpr double kMinPairSeparation = 0.02;
// A palm joint runs on from the wrist within this angle of the forearm's line; a thumb leaves it at
// about 45 degrees (VRM's T-pose, vrm-c/vrm-specification VRMC_vrm-1.0/tpose.md) [E].
inline constexpr double kPalmAngleDeg = 30.0;
// A biped's legs leave the pelvis away from where the arms branch: the cosine between the two
// directions is below this (standing -0.97, seated about -0.8; a quadruped's hind legs -0.5) [E].
inline constexpr double kLegsAway = -0.7;
// ... and the arms at least this much less so (sideways: about 0, hanging toward the pelvis: up to 0.9) [E].
inline constexpr double kArmsAwayMargin = 0.5;
// A horse's neck chain may run forward and a little down (the head below the poll): down to this rise
// per unit of bone [E].
inline constexpr double kNeckMinRise = -0.2;
// A quadruped's legs end within this fraction of its height of the ground.
inline constexpr double kFootBand = 0.25;

// Split bones: Rigify cuts a long bone into segments of one length in one line (DEF-forefoot.L and
// DEF-forefoot.L.001). A leg joint within kSplitBoneDeg of straight between two bones whose lengths
// differ by at most kSplitLengthTolerance of the longer is such a cut, not a joint of the limb [E:
// Rigify's cuts are exact to float precision; the Rigify horse's straightest real joint, the fore knee,
// bends 6 degrees between bones of 0.36 and 0.26 m].
inline constexpr double kSplitBoneDeg = 1.0;
inline constexpr double kSplitLengthTolerance = 0.02;

// Which joints the rules count. A rider's: those carrying skin weight and those above them (end joints
// and unweighted helpers do not). A horse's: every joint but an end marker, an unweighted leaf under
// a weighted joint (Mixamo's ..._End, a hoof's tip joint): the one place weights decide, where the
// skeleton cannot tell a tip marker at the sole from a hoof joint there.
enum class JointCount { Weighted, Skeleton };

struct LimbPair {
  int a = -1, b = -1;   // the limbs' roots, mirror images
  int branch = -1;      // the joint they branch from (their lowest common ancestor)
  double reach = 0.0;   // how far the limb reaches from its root (file units)
};

// Mirror-image limb pairs, longest first.
std::vector<LimbPair> mirroredLimbs(const MappingSkeleton& s, JointCount count = JointCount::Weighted);

// The limb from `root` out: at every joint the child whose joints reach farthest from the root.
// Joints neither weighted nor above a weighted joint (end joints, helpers) are left out.
std::vector<int> limbChain(const MappingSkeleton& s, int root);

struct TopologyRoles {
  std::map<std::string, int> roles;         // role -> joint (limb sides provisional)
  std::map<std::string, std::string> why;   // role -> the rule that chose it
  std::vector<std::string> warnings;
};

// A horse's skeleton as its names or its shape show it, from which both take the trunk's roles by the
// same rules (horseTrunkRoles).
struct HorseChains {
  std::vector<int> body;  // the back's joints from the rear (one may lie behind the hind legs, as Rigify's
                          // spine.001 over the croup) to the last before the neck, in order
  std::vector<int> neck;  // the neck's joints from the body to the one the head hangs from
  int head = -1;
  std::vector<int> tail;  // the tail's joints from its root along its longest line
  std::array<int, 2> hind_roots{-1, -1}, fore_roots{-1, -1};  // where each pair of legs leaves the body
                                                              // (the hip joints, the scapulae's pivots)
};

// The trunk's roles: `root` and `chest` where the hind and fore legs hang (the body's joint both legs'
// roots hang from in the file itself; where they hang from a side bone, as Rigify's thighs from its
// pelvis bones, or were loose roots, the body's joint whose bone passes nearest their roots); backMid
// the middle joint of the body from root to chest; neck1 the neck's first joint, neck2 its middle one
// (shared with neck1 when it has one), the head; tail1, tail2, tail3 spread along the tail (a shorter
// tail shares its last). `how` starts each reason ("topology", "rigify horse names").
void horseTrunkRoles(const MappingSkeleton& s, const HorseChains& c, const std::string& how, std::map<std::string, int>& roles,
                     std::map<std::string, std::string>& why);

// A biped's roles; an InputError naming the file and what was found when the skeleton is not one.
TopologyRoles riderByTopology(const MappingSkeleton& s);
// A quadruped's roles (legs, trunk, neck, head, tail; tack only where a joint is named saddle,
// stirrup or rein); an InputError naming the file and what was found when it is not one.
TopologyRoles horseByTopology(const MappingSkeleton& s);

// The spine joint both shoulders hang from in the file's own hierarchy (strictly between the pelvis
// and the neck), or -1 when they do not meet on the spine or either was hung from the body by proximity.
int upperChestJoint(const MappingSkeleton& s, const std::map<std::string, int>& roles);

}  // namespace stirrup::rig
