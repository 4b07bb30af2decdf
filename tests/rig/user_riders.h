// Riders stirrup has never seen, for tests: the standing test humanoids (rig/characters/
// standing_humanoid.h) in several conventions, rest poses and layouts, written as other tools write
// them (rig/io/gltf_humanoid.h: metres, +Y up, facing +Z, bone-aligned joints, a texture), each with a
// mapping file made from the generator's own anatomical labels (not from stirrup's mapper), so a test
// can load them as a user would with a hand-written mapping.
#pragma once

#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/characters/standing_humanoid.h"
#include "rig/io/gltf_humanoid.h"

namespace stirrup::rig::test {

struct UserRiderSpec {
  std::string name;
  StandingHumanoidParams params;
};
// GoogleTest prints a parameter by its name.
// A generated humanoid on a coarse grid (cell 4 cm): what the mapping reads, its skeleton and the mesh's
// height, without the cost of a fine mesh.
inline StandingHumanoid coarseHumanoid(HumanoidNames names) {
  StandingHumanoidParams p = humanoidConventionDefaults(names);
  p.cell = 4.0f;
  return buildStandingHumanoid(p);
}

inline void PrintTo(const UserRiderSpec& spec, std::ostream* os) { *os << spec.name; }

// The list: T- and A-pose, 2, 3 and 6 spine joints, a shared wrist/hand, Mixamo-, Rigify-,
// mannequin- and VRM-style names; plus HumanIK names without toes and a short rider with meaningless
// names, so proportions and layouts differ from one to the next.
inline std::vector<UserRiderSpec> userRiderSpecs() {
  std::vector<UserRiderSpec> out;
  const auto add = [&](std::string name, HumanoidNames names, auto&& change) {
    StandingHumanoidParams p = humanoidConventionDefaults(names);
    change(p);
    out.push_back({std::move(name), p});
  };
  add("mixamo_t3", HumanoidNames::Mixamo, [](StandingHumanoidParams& p) { p.pose = HumanoidRestPose::T; p.spine_joints = 3; });
  add("rigify_a6", HumanoidNames::Rigify, [](StandingHumanoidParams& p) { p.pose = HumanoidRestPose::A; p.spine_joints = 6; });
  add("unreal_relaxed2_shared", HumanoidNames::Unreal, [](StandingHumanoidParams& p) {
    p.pose = HumanoidRestPose::Relaxed;
    p.spine_joints = 2;
    p.separate_hand = false;
  });
  add("vrm_a3_short", HumanoidNames::Vrm, [](StandingHumanoidParams& p) {
    p.pose = HumanoidRestPose::A;
    p.spine_joints = 3;
    p.height = 158.0f;
    p.seed = 7;
  });
  add("humanik_t2_no_toes", HumanoidNames::HumanIK, [](StandingHumanoidParams& p) {
    p.pose = HumanoidRestPose::T;
    p.spine_joints = 2;
    p.toes = false;
    p.height = 184.0f;
    p.seed = 3;
  });
  return out;
}

// Each rider role's joint, from the generator's labels: the pelvis, the first neck joint, the head;
// per side the upper arm's root, the forearm's root, the joint at the wrist, the palm joint as the hand
// where there is one, the thigh's and the shin's roots, the foot at the ankle and the toe; with
// `upper_chest`, also the top spine joint where the clavicles hang from it (not with detached limbs).
inline std::map<std::string, std::string> labelledRiderRoles(const StandingHumanoid& h, bool upper_chest) {
  std::map<std::string, std::string> roles;
  const Skeleton& s = h.character.skeleton;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const HumanoidJointLabel& l = h.labels[j];
    const std::string side = l.side > 0 ? "l" : "r";
    const std::string& name = s.joints[j].name;
    switch (l.bone) {
      case HumanoidBone::Pelvis: roles["pelvis"] = name; break;
      case HumanoidBone::Neck: if (l.index == 0) roles["neck"] = name; break;
      case HumanoidBone::Head: roles["head"] = name; break;
      case HumanoidBone::Spine:
        if (upper_chest && l.index == h.params.spine_joints - 1 && !h.params.detached_limbs) roles["upperChest"] = name;
        break;
      case HumanoidBone::UpperArm: if (l.index == 0) roles[side + "Shoulder"] = name; break;
      case HumanoidBone::Forearm: if (l.index == 0) roles[side + "Elbow"] = name; break;
      case HumanoidBone::Hand: roles[side + "Wrist"] = name; break;
      case HumanoidBone::Palm: roles[side + "Hand"] = name; break;
      case HumanoidBone::UpperLeg: if (l.index == 0) roles[side + "Hip"] = name; break;
      case HumanoidBone::LowerLeg: if (l.index == 0) roles[side + "Knee"] = name; break;
      case HumanoidBone::Foot: roles[side + "Ankle"] = name; break;
      case HumanoidBone::Toe: roles[side + "Ball"] = name; break;
      default: break;
    }
  }
  return roles;
}

// The mapping a user would write for it: the roles above, without upperChest.
inline nlohmann::json userRiderMapping(const StandingHumanoid& h) {
  return {{"character", "rider"}, {"scale_cm", 100}, {"forward", {0, 0, 1}}, {"up", {0, 1, 0}},
          {"roles", labelledRiderRoles(h, false)}};
}

struct UserRiderFiles {
  std::filesystem::path glb, mapping;
};

// Writes the rider's .glb and its mapping file into `dir` (made if need be).
inline UserRiderFiles writeUserRider(const UserRiderSpec& spec, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const StandingHumanoid h = buildStandingHumanoid(spec.params);
  UserRiderFiles f{dir / (spec.name + ".glb"), dir / (spec.name + "-mapping.json")};
  const std::vector<unsigned char> bytes = humanoidGlb(h);
  std::ofstream(f.glb, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  std::ofstream(f.mapping) << userRiderMapping(h).dump(2);
  return f;
}

}  // namespace stirrup::rig::test
