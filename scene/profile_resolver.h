// Finding a rig profile by the name or path a scene's "profile" or the command line's --profile gives,
// and applying the overrides after it: the one rule every command uses (docs/rider-rig.md, "Where
// profiles are found").
//
// A value ending in .json or holding a '/' is a file: a relative one is relative to the scene file's
// folder (a scene's "profile") or to the working folder (--profile). Any other value is a name, NAME,
// read from the first of these folders that holds NAME.json:
//   1. the scene's own profiles/ folder (SCENE_DIR/profiles), for a scene's profile;
//   2. $STIRRUP_PROFILES, when set;
//   3. scenes/profiles in stirrup's data folder (scene/data_dir.h), when there is one.
// A scene's own folder comes first so a scene renders with the profiles it was made with whoever runs
// it (a farm node's environment included). "rigid" is built in (RigProfile::rigidRider()) unless one
// of the folders has a rigid.json. Then the scene's profile_overrides apply, then the command line's
// --set, each checked against the parameter table (scene::applyProfileOverrides).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/rig_profile.h"

namespace stirrup::scene {

struct SceneSpec;

// Where a profile value is looked for.
struct ProfileSearch {
  std::filesystem::path base;                  // a relative path's folder; empty: the working folder
  std::vector<std::filesystem::path> folders;  // NAME.json is looked for in each, in order
};

// The search for a scene file's profile (scene_file given) or the command line's (empty), by the rule
// above, reading $STIRRUP_PROFILES and the data folder now.
ProfileSearch profileSearch(const std::filesystem::path& scene_file = {});

// Whether `value` names a file (ends in .json or holds a '/') rather than a profile name.
bool isProfilePath(const std::string& value);

// The profile `value` names, found by `search`. InputError naming `context` ("--profile",
// "scenes/x.json: profile") when no folder holds the name, listing the folders and the names they
// hold; a file's own errors name the file (scene::loadRigProfile).
rig::RigProfile findProfile(const std::string& value, const ProfileSearch& search, const std::string& context);

// The scene's profile: its "profile" found by profileSearch(scene.file), its profile_overrides applied,
// then `sets` (the command line's --set, named "--set" in errors).
rig::RigProfile resolveProfile(const SceneSpec& scene, const nlohmann::json& sets = nlohmann::json::object());

// The scene's profile as above, and `sets` joined to the scene's profile_overrides after its own: a
// crowd's pairs resolve their own profiles from the scene (ShotEvaluator), so the command line's --set
// reaches every pair, not only the scene's profile. Errors in `sets` name "--set".
rig::RigProfile resolveProfileForEveryPair(SceneSpec& scene, const nlohmann::json& sets);

// The command line's --profile VALUE found by profileSearch(), then `sets` (--set).
rig::RigProfile resolveProfile(const std::string& value, const nlohmann::json& sets = nlohmann::json::object());

}  // namespace stirrup::scene
