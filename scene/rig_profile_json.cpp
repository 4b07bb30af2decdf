// Rig profile files: reading a profile from JSON, single overrides by key, and the JSON form.
#include "scene/rig_profile_json.h"

#include <charconv>
#include <set>

#include "rig/error.h"
#include "rig/io/json_fields.h"

namespace stirrup::scene {
namespace {

std::string knownKeysHint() { return "see docs/rider-rig.md for the parameter keys"; }

// Shortest round-trip text of a number for messages: 1e+300, 0.1, -20.
std::string formatValue(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::to_string(v);
}

void setParameter(rig::RigProfile& p, const std::string& key, const nlohmann::json& value, const std::string& context) {
  const rig::RigParameter* param = rig::findRigParameter(key);
  if (!param) throw rig::InputError(context + ": " + key + ": unknown rig profile parameter (" + knownKeysHint() + ")");
  if (!value.is_number())
    throw rig::InputError(context + ": " + key + ": expected a number, got " + rig::describeJson(value));
  const double v = value.get<double>();
  // Every parameter has a documented range (docs/rider-rig.md, "Valid ranges"): a value past it is a
  // typo or a unit slip that would render a broken rider, or divide by zero.
  if (!param->accepts(v))
    throw rig::InputError(context + ": " + key + ": expected a number from " + formatValue(param->min) + " to " +
                     formatValue(param->max) + " (docs/rider-rig.md, valid ranges), got " + formatValue(v));
  param->field(p) = v;
}

}  // namespace

rig::RigProfile loadRigProfile(const std::string& nameOrPath, const std::filesystem::path& profilesDir) {
  namespace fs = std::filesystem;
  const bool is_path = fs::path(nameOrPath).extension() == ".json" || nameOrPath.find('/') != std::string::npos;
  if (nameOrPath.empty()) throw rig::InputError("rig profile: expected a profile name or a .json path, got \"\"");
  const fs::path file = is_path ? fs::path(nameOrPath) : profilesDir / (nameOrPath + ".json");
  if (!is_path && nameOrPath == "rigid" && !fs::exists(file)) return rig::RigProfile::rigidRider();
  if (!fs::exists(file)) {
    std::string names;
    std::error_code ec;
    std::set<std::string> found;
    for (const auto& e : fs::directory_iterator(profilesDir, ec))
      if (e.path().extension() == ".json") found.insert(e.path().stem().string());
    for (const std::string& n : found) names += (names.empty() ? "" : ", ") + n;
    throw rig::InputError(file.string() + ": no such rig profile" +
                     (names.empty() ? std::string() : " (expected one of " + names + ")"));
  }
  const nlohmann::json j = rig::readJsonFile(file);
  if (!j.is_object()) throw rig::InputError(file.string() + ": expected a JSON object, got " + rig::describeJson(j));

  rig::RigProfile p = rig::RigProfile::thesis();
  p.name = file.stem().string();
  p.doc.clear();
  for (const auto& [key, value] : j.items()) {
    if (key == "rigid") {
      if (!value.is_boolean()) throw rig::InputError(file.string() + ": rigid: expected true or false, got " + rig::describeJson(value));
      p.rigid = value.get<bool>();
    } else if (key == "name" || key == "doc") {
      if (!value.is_string()) throw rig::InputError(file.string() + ": " + key + ": expected a string, got " + rig::describeJson(value));
      (key == "name" ? p.name : p.doc) = value.get<std::string>();
    } else if (key == "notes") {
      // Why each value is what it is: documentation, but it must name real parameters.
      if (!value.is_object()) throw rig::InputError(file.string() + ": notes: expected an object, got " + rig::describeJson(value));
      for (const auto& [note_key, note] : value.items()) {
        if (!rig::findRigParameter(note_key))
          throw rig::InputError(file.string() + ": notes." + note_key + ": unknown rig profile parameter (" + knownKeysHint() + ")");
        if (!note.is_string())
          throw rig::InputError(file.string() + ": notes." + note_key + ": expected a string, got " + rig::describeJson(note));
      }
    } else {
      setParameter(p, key, value, file.string());
    }
  }
  return p;
}

void applyProfileOverrides(rig::RigProfile& p, const nlohmann::json& overrides, const std::string& context) {
  if (overrides.is_null()) return;
  if (!overrides.is_object())
    throw rig::InputError(context + ": expected an object of parameter keys and numbers, got " + rig::describeJson(overrides));
  for (const auto& [key, value] : overrides.items()) setParameter(p, key, value, context);
}

nlohmann::json profileToJson(const rig::RigProfile& p) {
  nlohmann::json j = nlohmann::json::object();
  j["name"] = p.name;
  j["doc"] = p.doc;
  if (p.rigid) j["rigid"] = true;
  for (const rig::RigParameter& param : rig::rigParameters()) j[std::string(param.key)] = param.get(p);
  return j;
}

}  // namespace stirrup::scene
