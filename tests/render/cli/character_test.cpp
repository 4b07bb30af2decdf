// stirrup character make: the shipped characters are exactly what the generator makes (a stale
// scenes/characters/*.glb fails here; scripts/make-characters regenerates them), and bad parameters
// are one-line errors.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>

#include "tests/render/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

std::vector<char> readBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "test_character" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void expectGeneratorMatchesShipped(const std::string& kind) {
  const fs::path out = tempDir(kind) / (kind + ".glb");
  const CommandResult r = runStirrup("character make " + kind + " -o " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path shipped = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "characters" / (kind + ".glb");
  const std::vector<char> made = readBytes(out), checked_in = readBytes(shipped);
  EXPECT_GT(made.size(), 100000u);
  EXPECT_LT(made.size(), 4u << 20);  // a few MB at most
  EXPECT_TRUE(made == checked_in) << shipped << " is stale (" << checked_in.size() << " bytes, the generator makes "
                                  << made.size() << "): run scripts/make-characters";
  // No temporary file is left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(out.parent_path()), fs::directory_iterator()), 1);
}

TEST(CharacterMake, ShippedHorseIsTheGeneratorsOutput) { expectGeneratorMatchesShipped("horse"); }
TEST(CharacterMake, ShippedRiderIsTheGeneratorsOutput) { expectGeneratorMatchesShipped("rider"); }

TEST(CharacterMake, ParametersChangeTheCharacter) {
  const fs::path dir = tempDir("params");
  const CommandResult a = runStirrup("character make rider --cell 3 -o " + quote((dir / "a.glb").string()));
  const CommandResult b = runStirrup("character make rider --cell 3 --braid-length 50 -o " + quote((dir / "b.glb").string()));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_FALSE(readBytes(dir / "a.glb") == readBytes(dir / "b.glb"));
}

TEST(CharacterMake, BadInputIsAOneLineError) {
  const fs::path out = tempDir("bad") / "x.glb";
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"character make horse --tail-lenght 90", "character make horse: --tail_lenght: unknown parameter"},
           {"character make horse --tail-length long", "character make horse: --tail_length: expected a number, got \"long\""},
           {"character make horse --hips 1,2", "character make horse: --hips: expected three numbers x,y,z"},
           {"character make dragon", "character make: expected horse, rider or humanoid, got \"dragon\""}}) {
    const CommandResult r = runStirrup(args + " -o " + quote(out.string()));
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err.rfind("stirrup: " + expected, 0), 0u) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(CharacterMake, SceneNamingAMissingCharacterFileFails) {
  const fs::path dir = tempDir("scene");
  std::ofstream(dir / "s.json") << R"({"characters": {"horse": "nope.glb"}, "frames": "1"})";
  const CommandResult r = runStirrup("bake " + quote((dir / "s.json").string()) + " --channels " + quote((dir / "c.csv").string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("characters.horse: no such file"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace stirrup::test
