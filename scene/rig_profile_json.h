// Rig profile files (scenes/profiles/NAME.json): a profile read from JSON, single parameters set by
// their key (a scene's profile_overrides, `--set`), and a profile written back as JSON. The profile
// itself, its thesis values and the key table are runtime (rig/rig_profile.h).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "rig/rig_profile.h"

namespace stirrup::scene {

// nameOrPath: a name ("thesis") looked up as profilesDir/NAME.json, or a path to a .json file.
// Parameters the file does not name keep the thesis value.
rig::RigProfile loadRigProfile(const std::string& nameOrPath, const std::filesystem::path& profilesDir);
// Overrides single parameters by their JSON key; unknown key or wrong type -> InputError naming `context` and the key.
void applyProfileOverrides(rig::RigProfile& p, const nlohmann::json& overrides, const std::string& context);
// The JSON form of a profile: name, doc and every parameter by key.
nlohmann::json profileToJson(const rig::RigProfile& p);

}  // namespace stirrup::scene
