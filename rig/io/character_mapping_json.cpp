#include "rig/io/character_mapping_json.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rig/error.h"
#include "rig/io/json_fields.h"
#include "rig/mapping/character_mapping.h"

namespace stirrup::rig {

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
  m.scale_cm = r.number("scale_cm", m.scale_cm, kMinMappingScaleCm, kMaxMappingScaleCm, "centimetres per file unit");
  m.forward = r.numbers<3>("forward", m.forward, -kMaxMappingAxis, kMaxMappingAxis);
  m.up = r.numbers<3>("up", m.up, -kMaxMappingAxis, kMaxMappingAxis);
  m.offset_cm = r.numbers<3>("offset_cm", m.offset_cm, -kMaxMappingOffsetCm, kMaxMappingOffsetCm);
  if (const auto [field, expected] = mappingAxesProblem(m.forward, m.up); !field.empty()) r.fail(field, expected);
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

}  // namespace stirrup::rig
