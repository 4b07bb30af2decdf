// Character mapping files (rig/io/character_mapping.cpp): the roles each kind needs and may name, reading
// a file with one-line errors naming the file and the field, the order roles must keep on the skeleton,
// and the file's space to stirrup's, worked out by hand.
#include "rig/io/character_mapping.h"

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

// The header's lists: the horse's root, neck1, head and 4 legs x (Upper, Middle, Fetlock, Hoof) = 19;
// the rider's pelvis, neck, head and 2 sides x (Shoulder, Elbow, Wrist, Hip, Knee, Ankle) = 15.
TEST(CharacterMapping, TheRolesEachKindNeeds) {
  EXPECT_EQ(requiredRoles(CharacterKind::Horse).size(), 19u);
  EXPECT_EQ(requiredRoles(CharacterKind::Horse).front(), "root");
  EXPECT_EQ(requiredRoles(CharacterKind::Rider).size(), 15u);
  EXPECT_EQ(requiredRoles(CharacterKind::Rider)[3], "lShoulder");
  const std::vector<std::string>& horse = optionalRoles(CharacterKind::Horse);
  EXPECT_NE(std::find(horse.begin(), horse.end(), "lRein"), horse.end());
  const std::vector<std::string>& rider = optionalRoles(CharacterKind::Rider);
  EXPECT_NE(std::find(rider.begin(), rider.end(), "spine10"), rider.end());
  EXPECT_NE(std::find(rider.begin(), rider.end(), "rBall"), rider.end());
  EXPECT_EQ(characterKindName(CharacterKind::Horse), "horse");
}

TEST(CharacterMapping, AFileGivesRolesUnitsAndAxes) {
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

TEST(CharacterMapping, MissingRoleNamesTheRoleAndTheMappingFile) {
  const fs::path dir = tempDir("missing_role");
  nlohmann::json j = nlohmann::json::parse(std::ifstream(kCharacters / "horse-mapping.json"));
  j["roles"].erase("neck1");
  const fs::path m = writeJson(dir / "mapping.json", j);
  const std::string e = errorOf([&] { loadCharacterMapping(m, CharacterKind::Horse); });
  EXPECT_EQ(e, m.string() + ": roles.neck1: missing: expected the name of the horse's neck1 joint") << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(CharacterMapping, BadFieldsAreOneLineErrorsNamingTheField) {
  const fs::path dir = tempDir("bad");
  const auto error = [&](CharacterKind kind, const nlohmann::json& j) {
    const fs::path f = writeJson(dir / "m.json", j);
    return errorOf([&] { loadCharacterMapping(f, kind); });
  };
  const std::string f = (dir / "m.json").string();
  EXPECT_EQ(error(CharacterKind::Horse, mappingOf(CharacterKind::Rider)),
            f + ": character: expected \"horse\" (this file is used for the horse), got \"rider\"");
  EXPECT_EQ(error(CharacterKind::Rider, mappingOf(CharacterKind::Rider, {{"scale_cm", 0}})),
            f + ": scale_cm: expected centimetres per file unit > 0");
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

// A rider: pelvis 0 -> spine 1 -> neck 2 -> head 3; shoulder 4 on the spine, elbow 5, wrist 6.
TEST(CharacterMapping, RolesKeepTheirOrderOnTheSkeleton) {
  const std::vector<int> parent = {-1, 0, 1, 2, 1, 4, 5};
  const std::vector<std::string> names = {"Hips", "Spine", "Neck", "Head", "LeftArm", "LeftForeArm", "LeftHand"};
  std::map<std::string, int> roles = {{"pelvis", 0}, {"neck", 2}, {"head", 3}, {"lShoulder", 4}, {"lElbow", 5}, {"lWrist", 6}};
  EXPECT_EQ(roleChainProblem(CharacterKind::Rider, roles, parent, names), "");
  roles["lElbow"] = 6, roles["lWrist"] = 5;  // swapped: the elbow is still below the shoulder, the wrist is not below it
  EXPECT_EQ(roleChainProblem(CharacterKind::Rider, roles, parent, names),
            "roles.lWrist: joint \"LeftForeArm\" is not below lElbow \"LeftHand\" (expected the wrist on the arm's chain "
            "below the elbow)");
  roles = {{"pelvis", 0}, {"neck", 1}};  // no spine joint between
  EXPECT_EQ(roleChainProblem(CharacterKind::Rider, roles, parent, names, "see docs/characters.md"),
            "roles.neck: joint \"Spine\" is not above pelvis \"Hips\" with a spine joint between them (expected the neck "
            "on the chain that runs up from the pelvis; see docs/characters.md)");
  // A horse's tail must not hold the body.
  EXPECT_EQ(roleChainProblem(CharacterKind::Horse, {{"tail1", 0}, {"root", 1}}, {-1, 0}, {"Tail", "Hips"}),
            "roles.tail1: joint \"Tail\" holds root \"Hips\" (expected the tail's first joint, on a chain of its own "
            "behind the hips)");
}

// The file's axes are the rows: x_rig = fw . p, y_rig = up . p, z_rig = (fw x up) . p, times 100 cm a
// unit, then the offset. Here forward is the file's +Z, up its +Y, and the offset 90 cm down.
TEST(CharacterMapping, TheFilesSpaceToStirrups) {
  CharacterMapping m;
  m.scale_cm = 100.0;
  m.forward = {0, 0, 1};
  m.offset_cm = {0, -90, 0};
  const glm::dmat4 to_rig = mappingToRig(m);
  const auto apply = [&](glm::dvec3 p) { return glm::dvec3(to_rig * glm::dvec4(p, 1.0)); };
  // The file's forward (0, 0, 1), 1 m: stirrup's +X, 100 cm; its up 1 m: 100 cm up less the offset's 90.
  const glm::dvec3 ahead = apply({0, 0, 1}), above = apply({0, 1, 0}), side = apply({1, 0, 0});
  EXPECT_NEAR(ahead.x, 100.0, 1e-12);
  EXPECT_NEAR(ahead.y, -90.0, 1e-12);
  EXPECT_NEAR(above.y, 10.0, 1e-12);
  // fw x up = (0, 0, 1) x (0, 1, 0) = (-1, 0, 0): the file's +X is stirrup's -Z (its left).
  EXPECT_NEAR(side.z, -100.0, 1e-12);
  EXPECT_NEAR(side.x, 0.0, 1e-12);
  EXPECT_EQ(mappingToRig(CharacterMapping{}), glm::dmat4(1.0));  // the defaults change nothing
}

}  // namespace
}  // namespace stirrup::rig
