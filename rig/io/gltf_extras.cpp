#include "rig/io/gltf_extras.h"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include <tiny_gltf.h>

namespace stirrup::rig {
namespace {

// Whether the value holds an empty array or object anywhere: what tinygltf would write as null.
bool holdsEmpty(const tinygltf::Value& v) {
  if (v.IsArray()) {
    if (v.ArrayLen() == 0) return true;
    for (std::size_t i = 0; i < v.ArrayLen(); ++i)
      if (holdsEmpty(v.Get(int(i)))) return true;
  }
  if (v.IsObject()) {
    if (v.Keys().empty()) return true;
    for (const std::string& k : v.Keys())
      if (holdsEmpty(v.Get(k))) return true;
  }
  return false;
}

std::uint32_t readU32(const std::vector<unsigned char>& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // GLB is little-endian, as every target stirrup builds for
  return v;
}

void writeU32(std::vector<unsigned char>& b, std::size_t at, std::uint32_t v) { std::memcpy(b.data() + at, &v, 4); }

// Each element's extras of `array` in the JSON from the model's `elements`.
template <class T>
void replaceExtras(nlohmann::json& json, const char* array, const std::vector<T>& elements) {
  if (!json.contains(array)) return;
  nlohmann::json& list = json[array];
  for (std::size_t i = 0; i < elements.size() && i < list.size(); ++i)
    if (elements[i].extras.IsObject() || elements[i].extras.IsArray()) list[i]["extras"] = extrasJson(elements[i].extras);
}

}  // namespace

nlohmann::json extrasJson(const tinygltf::Value& v) {
  if (v.IsBool()) return v.Get<bool>();
  if (v.IsInt()) return v.Get<int>();
  if (v.IsNumber()) return v.GetNumberAsDouble();
  if (v.IsString()) return v.Get<std::string>();
  if (v.IsArray()) {
    nlohmann::json a = nlohmann::json::array();
    for (std::size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(extrasJson(v.Get(int(i))));
    return a;
  }
  if (v.IsObject()) {
    nlohmann::json o = nlohmann::json::object();
    for (const std::string& k : v.Keys()) o[k] = extrasJson(v.Get(k));
    return o;
  }
  return nullptr;
}

std::vector<unsigned char> withExactExtras(const tinygltf::Model& model, std::vector<unsigned char> glb) {
  bool empty = false;
  for (const tinygltf::Node& n : model.nodes) empty = empty || holdsEmpty(n.extras);
  for (const tinygltf::Scene& s : model.scenes) empty = empty || holdsEmpty(s.extras);
  for (const tinygltf::Mesh& m : model.meshes) empty = empty || holdsEmpty(m.extras);
  for (const tinygltf::Material& m : model.materials) empty = empty || holdsEmpty(m.extras);
  for (const tinygltf::Camera& c : model.cameras) empty = empty || holdsEmpty(c.extras);
  if (!empty) return glb;
  // GLB (glTF 2.0, section 4.4): a 12-byte header, the JSON chunk (length, "JSON", text padded with
  // spaces to 4 bytes), then the BIN chunk, kept as it is.
  if (glb.size() < 20 || readU32(glb, 16) != 0x4E4F534Au) throw std::logic_error("withExactExtras: not a GLB with a JSON chunk first");
  const std::size_t json_length = readU32(glb, 12);
  nlohmann::json json = nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + std::ptrdiff_t(json_length));
  replaceExtras(json, "nodes", model.nodes);
  replaceExtras(json, "scenes", model.scenes);
  replaceExtras(json, "meshes", model.meshes);
  replaceExtras(json, "materials", model.materials);
  replaceExtras(json, "cameras", model.cameras);
  std::string text = json.dump();
  while (text.size() % 4) text.push_back(' ');
  std::vector<unsigned char> out(glb.begin(), glb.begin() + 12);
  out.resize(20);
  writeU32(out, 12, std::uint32_t(text.size()));
  writeU32(out, 16, 0x4E4F534Au);  // "JSON"
  out.insert(out.end(), text.begin(), text.end());
  out.insert(out.end(), glb.begin() + 20 + std::ptrdiff_t(json_length), glb.end());
  writeU32(out, 8, std::uint32_t(out.size()));
  return out;
}

}  // namespace stirrup::rig
