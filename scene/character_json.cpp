#include "scene/character_json.h"

namespace stirrup::scene {

CharacterEntry parseCharacterEntry(rig::JsonObjectReader& r, const std::string& key, const std::filesystem::path& dir,
                                   const CharacterEntry& fallback) {
  const nlohmann::json* v = r.value(key);
  if (!v) return fallback;
  const auto resolve = [&](rig::JsonObjectReader& at, const std::string& field, const std::string& name) {
    const std::filesystem::path f = dir / name;
    if (!std::filesystem::exists(f)) at.fail(field, "no such file: " + f.string());
    return f.string();
  };
  CharacterEntry out;
  if (v->is_string() && v->get<std::string>() == "default") return out;
  if (v->is_string()) {
    out.file = resolve(r, key, v->get<std::string>());
  } else if (v->is_object()) {
    rig::JsonObjectReader o = r.object(key);
    const std::string f = o.string("file", "");
    if (f.empty()) o.fail("file", "expected a glTF file (.glb or .gltf)");
    out.file = f == "default" ? f : resolve(o, "file", f);
    const std::string m = o.string("mapping", "");
    if (!m.empty()) out.mapping = resolve(o, "mapping", m);
    o.finish();
  } else {
    r.fail(key, "expected \"default\", a glTF file or {\"file\": ..., \"mapping\": ...}, got " + rig::describeJson(*v));
  }
  return out;
}

}  // namespace stirrup::scene
