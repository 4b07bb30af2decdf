// Test characters that stand for a studio's own rider: a clothed human standing on the ground in a T-,
// A- or relaxed rest pose, with the skeleton layout and joint names of a file some other tool made
// (Mixamo, Rigify, the Unreal mannequin, VRoid's VRM, HumanIK, or meaningless names). Nothing here is
// stirrup's own seated rider: no roles, no saddle space. An offline job: parameters in, a built
// character out, with what a third-party-style glTF writer needs (rig/io/gltf_humanoid.h): each joint's
// anatomical label, its bone's tail, per-vertex texture coordinates and the base colour texture.
//
// Space: centimetres, +Y up, facing +Z, the character's left at +X (glTF's humanoid front, VRM 1.0's
// "T-pose" spec, vrm-c/vrm-specification specification/VRMC_vrm-1.0/tpose.md), soles at y = 0.
//
// Proportions are fractions of the height H from D. A. Winter, "Biomechanics and Motor Control of
// Human Movement" (4th ed., Wiley 2009), Fig. 4.1, segment lengths after Drillis & Contini (1966); the
// rest (joint spacings, spine curve, soft tissue) are our estimates, marked as such.
//
// Joint names per convention (docs/characters.md, "Test characters", lists the sources):
//   mixamo   "mixamorig:Hips", "mixamorig:Spine", "mixamorig:Spine1".., "mixamorig:LeftArm", ...
//   rigify   Rigify's generated deform bones "DEF-spine" (pelvis), "DEF-spine.001"..., "DEF-upper_arm.L",
//            "DEF-upper_arm.L.001", "DEF-forearm.L", "DEF-hand.L", "DEF-thigh.L", "DEF-shin.L", "DEF-foot.L", "DEF-toe.L"
//   unreal   the UE4/UE5 mannequin "root", "pelvis", "spine_01".., "neck_01", "head", "clavicle_l", "upperarm_l", ...
//   vrm      VRoid's node names "J_Bip_C_Hips", "J_Bip_L_UpperArm", ... (the writer adds VRMC_vrm's humanBones)
//   humanik  the FBX/HumanIK character node names "Hips", "Spine", "Spine1".., "LeftArm", "LeftForeArm", ...
//   none     "Bone", "Bone.001", ...: nothing but the topology to go by
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include "rig/character.h"

namespace stirrup::rig {

enum class HumanoidRestPose { T, A, Relaxed };
enum class HumanoidNames { Mixamo, Rigify, Unreal, Vrm, HumanIK, None };
// How the joints' rest rotations are written: along the bones (Blender's and most DCC tools' way: each
// joint's +Y points along its bone to the bone's tail), or all identity, translations only (how VRoid
// and UniVRM export VRM models).
enum class HumanoidJointAxes { Bone, World };

struct StandingHumanoidParams {
  HumanoidNames names = HumanoidNames::Mixamo;
  HumanoidRestPose pose = HumanoidRestPose::T;
  HumanoidJointAxes joint_axes = HumanoidJointAxes::Bone;

  // Skeleton layout.
  int spine_joints = 3;           // joints between the pelvis and the first neck joint, 1..8
  int neck_joints = 1;            // 1..2
  // A hand joint in the palm below the one at the wrist (the fingers hang from it); false: the joint at
  // the wrist is the whole hand (wrist and hand shared), as in most rigs.
  bool separate_hand = true;
  bool toes = true;               // a ball-of-foot (toe) joint below the foot
  bool clavicles = true;          // shoulder (clavicle) joints between the top spine joint and the upper arms
  bool split_limbs = false;       // a second joint halfway along the upper arm, forearm, thigh and shin (Rigify's ".001")
  bool fingers = true;            // a thumb and one finger chain (three joints each)
  bool end_joints = false;        // unskinned leaf joints at the crown, the toe tips and the finger tips (Mixamo's "_End")
  bool ground_root = false;       // a root joint on the ground below the pelvis (Unreal's "root", VRoid's "Root")
  // Clavicles, upper arms and thighs parented to the root (or none: roots of their own) instead of the
  // trunk: what Blender's deform-bones-only glTF export of a Rigify rig gives, since their Blender
  // parents are the rig's ORG- and MCH- bones (tests/blender/rigify-rider makes such a file).
  bool detached_limbs = false;

  // Proportions, fractions of the height (Winter 2009, Fig. 4.1).
  float height = 170.0f;          // cm, sole to crown
  float upper_arm = 0.186f;       // shoulder to elbow
  float forearm = 0.146f;         // elbow to wrist
  float hand = 0.108f;            // wrist to finger tip
  float thigh = 0.245f;           // hip to knee
  float shin = 0.246f;            // knee to ankle
  float ankle_height = 0.039f;    // ground to ankle
  float foot_length = 0.152f;     // heel to toe tip
  float shoulder_height = 0.818f; // ground to acromion
  float shoulder_width = 0.259f;  // across the shoulders
  float hip_width = 0.191f;       // across the hips
  float chin_height = 0.870f;     // ground to chin
  // Our estimates [E], fractions of the height.
  float hip_spacing = 0.105f;     // between the hip joint centres
  float shoulder_spacing = 0.205f;  // between the shoulder (glenohumeral) joints
  float shoulder_drop = 0.02f;    // shoulder joint centre below the acromion
  float neck_base = 0.835f;       // ground to the first neck joint (C7)
  float head_pivot = 0.90f;       // ground to the head joint (top of the neck)
  float pelvis_above_hips = 0.02f;  // pelvis joint above the hip joints
  // The spine's rest curve in the side view: z offset from the pelvis-neck chord at u (0 at the pelvis,
  // 1 at the neck) is curve * H * u (1 - u) (inflection - u): forward over the lumbar spine (lordosis),
  // back over the thoracic spine (kyphosis). 0.27 puts the lumbar bulge 1.5 cm forward and the
  // thoracic 3 cm back at 170 cm [E].
  float spine_curve = 0.27f;
  float spine_inflection = 0.4f;
  // Rest pose angles (degrees).
  float a_pose_angle = 45.0f;         // A pose: arms this far below horizontal
  float relaxed_arm_angle = 10.0f;    // relaxed: arms this far out from the sides
  float relaxed_elbow_bend = 15.0f;   // relaxed: forearms bent this far forward
  float girth = 1.0f;                 // scales every soft-tissue radius

  // Variation: seed 0 is exactly these proportions; any other seed scales each length by up to +-4 %,
  // the girth by up to +-6 % and picks the clothes' colours, so no two test characters are alike.
  std::uint32_t seed = 0;
  float cell = 1.4f;                  // polygonisation grid, cm
};

// Anatomical label of a joint: what the writer names and maps (VRM humanBones).
// Hand is the joint at the wrist (every convention's hand bone starts there); Palm is the separate hand
// joint in the palm (StandingHumanoidParams::separate_hand), named as the conventions name a metacarpal.
enum class HumanoidBone {
  Root, Pelvis, Spine, Neck, Head, HeadEnd, Clavicle, UpperArm, Forearm, Hand, Palm, Thumb, Index,
  UpperLeg, LowerLeg, Foot, Toe, ToeEnd
};
struct HumanoidJointLabel {
  HumanoidBone bone = HumanoidBone::Root;
  int side = 0;   // +1 the character's left, -1 its right, 0 on the midline
  // Spine and neck: position in the chain from the bottom (0..). Split limbs: 0 or 1 (the ".001" half).
  // Fingers: 0..2 the three joints, 3 the end joint.
  int index = 0;
};

// An sRGB image, rows top to bottom (glTF's texture coordinates: (0, 0) is the top left corner).
struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3
  glm::u8vec3 at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// Where each clothing region lies in the texture: tiles of kHumanoidTile pixels in a 4 x 2 grid.
enum class HumanoidRegion { Jacket, Breeches, Boots, Skin, Face, Hair, Unused1, Unused2 };
inline constexpr int kHumanoidTile = 128;
inline constexpr int kHumanoidTextureWidth = 4 * kHumanoidTile, kHumanoidTextureHeight = 2 * kHumanoidTile;
// The tile's top left pixel.
inline glm::ivec2 humanoidTileOrigin(HumanoidRegion r) {
  const int i = static_cast<int>(r);
  return {(i % 4) * kHumanoidTile, (i / 4) * kHumanoidTile};
}

struct StandingHumanoid {
  // Skeleton (named per params.names, bind positions in cm) and the skinned mesh, bind pose, split at
  // texture seams; mesh.colors holds each vertex's region's base colour (linear), for viewers without
  // textures. No roles: this character stands for a file stirrup has never seen.
  Character character;
  std::vector<HumanoidJointLabel> labels;  // one per joint
  std::vector<glm::vec3> tails;            // one per joint: where its bone ends (cm)
  std::vector<glm::mat3> rest_axes;        // one per joint: its rest orientation in the file (columns x, y, z)
  std::vector<glm::vec2> uvs;              // one per vertex: TEXCOORD_0
  std::size_t hair_first_index = 0;        // mesh.indices before this are the body, from it on the hair
  RgbImage texture;                        // base colour, sRGB
  StandingHumanoidParams params;           // as built (seed variation applied)
};

// Throws InputError (one line) on parameters out of range.
StandingHumanoid buildStandingHumanoid(const StandingHumanoidParams& params);

// The layout files of each convention usually have: Rigify's split limbs, two neck bones and detached
// limbs, Unreal's
// and VRoid's ground root, Mixamo's end joints, VRoid's identity rest rotations. A caller sets names
// through this, then changes what it wants.
StandingHumanoidParams humanoidConventionDefaults(HumanoidNames names);

std::string_view humanoidNamesName(HumanoidNames names);            // "mixamo", "rigify", ...
bool parseHumanoidNames(std::string_view text, HumanoidNames& out);  // false when unknown
// The joint's name in a convention, from its label and (for "none") its index in the skeleton.
std::string humanoidJointName(HumanoidNames names, const HumanoidJointLabel& label, int spine_joints, int neck_joints,
                             int joint_index);

}  // namespace stirrup::rig
