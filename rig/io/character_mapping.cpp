#include "rig/io/character_mapping.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "rig/error.h"
#include "rig/io/json_fields.h"
#include "rig/characters/rider_character.h"

namespace stirrup::rig {

std::string_view characterKindName(CharacterKind kind) { return kind == CharacterKind::Horse ? "horse" : "rider"; }

const std::vector<std::string>& requiredRoles(CharacterKind kind) {
  static const std::vector<std::string> horse = [] {
    std::vector<std::string> r = {"root",  "backMid",  "chest",    "withers", "neck1",  "neck2", "head",  "saddle",
                                  "lStirrup", "rStirrup", "tail1", "tail2", "tail3", "lRein", "rRein"};
    for (const char* leg : {"lf", "rf", "lb", "rb"})
      for (const char* part : {"Upper", "Middle", "Fetlock", "Hoof"}) r.push_back(std::string(leg) + part);
    return r;
  }();
  static const std::vector<std::string> rider = [] {
    std::vector<std::string> r = {"pelvis", "neck", "head"};
    for (const char* side : {"l", "r"})
      for (const char* part : {"Shoulder", "Elbow", "Wrist", "Hip", "Knee", "Ankle"}) r.push_back(std::string(side) + part);
    return r;
  }();
  return kind == CharacterKind::Horse ? horse : rider;
}

const std::vector<std::string>& optionalRoles(CharacterKind kind) {
  static const std::vector<std::string> horse = {"lfPivot", "rfPivot", "lbPivot", "rbPivot"};
  static const std::vector<std::string> rider = [] {
    std::vector<std::string> r = {"lowerBack", "waist", "chest", "upperChest", "hipCentre", "braid1", "braid2", "braid3", "coatTail"};
    for (const char* side : {"l", "r"})
      for (const char* part : {"Hand", "Ball"}) r.push_back(std::string(side) + part);
    for (int i = 0; i <= kRiderSpineSegments; ++i) r.push_back("spine" + std::to_string(i));
    return r;
  }();
  return kind == CharacterKind::Horse ? horse : rider;
}

CharacterMapping loadCharacterMapping(const std::filesystem::path& file, CharacterKind kind) {
  const nlohmann::json json = readJsonFile(file);
  JsonObjectReader r(file.string(), "", json);
  CharacterMapping m;
  m.file = file;
  r.string("comment", "");
  const std::string expected(characterKindName(kind));
  const std::string character = r.string("character", expected);
  if (character != expected)
    r.fail("character", "expected \"" + expected + "\" (this file is used for the " + expected + "), got \"" +
                            character + "\"");
  m.scale_cm = r.number("scale_cm", m.scale_cm);
  if (!(m.scale_cm > 0.0)) r.fail("scale_cm", "expected centimetres per file unit > 0");
  m.forward = r.numbers<3>("forward", m.forward);
  m.up = r.numbers<3>("up", m.up);
  m.offset_cm = r.numbers<3>("offset_cm", m.offset_cm);
  const auto len = [](const std::array<double, 3>& a) { return a[0] * a[0] + a[1] * a[1] + a[2] * a[2]; };
  const double dot = m.forward[0] * m.up[0] + m.forward[1] * m.up[1] + m.forward[2] * m.up[2];
  if (!(len(m.forward) > 1e-12)) r.fail("forward", "expected a non-zero direction");
  if (!(len(m.up) > 1e-12)) r.fail("up", "expected a non-zero direction");
  if (std::abs(dot) > 1e-6 * std::sqrt(len(m.forward) * len(m.up))) r.fail("up", "expected a direction at right angles to forward");
  const nlohmann::json* roles = r.value("roles");
  if (!roles || !roles->is_object())
    r.fail("roles", "expected an object from role names to joint names, got " + (roles ? describeJson(*roles) : "nothing"));
  const std::vector<std::string>& needed = requiredRoles(kind);
  const std::vector<std::string>& optional = optionalRoles(kind);
  for (const auto& [role, joint] : roles->items()) {
    if (std::find(needed.begin(), needed.end(), role) == needed.end() &&
        std::find(optional.begin(), optional.end(), role) == optional.end())
      r.fail("roles." + role, "unknown " + expected + " role (docs/characters.md lists them)");
    if (!joint.is_string()) r.fail("roles." + role, "expected a joint name, got " + describeJson(joint));
    m.roles[role] = joint.get<std::string>();
  }
  for (const std::string& role : needed)
    if (!m.roles.count(role)) r.fail("roles." + role, "missing: expected the name of the " + expected + "'s " + role + " joint");
  r.finish();
  return m;
}

glm::dmat4 mappingToRig(const CharacterMapping& m) {
  const glm::dvec3 fw = glm::normalize(glm::dvec3(m.forward[0], m.forward[1], m.forward[2]));
  const glm::dvec3 up = glm::normalize(glm::dvec3(m.up[0], m.up[1], m.up[2]));
  const glm::dmat3 rows(fw, up, glm::cross(fw, up));  // columns; transposed, the rows
  glm::dmat4 to_rig(glm::transpose(rows) * m.scale_cm);
  to_rig[3] = glm::dvec4(m.offset_cm[0], m.offset_cm[1], m.offset_cm[2], 1.0);
  return to_rig;
}

}  // namespace stirrup::rig
