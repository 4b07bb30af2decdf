#include "rig/characters/standing_humanoid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <compare>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <span>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "rig/characters/implicit_body.h"
#include "rig/characters/joint_placement.h"
#include "rig/characters/torso_weights.h"
#include "rig/error.h"

namespace stirrup::rig {
namespace {

constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;

// SplitMix64 (Steele, Lea & Flood 2014): a few well-mixed numbers from a seed, the same on every
// platform (std's distributions are not).
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float symmetric() { return static_cast<float>(next() >> 40) / static_cast<float>(1ull << 23) - 1.0f; }  // [-1, 1)
};

// Clothing palettes (sRGB), picked by the seed; seed 0 takes the first of each.
constexpr std::array<glm::u8vec3, 4> kJackets = {{{28, 48, 110}, {25, 80, 50}, {110, 25, 35}, {55, 55, 62}}};
constexpr std::array<glm::u8vec3, 3> kBreeches = {{{214, 200, 160}, {226, 222, 210}, {190, 160, 110}}};
constexpr std::array<glm::u8vec3, 2> kBoots = {{{58, 34, 21}, {26, 23, 21}}};
constexpr std::array<glm::u8vec3, 3> kSkins = {{{230, 184, 150}, {198, 140, 100}, {141, 85, 54}}};
constexpr std::array<glm::u8vec3, 4> kHairs = {{{60, 38, 20}, {22, 18, 15}, {160, 118, 64}, {112, 50, 24}}};

float srgbToLinear(std::uint8_t c) {
  const float s = c / 255.0f;
  return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
}

std::string threeDigits(int n) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%03d", n);
  return buf;
}

std::string twoDigits(int n) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d", n);
  return buf;
}

// HumanIK's character node names (Mixamo's are the same behind "mixamorig:").
std::string humanIkName(const HumanoidJointLabel& l) {
  const std::string s = l.side > 0 ? "Left" : "Right";
  const std::string roll = l.index == 1 ? "Roll" : "";
  switch (l.bone) {
    case HumanoidBone::Root: return "Reference";
    case HumanoidBone::Pelvis: return "Hips";
    case HumanoidBone::Spine: return "Spine" + (l.index > 0 ? std::to_string(l.index) : "");
    case HumanoidBone::Neck: return "Neck" + (l.index > 0 ? std::to_string(l.index) : "");
    case HumanoidBone::Head: return "Head";
    case HumanoidBone::HeadEnd: return "HeadTop_End";
    case HumanoidBone::Clavicle: return s + "Shoulder";
    case HumanoidBone::UpperArm: return s + "Arm" + roll;
    case HumanoidBone::Forearm: return s + "ForeArm" + roll;
    case HumanoidBone::Hand: return s + "Hand";
    case HumanoidBone::Palm: return s + "InHandMiddle";
    case HumanoidBone::Thumb: return s + "HandThumb" + std::to_string(l.index + 1);
    case HumanoidBone::Index: return s + "HandIndex" + std::to_string(l.index + 1);
    case HumanoidBone::UpperLeg: return s + "UpLeg" + roll;
    case HumanoidBone::LowerLeg: return s + "Leg" + roll;
    case HumanoidBone::Foot: return s + "Foot";
    case HumanoidBone::Toe: return s + "ToeBase";
    case HumanoidBone::ToeEnd: return s + "Toe_End";
  }
  return "";
}

// Rigify's generated deform bones (the metarig's names behind "DEF-"; limbs in two halves, ".001").
std::string rigifyName(const HumanoidJointLabel& l, int spine_joints, int neck_joints) {
  const std::string s = l.side > 0 ? ".L" : ".R";
  const std::string half = l.index == 1 ? ".001" : "";
  const std::string head = "DEF-spine." + threeDigits(spine_joints + neck_joints + 1);
  switch (l.bone) {
    case HumanoidBone::Root: return "root";
    case HumanoidBone::Pelvis: return "DEF-spine";
    case HumanoidBone::Spine: return "DEF-spine." + threeDigits(l.index + 1);
    case HumanoidBone::Neck: return "DEF-spine." + threeDigits(spine_joints + 1 + l.index);
    case HumanoidBone::Head: return head;
    case HumanoidBone::HeadEnd: return head + "_end";
    case HumanoidBone::Clavicle: return "DEF-shoulder" + s;
    case HumanoidBone::UpperArm: return "DEF-upper_arm" + s + half;
    case HumanoidBone::Forearm: return "DEF-forearm" + s + half;
    case HumanoidBone::Hand: return "DEF-hand" + s;
    case HumanoidBone::Palm: return "DEF-palm.02" + s;
    case HumanoidBone::Thumb:
      return l.index < 3 ? "DEF-thumb.0" + std::to_string(l.index + 1) + s : "DEF-thumb.03" + s + "_end";
    case HumanoidBone::Index:
      return l.index < 3 ? "DEF-f_index.0" + std::to_string(l.index + 1) + s : "DEF-f_index.03" + s + "_end";
    case HumanoidBone::UpperLeg: return "DEF-thigh" + s + half;
    case HumanoidBone::LowerLeg: return "DEF-shin" + s + half;
    case HumanoidBone::Foot: return "DEF-foot" + s;
    case HumanoidBone::Toe: return "DEF-toe" + s;
    case HumanoidBone::ToeEnd: return "DEF-toe" + s + "_end";
  }
  return "";
}

// The UE4/UE5 mannequin (UE5's twist bones stand in for the second halves of split limbs).
std::string unrealName(const HumanoidJointLabel& l) {
  const std::string s = l.side > 0 ? "_l" : "_r";
  const std::string twist = l.index == 1 ? "_twist_01" : "";
  switch (l.bone) {
    case HumanoidBone::Root: return "root";
    case HumanoidBone::Pelvis: return "pelvis";
    case HumanoidBone::Spine: return "spine_" + twoDigits(l.index + 1);
    case HumanoidBone::Neck: return "neck_" + twoDigits(l.index + 1);
    case HumanoidBone::Head: return "head";
    case HumanoidBone::HeadEnd: return "head_end";
    case HumanoidBone::Clavicle: return "clavicle" + s;
    case HumanoidBone::UpperArm: return "upperarm" + twist + s;
    case HumanoidBone::Forearm: return "lowerarm" + twist + s;
    case HumanoidBone::Hand: return "hand" + s;
    case HumanoidBone::Palm: return "middle_metacarpal" + s;
    case HumanoidBone::Thumb: return "thumb_" + twoDigits(l.index + 1) + s;
    case HumanoidBone::Index: return "index_" + twoDigits(l.index + 1) + s;
    case HumanoidBone::UpperLeg: return "thigh" + twist + s;
    case HumanoidBone::LowerLeg: return "calf" + twist + s;
    case HumanoidBone::Foot: return "foot" + s;
    case HumanoidBone::Toe: return "ball" + s;
    case HumanoidBone::ToeEnd: return "toe_end" + s;
  }
  return "";
}

// VRoid Studio's node names: humanoid bones "J_Bip_", others ("adjustment") "J_Adj_".
std::string vrmName(const HumanoidJointLabel& l, int spine_joints) {
  const std::string s = l.side > 0 ? "L_" : "R_";
  switch (l.bone) {
    case HumanoidBone::Root: return "Root";
    case HumanoidBone::Pelvis: return "J_Bip_C_Hips";
    case HumanoidBone::Spine:
      if (l.index == 0) return "J_Bip_C_Spine";
      if (l.index == 1) return "J_Bip_C_Chest";
      if (l.index == spine_joints - 1) return "J_Bip_C_UpperChest";
      return "J_Adj_C_Chest" + std::to_string(l.index - 1);
    case HumanoidBone::Neck: return l.index == 0 ? "J_Bip_C_Neck" : "J_Adj_C_Neck1";
    case HumanoidBone::Head: return "J_Bip_C_Head";
    case HumanoidBone::HeadEnd: return "J_Adj_C_HeadTop";
    case HumanoidBone::Clavicle: return "J_Bip_" + s + "Shoulder";
    case HumanoidBone::UpperArm: return l.index == 0 ? "J_Bip_" + s + "UpperArm" : "J_Adj_" + s + "UpperArmTwist";
    case HumanoidBone::Forearm: return l.index == 0 ? "J_Bip_" + s + "LowerArm" : "J_Adj_" + s + "LowerArmTwist";
    case HumanoidBone::Hand: return "J_Bip_" + s + "Hand";
    case HumanoidBone::Palm: return "J_Adj_" + s + "Palm";
    case HumanoidBone::Thumb: return l.index < 3 ? "J_Bip_" + s + "Thumb" + std::to_string(l.index + 1) : "J_Adj_" + s + "ThumbTip";
    case HumanoidBone::Index: return l.index < 3 ? "J_Bip_" + s + "Index" + std::to_string(l.index + 1) : "J_Adj_" + s + "IndexTip";
    case HumanoidBone::UpperLeg: return l.index == 0 ? "J_Bip_" + s + "UpperLeg" : "J_Adj_" + s + "UpperLegTwist";
    case HumanoidBone::LowerLeg: return l.index == 0 ? "J_Bip_" + s + "LowerLeg" : "J_Adj_" + s + "LowerLegTwist";
    case HumanoidBone::Foot: return "J_Bip_" + s + "Foot";
    case HumanoidBone::Toe: return "J_Bip_" + s + "ToeBase";
    case HumanoidBone::ToeEnd: return "J_Adj_" + s + "ToeTip";
  }
  return "";
}

// A bone's rest frame the way Blender builds one: +Y from head to tail, +Z rolled toward the front
// (toward up for bones that point forward, the feet and toes), +X = Y x Z.
glm::mat3 boneAxes(glm::vec3 head, glm::vec3 tail) {
  const glm::vec3 y = glm::normalize(tail - head);
  const glm::vec3 ref = std::abs(y.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  const glm::vec3 z = glm::normalize(ref - glm::dot(ref, y) * y);
  return glm::mat3(glm::cross(y, z), y, z);
}

// An ellipsoid with explicit axes (the hands lie in any direction).
ImplicitPrimitive orientedEllipsoid(glm::vec3 center, glm::vec3 radii, const glm::mat3& axes, int joint, glm::vec3 tag,
                                    float blend) {
  ImplicitPrimitive p = ellipsoid(center, radii, joint, tag, blend);
  p.axes = axes;
  return p;
}

// -------------------------------------------------------------------------------------------------
// The texture: one tile a region, each a flat colour with a pattern, so a viewer that ignores the
// texture (a white figure) or misplaces it (patterns cut at the wrong places, magenta) shows.

glm::u8vec3 shade(glm::u8vec3 c, float f) {
  return glm::u8vec3(glm::clamp(glm::vec3(c) * f + 0.5f, glm::vec3(0.0f), glm::vec3(255.0f)));
}

glm::u8vec3 mixColor(glm::u8vec3 a, glm::u8vec3 b, float t) {
  return glm::u8vec3(glm::vec3(a) * (1.0f - t) + glm::vec3(b) * t + 0.5f);
}

struct Palette {
  glm::u8vec3 jacket, breeches, boots, skin, hair;
  glm::u8vec3 of(HumanoidRegion r) const {
    switch (r) {
      case HumanoidRegion::Jacket: return jacket;
      case HumanoidRegion::Breeches: return breeches;
      case HumanoidRegion::Boots: return boots;
      case HumanoidRegion::Skin:
      case HumanoidRegion::Face: return skin;
      case HumanoidRegion::Hair: return hair;
      default: return {255, 0, 255};
    }
  }
};

void setPixel(RgbImage& img, int x, int y, glm::u8vec3 c) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  const std::size_t i = (static_cast<std::size_t>(y) * img.width + x) * 3;
  img.rgb[i] = c.x;
  img.rgb[i + 1] = c.y;
  img.rgb[i + 2] = c.z;
}

void paintTiles(RgbImage& img, const Palette& pal) {
  img.width = kHumanoidTextureWidth;
  img.height = kHumanoidTextureHeight;
  img.rgb.assign(static_cast<std::size_t>(img.width) * img.height * 3, 0);
  for (int r = 0; r < 8; ++r) {
    const auto region = static_cast<HumanoidRegion>(r);
    const glm::ivec2 o = humanoidTileOrigin(region);
    const glm::u8vec3 base = pal.of(region);
    for (int y = 0; y < kHumanoidTile; ++y)
      for (int x = 0; x < kHumanoidTile; ++x) {
        glm::u8vec3 c = base;
        switch (region) {
          case HumanoidRegion::Jacket:  // a tartan: light bands every 16 px, a dark thread between
            if (x % 16 < 3 || y % 16 < 3) c = mixColor(base, {235, 205, 80}, 0.55f);
            else if (x % 16 == 9 || y % 16 == 9) c = shade(base, 0.55f);
            break;
          case HumanoidRegion::Breeches:  // pinstripes
            if (x % 8 == 0) c = shade(base, 0.8f);
            break;
          case HumanoidRegion::Boots:  // diagonal shine
            if ((x + y) % 12 < 2) c = shade(base, 1.8f);
            break;
          case HumanoidRegion::Skin:
          case HumanoidRegion::Face:  // freckles
            if ((x * 7 + y * 13) % 29 == 0) c = shade(base, 0.9f);
            break;
          case HumanoidRegion::Hair: {  // wavy strands
            const int wave = static_cast<int>(std::lround(2.0 * std::sin(y * 0.25)));
            if ((x + wave + 64) % 5 == 0) c = shade(base, 1.6f);
            break;
          }
          default:  // no geometry maps here: a magenta checker shows any that does
            c = ((x / 8 + y / 8) % 2) ? glm::u8vec3{255, 0, 255} : glm::u8vec3{20, 20, 20};
        }
        setPixel(img, o.x + x, o.y + y, c);
      }
  }
}

void fillEllipse(RgbImage& img, glm::vec2 centre, glm::vec2 radii, glm::u8vec3 c) {
  for (int y = static_cast<int>(std::floor(centre.y - radii.y)); y <= static_cast<int>(std::ceil(centre.y + radii.y)); ++y)
    for (int x = static_cast<int>(std::floor(centre.x - radii.x)); x <= static_cast<int>(std::ceil(centre.x + radii.x)); ++x) {
      const glm::vec2 d = (glm::vec2(x + 0.5f, y + 0.5f) - centre) / radii;
      if (glm::dot(d, d) <= 1.0f) setPixel(img, x, y, c);
    }
}

// -------------------------------------------------------------------------------------------------
// Texture charts: each triangle is projected along the axis of its primitive's frame its normal is
// closest to (a box projection), and every (region, frame, direction) chart is fitted into its
// region's tile. Vertices on chart borders are split, as exporters split them at UV seams.

struct ChartKey {
  int region, frame, dir;
  auto operator<=>(const ChartKey&) const = default;
};

// The two in-plane coordinates of a frame-local point for a projection along axis dir / 2: (right,
// down) as seen from outside, so the image's top is the frame's up.
glm::vec2 chartCoords(glm::vec3 local, int dir) {
  switch (dir / 2) {
    case 0: return {local.z, -local.y};   // along x: side view
    case 1: return {local.x, local.z};    // along y: top or bottom
    default: return {local.x, -local.y};  // along z: front or back
  }
}

constexpr int kTileMargin = 3;  // px kept clear inside a tile, so filtering never reaches the next tile

struct ChartFit {
  glm::vec2 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
  float scale = 1.0f;  // px per cm
  glm::vec2 offset{0.0f};
  glm::vec2 pixel(glm::vec2 c) const { return offset + (c - lo) * scale; }
};

}  // namespace

std::string_view humanoidNamesName(HumanoidNames names) {
  switch (names) {
    case HumanoidNames::Mixamo: return "mixamo";
    case HumanoidNames::Rigify: return "rigify";
    case HumanoidNames::Unreal: return "unreal";
    case HumanoidNames::Vrm: return "vrm";
    case HumanoidNames::HumanIK: return "humanik";
    case HumanoidNames::None: return "none";
  }
  return "";
}

bool parseHumanoidNames(std::string_view text, HumanoidNames& out) {
  for (HumanoidNames n : {HumanoidNames::Mixamo, HumanoidNames::Rigify, HumanoidNames::Unreal, HumanoidNames::Vrm,
                          HumanoidNames::HumanIK, HumanoidNames::None})
    if (text == humanoidNamesName(n)) {
      out = n;
      return true;
    }
  return false;
}

std::string humanoidJointName(HumanoidNames names, const HumanoidJointLabel& label, int spine_joints, int neck_joints,
                              int joint_index) {
  switch (names) {
    case HumanoidNames::Mixamo: return "mixamorig:" + humanIkName(label);
    case HumanoidNames::HumanIK: return humanIkName(label);
    case HumanoidNames::Rigify: return rigifyName(label, spine_joints, neck_joints);
    case HumanoidNames::Unreal: return unrealName(label);
    case HumanoidNames::Vrm: return vrmName(label, spine_joints);
    case HumanoidNames::None: return joint_index == 0 ? "Bone" : "Bone." + threeDigits(joint_index);
  }
  return "";
}

StandingHumanoidParams humanoidConventionDefaults(HumanoidNames names) {
  StandingHumanoidParams p;
  p.names = names;
  switch (names) {
    case HumanoidNames::Mixamo: p.end_joints = true; break;           // HeadTop_End, LeftToe_End, LeftHandIndex4
    case HumanoidNames::Rigify:  // spine.004, .005 are the neck; limbs detached as Blender exports them
      p.split_limbs = true;
      p.neck_joints = 2;
      p.detached_limbs = true;
      break;
    case HumanoidNames::Unreal: p.ground_root = true; break;
    case HumanoidNames::Vrm: p.ground_root = true; p.joint_axes = HumanoidJointAxes::World; break;
    case HumanoidNames::HumanIK:
    case HumanoidNames::None: break;
  }
  return p;
}

namespace {

void checkHumanoidParams(const StandingHumanoidParams& p) {
  const auto fail = [](const std::string& what) { throw InputError("standing humanoid: " + what); };
  if (p.spine_joints < 1 || p.spine_joints > 8) fail("spine joints: expected 1..8, got " + std::to_string(p.spine_joints));
  if (p.neck_joints < 1 || p.neck_joints > 2) fail("neck joints: expected 1 or 2, got " + std::to_string(p.neck_joints));
  if (!(p.height >= 100.0f && p.height <= 250.0f)) fail("height: expected 100..250 cm");
  if (!(p.cell >= 0.5f && p.cell <= 5.0f)) fail("cell: expected 0.5..5 cm");
  if (!(p.girth >= 0.5f && p.girth <= 2.0f)) fail("girth: expected 0.5..2");
}

// Seeded variation: the proportions within a few percent, and the colours.
Palette varyHumanoid(StandingHumanoidParams& p) {
  Palette pal{kJackets[0], kBreeches[0], kBoots[0], kSkins[0], kHairs[0]};
  if (p.seed != 0) {
    SplitMix64 rng{p.seed};
    for (float* f : {&p.upper_arm, &p.forearm, &p.hand, &p.thigh, &p.shin, &p.foot_length, &p.shoulder_width,
                     &p.hip_width, &p.hip_spacing, &p.shoulder_spacing})
      *f *= 1.0f + 0.04f * rng.symmetric();
    p.girth *= 1.0f + 0.06f * rng.symmetric();
    pal = {kJackets[rng.next() % kJackets.size()], kBreeches[rng.next() % kBreeches.size()],
           kBoots[rng.next() % kBoots.size()], kSkins[rng.next() % kSkins.size()], kHairs[rng.next() % kHairs.size()]};
  }
  return pal;
}

// Where the generator puts the figure at rest, in cm, for the parameters as varied: the trunk, and the
// left limbs (+X; the right mirror them).
struct HumanoidLayout {
  float H, k, g;  // height; scale from the 170 cm our absolute estimates are for; that times the girth
  int N, K;       // spine and neck joints
  float spine_curve, spine_inflection;
  float ankle_y;
  float knee_y;
  float hip_y;
  glm::vec3 pelvis_pos;
  glm::vec3 neck_pos;
  glm::vec3 head_pos;
  glm::vec3 crown;
  std::vector<glm::vec3> spine_pos;
  std::vector<glm::vec3> neck_chain;
  float shoulder_y;
  glm::vec3 clavicle_pos;
  glm::vec3 shoulder_pos;
  glm::vec3 upper_dir;
  glm::vec3 fore_dir;
  glm::vec3 hand_dir;
  glm::vec3 palm_normal;
  glm::vec3 thumb_side;
  float UA;
  float FA;
  float HL;
  glm::vec3 elbow_pos;
  glm::vec3 wrist_pos;
  glm::vec3 palm_pos;
  glm::vec3 knuckle_pos;
  glm::vec3 finger_tip;
  std::array<glm::vec3, 4> index_pos;
  glm::vec3 thumb_dir;
  glm::vec3 thumb_base;
  float TL;
  std::array<glm::vec3, 4> thumb_pos;
  float hip_x;
  glm::vec3 hip_pos;
  glm::vec3 knee_pos;
  glm::vec3 ankle_pos;
  float FL;
  float heel_z;
  glm::vec3 ball_pos;
  glm::vec3 toe_tip;
  float eye_y;
  glm::vec3 skull;
  float face_z;
  // The spine's curve at u from the pelvis (0) to the neck (1).
  glm::vec3 spineAt(float u) const {
    return glm::mix(pelvis_pos, neck_pos, u) +
           glm::vec3(0.0f, 0.0f, spine_curve * H * u * (1.0f - u) * (spine_inflection - u));
  }
};

HumanoidLayout layoutHumanoid(const StandingHumanoidParams& p) {
  const float H = p.height;
  const float k = H / 170.0f;  // our absolute estimates below are for 170 cm
  const float g = k * p.girth; // soft tissue
  const int N = p.spine_joints, K = p.neck_joints;
  const float ankle_y = p.ankle_height * H;
  const float knee_y = ankle_y + p.shin * H;
  const float hip_y = knee_y + p.thigh * H;
  const glm::vec3 pelvis_pos(0.0f, hip_y + p.pelvis_above_hips * H, -0.006f * H);
  const glm::vec3 neck_pos(0.0f, p.neck_base * H, -0.02f * H);
  const glm::vec3 head_pos(0.0f, p.head_pivot * H, -0.008f * H);
  const glm::vec3 crown(0.0f, H, head_pos.z);
  const auto spine_at = [&](float u) {
    return glm::mix(pelvis_pos, neck_pos, u) +
           glm::vec3(0.0f, 0.0f, p.spine_curve * H * u * (1.0f - u) * (p.spine_inflection - u));
  };
  std::vector<glm::vec3> spine_pos(N), neck_chain(K);
  for (int i = 0; i < N; ++i) spine_pos[i] = spine_at(static_cast<float>(i + 1) / static_cast<float>(N + 1));
  neck_chain[0] = neck_pos;
  if (K == 2) neck_chain[1] = glm::mix(neck_pos, head_pos, 0.5f) + glm::vec3(0.0f, 0.0f, 0.004f * H);  // cervical lordosis
  const float shoulder_y = (p.shoulder_height - p.shoulder_drop) * H;
  const glm::vec3 clavicle_pos(0.015f * H, shoulder_y, 0.006f * H);
  const glm::vec3 shoulder_pos(0.5f * p.shoulder_spacing * H, shoulder_y, -0.006f * H);
  glm::vec3 upper_dir(1.0f, 0.0f, 0.0f), fore_dir(1.0f, 0.0f, 0.0f);
  switch (p.pose) {
    case HumanoidRestPose::T: upper_dir = fore_dir = {1.0f, 0.0f, 0.0f}; break;
    case HumanoidRestPose::A:
      upper_dir = fore_dir = {std::cos(p.a_pose_angle * kDeg), -std::sin(p.a_pose_angle * kDeg), 0.0f};
      break;
    case HumanoidRestPose::Relaxed:
      upper_dir = {std::sin(p.relaxed_arm_angle * kDeg), -std::cos(p.relaxed_arm_angle * kDeg), 0.0f};
      fore_dir = glm::normalize(std::cos(p.relaxed_elbow_bend * kDeg) * upper_dir +
                                std::sin(p.relaxed_elbow_bend * kDeg) * glm::vec3(0.0f, 0.0f, 1.0f));
      break;
  }
  const glm::vec3 hand_dir = fore_dir;
  const glm::vec3 palm_normal = glm::normalize(glm::cross(hand_dir, glm::vec3(0.0f, 0.0f, 1.0f)));  // T pose: down
  const glm::vec3 thumb_side = glm::cross(palm_normal, hand_dir);                                   // T pose: forward
  const float UA = p.upper_arm * H, FA = p.forearm * H, HL = p.hand * H;
  const glm::vec3 elbow_pos = shoulder_pos + upper_dir * UA;
  const glm::vec3 wrist_pos = elbow_pos + fore_dir * FA;
  const glm::vec3 palm_pos = wrist_pos + hand_dir * (0.25f * HL);
  const glm::vec3 knuckle_pos = wrist_pos + hand_dir * (0.5f * HL);
  const glm::vec3 finger_tip = wrist_pos + hand_dir * HL;
  const std::array<glm::vec3, 4> index_pos = {knuckle_pos, knuckle_pos + hand_dir * (0.225f * HL),
                                              knuckle_pos + hand_dir * (0.375f * HL), finger_tip};
  const glm::vec3 thumb_dir = glm::normalize(hand_dir + thumb_side);  // 45 deg off the hand, as VRM's T-pose asks
  const glm::vec3 thumb_base = wrist_pos + hand_dir * (0.1f * HL) + thumb_side * (0.012f * H);
  const float TL = 0.45f * HL;
  const std::array<glm::vec3, 4> thumb_pos = {thumb_base, thumb_base + thumb_dir * (0.4f * TL),
                                              thumb_base + thumb_dir * (0.7f * TL), thumb_base + thumb_dir * TL};
  const float hip_x = 0.5f * p.hip_spacing * H;
  const glm::vec3 hip_pos(hip_x, hip_y, 0.0f);
  const glm::vec3 knee_pos(hip_x, knee_y, 0.003f * H);
  const glm::vec3 ankle_pos(hip_x, ankle_y, -0.003f * H);
  const float FL = p.foot_length * H;
  const float heel_z = ankle_pos.z - 0.22f * FL;
  const glm::vec3 ball_pos(hip_x, 0.016f * H, heel_z + 0.73f * FL);
  const glm::vec3 toe_tip(hip_x, 0.012f * H, heel_z + FL);

  const float eye_y = 0.936f * H;  // Winter 2009, Fig. 4.1: eye height
  const glm::vec3 skull(0.0f, H - 11.8f * k, head_pos.z + 1.0f * k);
  const float face_z = skull.z + 9.4f * k;
  return HumanoidLayout{H, k, g, N, K, p.spine_curve, p.spine_inflection, ankle_y, knee_y, hip_y, pelvis_pos, neck_pos, head_pos, crown, spine_pos, neck_chain, shoulder_y, clavicle_pos, shoulder_pos, upper_dir, fore_dir, hand_dir, palm_normal, thumb_side, UA, FA, HL, elbow_pos, wrist_pos, palm_pos, knuckle_pos, finger_tip, index_pos, thumb_dir, thumb_base, TL, thumb_pos, hip_x, hip_pos, knee_pos, ankle_pos, FL, heel_z, ball_pos, toe_tip, eye_y, skull, face_z};
}

// One side's limb joints (-1 where the convention has none; a limb's two halves the same joint unsplit).
struct HumanoidSide {
  int clavicle = -1, hand = -1, palm = -1, foot = -1, toe = -1;
  std::array<int, 2> upper{-1, -1}, fore{-1, -1}, thigh{-1, -1}, shin{-1, -1};
  std::array<int, 3> thumb{-1, -1, -1}, index{-1, -1, -1};
};

struct HumanoidJoints {
  int root = -1, pelvis = -1, head = -1;
  std::vector<int> spine, neck;
  std::array<HumanoidSide, 2> sides;  // [0] left, [1] right
};

// The joints, trunk first, then the arms and the legs, as the naming convention has them.
HumanoidJoints addHumanoidJoints(const StandingHumanoidParams& p, const HumanoidLayout& L, StandingHumanoid& out) {
  Skeleton& s = out.character.skeleton;
  const float H = L.H;
  const int N = L.N, K = L.K;
  HumanoidJoints J;
  const auto add = [&](HumanoidJointLabel label, int parent, glm::vec3 pos, glm::vec3 tail) {
    const int index = static_cast<int>(s.size());
    addJointAt(s, humanoidJointName(p.names, label, N, K, index), parent, pos);
    out.labels.push_back(label);
    out.tails.push_back(tail);
    return index;
  };
  if (p.ground_root) J.root = add({HumanoidBone::Root, 0, 0}, -1, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 0.1f * H));
  J.pelvis = add({HumanoidBone::Pelvis, 0, 0}, J.root, L.pelvis_pos, L.spine_pos[0]);
  J.spine.resize(N);
  J.neck.resize(K);
  for (int i = 0; i < N; ++i)
    J.spine[i] = add({HumanoidBone::Spine, 0, i}, i == 0 ? J.pelvis : J.spine[i - 1], L.spine_pos[i],
                   i + 1 < N ? L.spine_pos[i + 1] : L.neck_pos);
  for (int i = 0; i < K; ++i)
    J.neck[i] = add({HumanoidBone::Neck, 0, i}, i == 0 ? J.spine[N - 1] : J.neck[i - 1], L.neck_chain[i],
                  i + 1 < K ? L.neck_chain[i + 1] : L.head_pos);
  J.head = add({HumanoidBone::Head, 0, 0}, J.neck[K - 1], L.head_pos, L.crown);
  if (p.end_joints) add({HumanoidBone::HeadEnd, 0, 0}, J.head, L.crown, L.crown + glm::vec3(0.0f, 0.05f * H, 0.0f));

  const auto limb = [&](HumanoidBone bone, int side, int parent, glm::vec3 a, glm::vec3 b, glm::vec3 end,
                        std::array<int, 2>& joints) {
    if (p.split_limbs) {
      const glm::vec3 mid = glm::mix(a, b, 0.5f);
      joints[0] = add({bone, side, 0}, parent, a, mid);
      joints[1] = add({bone, side, 1}, joints[0], mid, b);
      return joints[1];
    }
    joints[0] = joints[1] = add({bone, side, 0}, parent, a, end);
    return joints[0];
  };
  for (int si = 0; si < 2; ++si) {
    const int side = si == 0 ? 1 : -1;
    const auto m = [&](glm::vec3 v) { return glm::vec3(v.x * static_cast<float>(side), v.y, v.z); };
    HumanoidSide& S = J.sides[si];
    int parent = p.detached_limbs ? J.root : J.spine[N - 1];
    if (p.clavicles) S.clavicle = add({HumanoidBone::Clavicle, side, 0}, parent, m(L.clavicle_pos), m(L.shoulder_pos));
    if (p.clavicles && !p.detached_limbs) parent = S.clavicle;
    parent = limb(HumanoidBone::UpperArm, side, parent, m(L.shoulder_pos), m(L.elbow_pos), m(L.elbow_pos), S.upper);
    parent = limb(HumanoidBone::Forearm, side, parent, m(L.elbow_pos), m(L.wrist_pos), m(L.wrist_pos), S.fore);
    S.hand = add({HumanoidBone::Hand, side, 0}, parent, m(L.wrist_pos), p.separate_hand ? m(L.palm_pos) : m(L.knuckle_pos));
    if (p.separate_hand) S.palm = add({HumanoidBone::Palm, side, 0}, S.hand, m(L.palm_pos), m(L.knuckle_pos));
    if (p.fingers) {
      for (int i = 0; i < 3; ++i)
        S.thumb[i] = add({HumanoidBone::Thumb, side, i}, i == 0 ? S.hand : S.thumb[i - 1], m(L.thumb_pos[i]), m(L.thumb_pos[i + 1]));
      if (p.end_joints) add({HumanoidBone::Thumb, side, 3}, S.thumb[2], m(L.thumb_pos[3]), m(L.thumb_pos[3] + L.thumb_dir * (0.1f * L.TL)));
      const int finger_root = S.palm >= 0 ? S.palm : S.hand;
      for (int i = 0; i < 3; ++i)
        S.index[i] = add({HumanoidBone::Index, side, i}, i == 0 ? finger_root : S.index[i - 1], m(L.index_pos[i]), m(L.index_pos[i + 1]));
      if (p.end_joints) add({HumanoidBone::Index, side, 3}, S.index[2], m(L.index_pos[3]), m(L.index_pos[3] + L.hand_dir * (0.05f * L.HL)));
    }
  }
  for (int si = 0; si < 2; ++si) {
    const int side = si == 0 ? 1 : -1;
    const auto m = [&](glm::vec3 v) { return glm::vec3(v.x * static_cast<float>(side), v.y, v.z); };
    HumanoidSide& S = J.sides[si];
    int parent = limb(HumanoidBone::UpperLeg, side, p.detached_limbs ? J.root : J.pelvis, m(L.hip_pos), m(L.knee_pos), m(L.knee_pos), S.thigh);
    parent = limb(HumanoidBone::LowerLeg, side, parent, m(L.knee_pos), m(L.ankle_pos), m(L.ankle_pos), S.shin);
    S.foot = add({HumanoidBone::Foot, side, 0}, parent, m(L.ankle_pos), p.toes ? m(L.ball_pos) : m(L.toe_tip));
    const int last = p.toes ? (S.toe = add({HumanoidBone::Toe, side, 0}, S.foot, m(L.ball_pos), m(L.toe_tip))) : S.foot;
    if (p.end_joints) add({HumanoidBone::ToeEnd, side, 0}, last, m(L.toe_tip), m(L.toe_tip + glm::vec3(0.0f, 0.0f, 0.02f * H)));
  }
  return J;
}

// The body as implicit primitives, each on its joint. Each primitive's colour carries its texture region (x)
// and chart frame (y: 0 the world, j + 1 joint j's bone frame); the real colours are set after polygonising.
// The pieces below add the trunk, the head, and each side's arm, hand and leg, in that order.
struct HumanoidBodyBuilder {
  using R = HumanoidRegion;
  const StandingHumanoidParams& p;
  const HumanoidLayout& L;
  const HumanoidJoints& J;
  const Skeleton& s;
  ImplicitBody& body;

  static glm::vec3 tag(HumanoidRegion r, int frame_joint) {
    return glm::vec3(static_cast<float>(r), static_cast<float>(frame_joint + 1), 0.0f);
  }
  int topSpine() const { return J.spine[L.N - 1]; }
  // The spine joint nearest a height.
  int chainAt(float y) const {
    int best = J.spine[0];
    for (int i = 0; i < L.N; ++i)
      if (std::abs(L.spine_pos[i].y - y) < std::abs(s.restPosition(best).y - y)) best = J.spine[i];
    return best;
  }
  // A limb segment from a to b: one capsule on one joint, or two halves when the segment has a twist joint.
  void twoHalves(glm::vec3 a, glm::vec3 b, float ra, float rb, const std::array<int, 2>& j, R region, float blend) const {
    if (j[0] == j[1]) {
      body.add(taperedCapsule(a, b, ra, rb, j[0], tag(region, j[0]), blend));
      return;
    }
    const glm::vec3 mid = glm::mix(a, b, 0.5f);
    const float rm = 0.5f * (ra + rb);
    body.add(taperedCapsule(a, mid, ra, rm, j[0], tag(region, j[0]), blend));
    body.add(taperedCapsule(mid, b, rm, rb, j[1], tag(region, j[1]), blend));
  }

  // Hips in breeches, then the jacket over the abdomen, chest and shoulder girdle.
  void addTrunk() const {
    const float H = L.H, k = L.k, g = L.g;
    body.add(ellipsoid(L.pelvis_pos + glm::vec3(0.0f, -0.02f * H, 0.5f * k), {0.5f * p.hip_width * H * p.girth, 11.0f * g, 11.5f * g},
                       J.pelvis, tag(R::Breeches, -1), 4.0f));
    const glm::vec3 waist_c = L.spineAt(0.3f) + glm::vec3(0.0f, 0.0f, 0.5f * k);
    const glm::vec3 chest_c = L.spineAt(0.7f) + glm::vec3(0.0f, 0.0f, 2.5f * k);
    const glm::vec3 girdle_c(0.0f, L.shoulder_y - 1.0f * k, -0.5f * k);
    body.add(ellipsoid(waist_c, {13.5f * g, 11.0f * g, 9.5f * g}, chainAt(waist_c.y), tag(R::Jacket, -1), 6.0f * k));
    body.add(ellipsoid(chest_c, {16.0f * g, 15.0f * g, 11.5f * g}, chainAt(chest_c.y), tag(R::Jacket, -1), 6.0f * k));
    body.add(ellipsoid(girdle_c, {0.5f * p.shoulder_width * H - 4.0f * k, 7.0f * g, 9.5f * g}, topSpine(), tag(R::Jacket, -1), 5.0f * k));
  }

  // Neck and head; hair: a cap above the brows, the back of the head down to the nape, a ponytail.
  void addHead() const {
    const float H = L.H, k = L.k, g = L.g;
    {
      const glm::vec3 a = L.neck_pos + glm::vec3(0.0f, -2.0f * k, 0.0f), b = L.head_pos + glm::vec3(0.0f, 2.0f * k, 0.5f * k);
      if (L.K == 1) {
        body.add(taperedCapsule(a, b, 5.5f * g, 5.0f * g, J.neck[0], tag(R::Skin, -1), 3.0f * k));
      } else {
        body.add(taperedCapsule(a, L.neck_chain[1], 5.5f * g, 5.2f * g, J.neck[0], tag(R::Skin, -1), 3.0f * k));
        body.add(taperedCapsule(L.neck_chain[1], b, 5.2f * g, 5.0f * g, J.neck[1], tag(R::Skin, -1), 3.0f * k));
      }
    }
    body.add(ellipsoid(L.skull, {7.6f * k, 11.0f * k, 9.6f * k}, J.head, tag(R::Skin, J.head), 3.0f * k));
    body.add(ellipsoid({0.0f, p.chin_height * H + 6.2f * k, L.head_pos.z + 3.5f * k}, {6.0f * k, 6.8f * k, 6.5f * k}, J.head,
                       tag(R::Skin, J.head), 3.0f * k));
    body.add(taperedCapsule({0.0f, L.eye_y - 1.0f * k, L.face_z - 0.8f * k}, {0.0f, L.eye_y - 4.3f * k, L.face_z + 1.2f * k}, 0.9f * k,
                            1.4f * k, J.head, tag(R::Skin, J.head), 1.2f * k));  // nose
    for (float sx : {-1.0f, 1.0f})
      body.add(ellipsoid({sx * 7.5f * k, L.eye_y - 2.0f * k, L.skull.z - 0.8f * k}, {1.0f * k, 3.0f * k, 2.0f * k}, J.head,
                         tag(R::Skin, J.head), 1.0f * k));  // ears
    ImplicitPrimitive cap = ellipsoid(L.skull + glm::vec3(0.0f, 0.3f * k, -0.5f * k), {8.3f * k, 11.5f * k, 10.3f * k}, J.head,
                                      tag(R::Hair, J.head), 0.6f * k);
    cap.clip_min.y = L.eye_y + 2.8f * k;
    body.add(cap);
    ImplicitPrimitive back_hair = ellipsoid(L.skull + glm::vec3(0.0f, -1.5f * k, -2.0f * k), {8.2f * k, 10.5f * k, 8.6f * k}, J.head,
                                            tag(R::Hair, J.head), 0.6f * k);
    back_hair.clip_max.z = L.skull.z - 2.0f * k;
    body.add(back_hair);
    body.add(taperedCapsule(L.skull + glm::vec3(0.0f, 1.0f * k, -9.5f * k), L.skull + glm::vec3(0.0f, -12.5f * k, -11.5f * k),
                            2.6f * k, 1.6f * k, J.head, tag(R::Hair, J.head), 1.0f * k));
  }

  // One side's arm (si 0 the +x side): trapezius, deltoid, upper arm and forearm in the jacket.
  void addArm(int si) const {
    const float k = L.k, g = L.g;
    const float sx = si == 0 ? 1.0f : -1.0f;
    const auto m = [&](glm::vec3 v) { return glm::vec3(v.x * sx, v.y, v.z); };
    const HumanoidSide& S = J.sides[si];
    const int shoulder_joint = S.clavicle >= 0 ? S.clavicle : topSpine();
    body.add(taperedCapsule(L.neck_pos + glm::vec3(sx * 3.0f * k, 1.0f * k, 0.0f), m(L.shoulder_pos) + glm::vec3(-sx * 2.0f * k, 3.0f * k, 0.0f),
                            5.0f * g, 5.5f * g, shoulder_joint, tag(R::Jacket, -1), 3.0f * k));  // trapezius
    body.add(ellipsoid(m(L.shoulder_pos + L.upper_dir * (1.5f * k)) + glm::vec3(0.0f, 1.0f * k, 0.0f), {6.5f * g, 6.0f * g, 6.5f * g},
                       S.upper[0], tag(R::Jacket, S.upper[0]), 4.0f * k, m(L.upper_dir)));  // deltoid
    twoHalves(m(L.shoulder_pos), m(L.elbow_pos), 5.2f * g, 4.2f * g, S.upper, R::Jacket, 3.0f * k);
    twoHalves(m(L.elbow_pos), m(L.wrist_pos - L.fore_dir * (1.0f * k)), 4.2f * g, 3.3f * g, S.fore, R::Jacket, 2.0f * k);
  }

  // One side's hand: wrist, palm, a mitten of four fingers on the finger chain, the thumb.
  void addHand(int si) const {
    const float k = L.k, g = L.g;
    const float sx = si == 0 ? 1.0f : -1.0f;
    const auto m = [&](glm::vec3 v) { return glm::vec3(v.x * sx, v.y, v.z); };
    const HumanoidSide& S = J.sides[si];
    const glm::vec3 hd = m(L.hand_dir), pn = m(L.palm_normal), ts = m(L.thumb_side);
    const glm::mat3 hand_axes(hd, pn, ts);
    const int palm_joint = S.palm >= 0 ? S.palm : S.hand;
    body.add(taperedCapsule(m(L.wrist_pos - L.fore_dir * (1.0f * k)), m(L.wrist_pos + L.hand_dir * (0.1f * L.HL)), 2.9f * g, 2.7f * g, S.hand,
                            tag(R::Skin, S.hand), 1.5f * k));
    body.add(orientedEllipsoid(m(L.wrist_pos + L.hand_dir * (0.27f * L.HL)), {0.28f * L.HL, 1.6f * k, 4.2f * k}, hand_axes, palm_joint,
                               tag(R::Skin, palm_joint), 1.5f * k));
    if (p.fingers) {
      for (int i = 0; i < 3; ++i) {
        const glm::vec3 a = L.index_pos[i], b = L.index_pos[i + 1];
        const float half = 0.5f * glm::length(b - a) + 0.6f * k;
        body.add(orientedEllipsoid(m(0.5f * (a + b)), {half, 1.1f * k, 3.8f * k * (1.0f - 0.08f * i)}, hand_axes, S.index[i],
                                   tag(R::Skin, S.index[i]), 0.8f * k));
      }
      const std::array<float, 4> tr = {1.5f * k, 1.2f * k, 1.05f * k, 0.9f * k};
      for (int i = 0; i < 3; ++i)
        body.add(taperedCapsule(m(L.thumb_pos[i]), m(L.thumb_pos[i + 1] - (i == 2 ? L.thumb_dir * tr[3] : glm::vec3(0.0f))), tr[i], tr[i + 1],
                                S.thumb[i], tag(R::Skin, S.thumb[i]), 0.8f * k));
    } else {
      const float half = 0.5f * glm::length(L.finger_tip - L.knuckle_pos);
      body.add(orientedEllipsoid(m(0.5f * (L.knuckle_pos + L.finger_tip)), {half, 1.1f * k, 3.8f * k}, hand_axes, palm_joint,
                                 tag(R::Skin, palm_joint), 0.8f * k));
      body.add(taperedCapsule(m(L.thumb_pos[0]), m(L.thumb_pos[3] - L.thumb_dir * (0.9f * k)), 1.5f * k, 0.9f * k, S.hand,
                              tag(R::Skin, S.hand), 0.8f * k));
    }
  }

  // One side's leg: breeches to below the knee, then the boot; a flat sole on the ground.
  void addLeg(int si) const {
    const float k = L.k, g = L.g;
    const float sx = si == 0 ? 1.0f : -1.0f;
    const auto m = [&](glm::vec3 v) { return glm::vec3(v.x * sx, v.y, v.z); };
    const HumanoidSide& S = J.sides[si];
    twoHalves(m(L.hip_pos) + glm::vec3(sx * 1.0f * k, 0.0f, 0.0f), m(L.knee_pos), 8.3f * g, 5.6f * g, S.thigh, R::Breeches, 4.0f * k);
    const glm::vec3 boot_top = glm::mix(L.knee_pos, L.ankle_pos, 0.25f);
    body.add(taperedCapsule(m(L.knee_pos), m(boot_top), 5.6f * g, 5.2f * g, S.shin[0], tag(R::Breeches, S.shin[0]), 2.0f * k));
    twoHalves(m(boot_top), m(L.ankle_pos), 5.8f * g, 4.3f * g, S.shin, R::Boots, 1.0f * k);
    const glm::vec3 heel(L.hip_x, 4.2f * k, L.heel_z + 4.2f * k);
    ImplicitPrimitive foot = taperedCapsule(m(heel), m(glm::vec3(L.hip_x, 3.0f * k, L.ball_pos.z)), 4.2f * k, 3.8f * k, S.foot,
                                            tag(R::Boots, -1), 1.5f * k);
    foot.clip_min.y = 0.0f;
    foot.clip_round = 0.4f * k;
    body.add(foot);
    ImplicitPrimitive toe = taperedCapsule(m(glm::vec3(L.hip_x, 3.0f * k, L.ball_pos.z)), m(L.toe_tip - glm::vec3(0.0f, 0.0f, 2.6f * k)), 3.8f * k,
                                           2.6f * k, S.toe >= 0 ? S.toe : S.foot, tag(R::Boots, -1), 0.6f * k);
    toe.clip_min.y = 0.0f;
    toe.clip_round = 0.4f * k;
    body.add(toe);
  }
};

ImplicitBody humanoidBody(const StandingHumanoidParams& p, const HumanoidLayout& L, const HumanoidJoints& J,
                          const Skeleton& s) {
  ImplicitBody body;
  const HumanoidBodyBuilder b{p, L, J, s, body};
  b.addTrunk();
  b.addHead();
  // Arms and legs, both sides.
  for (int si = 0; si < 2; ++si) {
    b.addArm(si);
    b.addHand(si);
    b.addLeg(si);
  }
  return body;
}

// The polygonised body, its trunk's weights spread along the spine.
SkinnedMesh skinHumanoid(const ImplicitBody& body, const StandingHumanoidParams& p, const HumanoidLayout& L,
                         const HumanoidJoints& J, const Skeleton& s) {
  const float k = L.k;
  const int N = L.N;
  PolygonizeParams poly;
  poly.cell = p.cell;
  poly.skin_falloff = 2.0f * k;
  SkinnedMesh mesh = polygonize(body, poly);
  {
    std::vector<int> chain = {J.pelvis};
    chain.insert(chain.end(), J.spine.begin(), J.spine.end());
    std::vector<float> middles;
    for (int i = 0; i <= N; ++i) {
      const float y0 = s.restPosition(chain[i]).y;
      const float y1 = i + 1 <= N ? s.restPosition(chain[i + 1]).y : L.neck_pos.y;
      middles.push_back(0.5f * (y0 + y1));
    }
    TorsoChain torso;
    torso.joints = chain;
    torso.middles = middles;
    spreadTorsoWeights(mesh, torso);
  }

  return mesh;
}

// A triangle's texture chart: its region, the frame it is projected in (0 the world, j + 1 joint j's bone
// frame) and the direction it faces there. Each chart is fitted into its region's tile.
struct HumanoidCharts {
  const std::vector<glm::mat3>& bone_frames;
  const Skeleton& s;
  std::vector<ChartKey> tri_chart;
  std::map<ChartKey, ChartFit> fits;

  glm::mat3 frameOf(int frame) const { return frame == 0 ? glm::mat3(1.0f) : bone_frames[frame - 1]; }
  glm::vec3 originOf(int frame) const { return frame == 0 ? glm::vec3(0.0f) : s.restPosition(frame - 1); }
  glm::vec3 local(glm::vec3 pos, int frame) const { return glm::transpose(frameOf(frame)) * (pos - originOf(frame)); }
};

// Each triangle's chart (the head's front chart is the face's), and each chart's fit in its tile.
HumanoidCharts chartTriangles(const SkinnedMesh& mesh, const Skeleton& s, const std::vector<glm::mat3>& bone_frames, int head) {
  using R = HumanoidRegion;
  HumanoidCharts charts{bone_frames, s, {}, {}};
  const std::size_t nt = mesh.triangleCount();
  std::vector<ChartKey>& tri_chart = charts.tri_chart;
  std::map<ChartKey, ChartFit>& fits = charts.fits;
  tri_chart.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t* tri = &mesh.indices[t * 3];
    const glm::vec3 tagv = mesh.colors[tri[0]];
    const int region = static_cast<int>(std::lround(tagv.x));
    const int frame = static_cast<int>(std::lround(tagv.y));
    const glm::vec3 n = glm::transpose(charts.frameOf(frame)) *
                        glm::cross(mesh.positions[tri[1]] - mesh.positions[tri[0]], mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    const glm::vec3 a = glm::abs(n);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    const int dir = axis * 2 + (n[axis] < 0.0f ? 1 : 0);
    ChartKey key{region, frame, dir};
    if (region == static_cast<int>(R::Skin) && frame == head + 1 && dir == 4) key.region = static_cast<int>(R::Face);
    tri_chart[t] = key;
    ChartFit& fit = fits[key];
    for (int v = 0; v < 3; ++v) {
      const glm::vec2 cc = chartCoords(charts.local(mesh.positions[tri[v]], frame), dir);
      fit.lo = glm::min(fit.lo, cc);
      fit.hi = glm::max(fit.hi, cc);
    }
  }
  for (auto& [key, fit] : fits) {
    const glm::vec2 size = glm::max(fit.hi - fit.lo, glm::vec2(1e-3f));
    const float room = static_cast<float>(kHumanoidTile - 2 * kTileMargin);
    fit.scale = room / std::max(size.x, size.y);
    const glm::vec2 used = size * fit.scale;
    fit.offset = glm::vec2(humanoidTileOrigin(static_cast<HumanoidRegion>(key.region))) + glm::vec2(static_cast<float>(kTileMargin)) +
                 0.5f * (glm::vec2(room) - used);
  }

  return charts;
}

// The mesh with its vertices split per chart, body triangles first, then the hair (from
// out.hair_first_index), coloured by region, with their texture coordinates in out.uvs.
void splitByChart(const SkinnedMesh& mesh, const HumanoidCharts& charts, const Palette& pal, StandingHumanoid& out) {
  using R = HumanoidRegion;
  const std::size_t nt = mesh.triangleCount();
  const std::vector<ChartKey>& tri_chart = charts.tri_chart;
  const std::map<ChartKey, ChartFit>& fits = charts.fits;
  SkinnedMesh& split = out.character.mesh;
  std::map<std::pair<std::uint32_t, ChartKey>, std::uint32_t> vertex_of;
  const glm::vec2 texture_size(static_cast<float>(kHumanoidTextureWidth), static_cast<float>(kHumanoidTextureHeight));
  const auto region_color = [&](int region) {
    const glm::u8vec3 c8 = pal.of(static_cast<HumanoidRegion>(region));
    return glm::vec3(srgbToLinear(c8.x), srgbToLinear(c8.y), srgbToLinear(c8.z));
  };
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) out.hair_first_index = split.indices.size();
    for (std::size_t t = 0; t < nt; ++t) {
      const ChartKey& key = tri_chart[t];
      if ((key.region == static_cast<int>(R::Hair)) != (pass == 1)) continue;
      for (int v = 0; v < 3; ++v) {
        const std::uint32_t old = mesh.indices[t * 3 + v];
        auto [it, fresh] = vertex_of.emplace(std::make_pair(old, key), static_cast<std::uint32_t>(split.positions.size()));
        if (fresh) {
          split.positions.push_back(mesh.positions[old]);
          split.normals.push_back(mesh.normals[old]);
          split.colors.push_back(region_color(key.region));
          split.joints.push_back(mesh.joints[old]);
          split.weights.push_back(mesh.weights[old]);
          const glm::vec2 px = fits.at(key).pixel(chartCoords(charts.local(mesh.positions[old], key.frame), key.dir));
          out.uvs.push_back(px / texture_size);
        }
        split.indices.push_back(it->second);
      }
    }
  }

}

// The texture, with a face drawn where the head's front chart put it.
void paintHumanoidTexture(const HumanoidCharts& charts, const Palette& pal, const StandingHumanoidParams& p,
                          const HumanoidLayout& L, int head, RgbImage& texture) {
  using R = HumanoidRegion;
  const float H = L.H, k = L.k;
  paintTiles(texture, pal);
  const ChartKey face_key{static_cast<int>(R::Face), head + 1, 4};
  if (const auto it = charts.fits.find(face_key); it != charts.fits.end()) {
    const ChartFit& fit = it->second;
    const auto px = [&](glm::vec3 world) { return fit.pixel(chartCoords(charts.local(world, head + 1), 4)); };
    const float r = 1.0f * k * fit.scale;
    for (float sx : {-1.0f, 1.0f}) {
      const glm::vec3 eye(sx * 3.1f * k, L.eye_y, L.face_z);
      fillEllipse(texture, px(eye), {1.5f * r, 0.9f * r}, {245, 245, 240});
      fillEllipse(texture, px(eye), {0.7f * r, 0.7f * r}, {40, 60, 90});
      fillEllipse(texture, px(eye + glm::vec3(0.0f, 1.9f * k, 0.0f)), {1.9f * r, 0.35f * r}, shade(pal.hair, 0.8f));
    }
    fillEllipse(texture, px({0.0f, p.chin_height * H + 3.4f * k, L.face_z}), {2.3f * r, 0.5f * r}, {170, 60, 60});
  }
}

}  // namespace

StandingHumanoid buildStandingHumanoid(const StandingHumanoidParams& params) {
  StandingHumanoidParams p = params;
  checkHumanoidParams(p);
  const Palette pal = varyHumanoid(p);
  StandingHumanoid out;
  out.params = p;
  Character& c = out.character;
  c.name = "humanoid";
  const Skeleton& s = c.skeleton;
  const HumanoidLayout L = layoutHumanoid(p);
  const HumanoidJoints J = addHumanoidJoints(p, L, out);
  // Rest frames: every joint's bone frame, used for the texture charts; the file's own are these or
  // identity.
  std::vector<glm::mat3> bone_frames(s.size());
  for (std::size_t j = 0; j < s.size(); ++j) bone_frames[j] = boneAxes(s.restPosition(static_cast<int>(j)), out.tails[j]);
  out.rest_axes = p.joint_axes == HumanoidJointAxes::Bone ? bone_frames : std::vector<glm::mat3>(s.size(), glm::mat3(1.0f));

  const SkinnedMesh mesh = skinHumanoid(humanoidBody(p, L, J, s), p, L, J, s);
  const HumanoidCharts charts = chartTriangles(mesh, s, bone_frames, J.head);
  splitByChart(mesh, charts, pal, out);
  paintHumanoidTexture(charts, pal, p, L, J.head, out.texture);
  return out;
}

}  // namespace stirrup::rig
