#include "scene/profile_resolver.h"

#include <cstdlib>
#include <optional>
#include <set>
#include <system_error>

#include "rig/error.h"
#include "scene/data_dir.h"
#include "scene/rig_profile_json.h"
#include "scene/scene.h"

namespace stirrup::scene {

namespace fs = std::filesystem;

ProfileSearch profileSearch(const fs::path& scene_file) {
  ProfileSearch search;
  if (!scene_file.empty()) {
    search.base = scene_file.parent_path();
    search.folders.push_back(search.base / "profiles");
  }
  if (const char* env = std::getenv("STIRRUP_PROFILES"); env && *env) search.folders.push_back(env);
  if (const std::optional<fs::path> data = findDataDir()) search.folders.push_back(*data / "scenes" / "profiles");
  return search;
}

bool isProfilePath(const std::string& value) {
  return fs::path(value).extension() == ".json" || value.find('/') != std::string::npos;
}

rig::RigProfile findProfile(const std::string& value, const ProfileSearch& search, const std::string& context) {
  if (value.empty()) throw rig::InputError(context + ": expected a rig profile name or a .json path, got \"\"");
  if (isProfilePath(value)) {
    const fs::path file = search.base / value;
    return scene::loadRigProfile(file.string(), file.parent_path());
  }
  std::error_code ec;
  for (const fs::path& folder : search.folders)
    if (const fs::path file = folder / (value + ".json"); fs::is_regular_file(file, ec))
      return scene::loadRigProfile(file.string(), folder);
  if (value == "rigid") return rig::RigProfile::rigidRider();

  std::set<std::string> names = {"rigid"};
  std::string folders;
  for (const fs::path& folder : search.folders) {
    folders += (folders.empty() ? "" : ", ") + folder.string();
    for (const auto& e : fs::directory_iterator(folder, ec))
      if (e.path().extension() == ".json") names.insert(e.path().stem().string());
  }
  std::string expected;
  for (const std::string& n : names) expected += n + ", ";
  throw rig::InputError(context + ": no rig profile \"" + value + "\" in " + (folders.empty() ? "any folder" : folders) +
                   " (expected one of " + expected + "or a path to a .json file)");
}

rig::RigProfile resolveProfile(const SceneSpec& scene, const nlohmann::json& sets) {
  rig::RigProfile p = findProfile(scene.profile, profileSearch(scene.file), scene.file.string() + ": profile");
  scene::applyProfileOverrides(p, scene.profile_overrides, scene.file.string() + ": profile_overrides");
  scene::applyProfileOverrides(p, sets, "--set");
  return p;
}

rig::RigProfile resolveProfileForEveryPair(SceneSpec& scene, const nlohmann::json& sets) {
  rig::RigProfile p = resolveProfile(scene, sets);  // checked here, so that an error names --set
  for (const auto& [key, value] : sets.items()) scene.profile_overrides[key] = value;
  return p;
}

rig::RigProfile resolveProfile(const std::string& value, const nlohmann::json& sets) {
  rig::RigProfile p = findProfile(value, profileSearch(), "--profile");
  scene::applyProfileOverrides(p, sets, "--set");
  return p;
}

}  // namespace stirrup::scene
