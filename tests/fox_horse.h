// The Khronos Fox (the shared assets' Fox.glb, CC-BY 4.0 rig by @tomkranis) mapped as a horse with
// every role named, tack included, by its joints' own names; 3.5 cm a unit (its hips 42.9 units high, a
// horse's about 150 cm). Shared by the tests that load it as a user's horse.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace stirrup::test {

inline std::filesystem::path foxGlb() { return std::filesystem::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb"; }

// The mapping file's JSON.
inline nlohmann::json foxHorseMapping() {
  const nlohmann::json roles = {
      {"root", "b_Hip_01"},        {"backMid", "b_Spine01_02"},  {"chest", "b_Spine02_03"},
      {"withers", "b_Spine02_03"}, {"neck1", "b_Neck_04"},       {"neck2", "b_Neck_04"},
      {"head", "b_Head_05"},       {"saddle", "b_Spine01_02"},   {"lStirrup", "b_Spine01_02"},
      {"rStirrup", "b_Spine01_02"}, {"lRein", "b_Head_05"},      {"rRein", "b_Head_05"},
      {"tail1", "b_Tail01_012"},   {"tail2", "b_Tail02_013"},    {"tail3", "b_Tail03_014"},
      {"lfUpper", "b_LeftUpperArm_09"}, {"lfMiddle", "b_LeftForeArm_010"}, {"lfFetlock", "b_LeftHand_011"},
      {"lfHoof", "b_LeftHand_011"},     {"rfUpper", "b_RightUpperArm_06"}, {"rfMiddle", "b_RightForeArm_07"},
      {"rfFetlock", "b_RightHand_08"},  {"rfHoof", "b_RightHand_08"},      {"lbUpper", "b_LeftLeg01_015"},
      {"lbMiddle", "b_LeftLeg02_016"},  {"lbFetlock", "b_LeftFoot01_017"}, {"lbHoof", "b_LeftFoot02_018"},
      {"rbUpper", "b_RightLeg01_019"},  {"rbMiddle", "b_RightLeg02_020"},  {"rbFetlock", "b_RightFoot01_021"},
      {"rbHoof", "b_RightFoot02_022"}};
  return {{"character", "horse"}, {"scale_cm", 3.5}, {"forward", {0, 0, 1}}, {"up", {0, 1, 0}}, {"roles", roles}};
}

}  // namespace stirrup::test
