// scene/character_json.h: a character entry as a scene's "characters" and a crowd's name it.
#include "scene/character_json.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

const std::filesystem::path kScenes = STIRRUP_SOURCE_DIR "/scenes";

CharacterEntry entryOf(const std::string& json) {
  const nlohmann::json j = nlohmann::json::parse(json);
  rig::JsonObjectReader r("s.json", "characters", j);
  return parseCharacterEntry(r, "horse", kScenes, {"fallback.glb", "fallback.json"});
}

TEST(CharacterEntry, DefaultAFileOrAFileWithItsMapping) {
  EXPECT_EQ(entryOf(R"({})").file, "fallback.glb");  // absent: the fallback
  EXPECT_EQ(entryOf(R"({"horse": "default"})").file, "default");
  EXPECT_EQ(entryOf(R"({"horse": "default"})").mapping, "");
  EXPECT_EQ(entryOf(R"({"horse": "characters/horse.glb"})").file, (kScenes / "characters/horse.glb").string());
  const CharacterEntry both = entryOf(R"({"horse": {"file": "characters/horse.glb", "mapping": "characters/horse-mapping.json"}})");
  EXPECT_EQ(both.file, (kScenes / "characters/horse.glb").string());
  EXPECT_EQ(both.mapping, (kScenes / "characters/horse-mapping.json").string());
}

TEST(CharacterEntry, AMissingFileOrAWrongTypeIsOneLineNamingTheField) {
  const auto error = [](const std::string& json) { return stirrup::test::errorOf([&] { entryOf(json); }); };
  EXPECT_EQ(error(R"({"horse": "nope.glb"})"), "s.json: characters.horse: no such file: " + (kScenes / "nope.glb").string());
  EXPECT_EQ(error(R"({"horse": {"file": "characters/horse.glb", "mapping": "nope.json"}})"),
            "s.json: characters.horse.mapping: no such file: " + (kScenes / "nope.json").string());
  EXPECT_EQ(error(R"({"horse": {"mapping": "characters/horse-mapping.json"}})"),
            "s.json: characters.horse.file: expected a glTF file (.glb or .gltf)");
  EXPECT_EQ(error(R"({"horse": 3})"), "s.json: characters.horse: expected \"default\", a glTF file or {\"file\": ..., \"mapping\": ...}, got 3");
  EXPECT_EQ(error(R"({"horse": {"file": "default", "colour": 1}})"), "s.json: characters.horse.colour: unknown field");
}

}  // namespace
}  // namespace stirrup::scene
