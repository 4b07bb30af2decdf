// A character mapping file read: its roles, units and axes; a missing role or a bad field is a one-line
// error naming the file and the field.
#include "rig/io/character_mapping_json.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/input_error.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

const fs::path kCharacters = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "characters";

fs::path tempDir(const std::string& name) { return stirrup::test::freshTestDir("test_character_mapping", name); }

fs::path writeJson(const fs::path& file, const nlohmann::json& j) {
  std::ofstream(file) << j.dump(2);
  return file;
}

// Every role mapped to a joint of its own name, with `more` on top.
nlohmann::json mappingOf(CharacterKind kind, const nlohmann::json& more = nlohmann::json::object()) {
  nlohmann::json j = {{"character", std::string(characterKindName(kind))}, {"roles", nlohmann::json::object()}};
  for (const std::string& role : requiredRoles(kind)) j["roles"][role] = role;
  j.update(more);
  return j;
}

TEST(CharacterMappingJson, AFileGivesRolesUnitsAndAxes) {
  const fs::path dir = tempDir("read");
  const fs::path f = writeJson(dir / "m.json", mappingOf(CharacterKind::Rider, {{"scale_cm", 100}, {"forward", {0, 0, 1}},
                                                                               {"offset_cm", {0, -90, 0}}}));
  const CharacterMapping m = loadCharacterMapping(f, CharacterKind::Rider);
  EXPECT_EQ(m.roles.at("lKnee"), "lKnee");
  EXPECT_EQ(m.scale_cm, 100.0);
  EXPECT_EQ(m.forward, (std::array<double, 3>{0, 0, 1}));
  EXPECT_EQ(m.up, (std::array<double, 3>{0, 1, 0}));  // not given: +Y
  EXPECT_EQ(m.file, f);
  // The shipped mappings read.
  EXPECT_EQ(loadCharacterMapping(kCharacters / "horse-mapping.json", CharacterKind::Horse).roles.count("neck1"), 1u);
}

TEST(CharacterMappingJson, MissingRoleNamesTheRoleAndTheMappingFile) {
  const fs::path dir = tempDir("missing_role");
  nlohmann::json j = nlohmann::json::parse(std::ifstream(kCharacters / "horse-mapping.json"));
  j["roles"].erase("neck1");
  const fs::path m = writeJson(dir / "mapping.json", j);
  const std::string e = errorOf([&] { loadCharacterMapping(m, CharacterKind::Horse); });
  EXPECT_EQ(e, m.string() + ": roles.neck1: missing: expected the name of the horse's neck1 joint") << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(CharacterMappingJson, BadFieldsAreOneLineErrorsNamingTheField) {
  const fs::path dir = tempDir("bad");
  const auto error = [&](CharacterKind kind, const nlohmann::json& j) {
    const fs::path f = writeJson(dir / "m.json", j);
    return errorOf([&] { loadCharacterMapping(f, kind); });
  };
  const std::string f = (dir / "m.json").string();
  EXPECT_EQ(error(CharacterKind::Horse, mappingOf(CharacterKind::Rider)),
            f + ": character: expected \"horse\" (this file is used for the horse), got \"rider\"");
  EXPECT_EQ(error(CharacterKind::Rider, mappingOf(CharacterKind::Rider, {{"scale_cm", 0}})),
            f + ": scale_cm: expected centimetres per file unit from 0.001 to 100000, got 0");
  EXPECT_EQ(error(CharacterKind::Rider, mappingOf(CharacterKind::Rider, {{"up", {1, 0, 0}}})),
            f + ": up: expected a direction at right angles to forward");
  EXPECT_EQ(error(CharacterKind::Rider, mappingOf(CharacterKind::Rider, {{"forward", {0, 0, 0}}})),
            f + ": forward: expected a non-zero direction");
  nlohmann::json tail = mappingOf(CharacterKind::Rider);
  tail["roles"]["tail1"] = "Tail";
  EXPECT_EQ(error(CharacterKind::Rider, tail), f + ": roles.tail1: unknown rider role (docs/characters.md lists them)");
  nlohmann::json number = mappingOf(CharacterKind::Rider);
  number["roles"]["lKnee"] = 3;
  EXPECT_EQ(error(CharacterKind::Rider, number), f + ": roles.lKnee: expected a joint name, got 3");
  EXPECT_EQ(error(CharacterKind::Rider, mappingOf(CharacterKind::Rider, {{"colour", "red"}})), f + ": colour: unknown field");
}


}  // namespace
}  // namespace stirrup::rig
