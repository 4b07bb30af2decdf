// Bad scene files through the program: a one-line error naming the file and the field, a non-zero
// exit, and no frames written.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"
#include "tests/scene_folder.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

class SceneErrors : public SceneFolderTest {
 protected:
  SceneErrors() : SceneFolderTest("test_scene_errors") {}
  void expectError(const std::string& args, const std::string& message) {
    const CommandResult r = runStirrup(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.err, "stirrup: " + message + "\n");
    EXPECT_FALSE(fs::exists(dir / "out")) << "output written despite the error";
  }
};

TEST_F(SceneErrors, WrongType) {
  const fs::path f = write("x.json", R"({"output": "out", "cameras": [{}, {"fov": "wide"}]})");
  expectError("render " + quote(f.string()), f.string() + ": cameras[1].fov: expected a number, got \"wide\"");
}

TEST_F(SceneErrors, UnknownField) {
  const fs::path f = write("x.json", R"({"output": "out", "resolutoin": [64, 36]})");
  expectError("bake " + quote(f.string()) + " --channels " + quote((dir / "out/c.csv").string()),
              f.string() + ": resolutoin: unknown field");
}

TEST_F(SceneErrors, MissingSceneFile) {
  const std::string f = (dir / "absent.json").string();
  expectError("render " + quote(f), f + ": cannot open the file (expected a readable JSON file)");
}

TEST_F(SceneErrors, MissingProfileFileNamesIt) {
  const fs::path f = write("x.json", R"({"output": "out", "profile": "nosuch"})");
  const CommandResult r = runStirrup("render " + quote(f.string()));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("nosuch"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(SceneErrors, InvalidJson) {
  const fs::path f = write("x.json", "{\"fps\": 24,,}");
  const CommandResult r = runStirrup("render " + quote(f.string()));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("stirrup: " + f.string() + ": not valid JSON", 0), 0u) << r.err;
}

TEST_F(SceneErrors, BadFrameRangeOnTheCommandLine) {
  expectError("bake " + quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes/trot.json").string()) +
                  " --frames 5-1 --channels " + quote((dir / "out/c.csv").string()),
              "--frames: \"5-1\": expected FIRST <= LAST");
}

// The issue's example: this failed with std::bad_alloc. Frame numbers have a documented maximum
// (scene/frame_range.h, docs/install.md "Input limits").
TEST_F(SceneErrors, AFrameRangePastTheMaximumIsOneLineNotBadAlloc) {
  const std::string trot = quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes/trot.json").string());
  expectError("bake " + trot + " --frames 1-100000000 -o " + quote((dir / "out/t.glb").string()),
              "--frames: \"1-100000000\": expected frame numbers from -999999 to 999999, got 100000000");
  expectError("render " + trot + " --frames 1-200000 --out " + quote((dir / "out").string()),
              "--frames: \"1-200000\": expected at most 100000 frames in the list");
  const fs::path f = write("x.json", R"({"output": "out", "frames": "1-100000000"})");
  expectError("render " + quote(f.string()),
              f.string() + ": frames: \"1-100000000\": expected frame numbers from -999999 to 999999, got 100000000");
}

// Notepad's "UTF-8 with BOM": the scene (and the profile it names) read as without.
TEST_F(SceneErrors, AByteOrderMarkIsNotAnError) {
  std::ifstream in(thesisProfile(), std::ios::binary);
  const std::string profile{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  write("profiles/bom.json", "\xEF\xBB\xBF" + profile);
  const fs::path f = write("x.json", "\xEF\xBB\xBF" R"({"clip": {"generator": "trot"}, "profile": "bom", "frames": "1-3", "output": "out"})");
  const CommandResult r = runStirrup("bake " + quote(f.string()) + " --channels " + quote((dir / "c.csv").string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "c.csv"));
}

// Paths and terrain (issue 15): a path with fewer than two points, a repeated point (a zero-length
// segment), a speed <= 0, a heightfield parameter out of range or of the wrong type.
TEST_F(SceneErrors, BadPathsAndTerrainsAreOneLine) {
  const auto scene = [this](const std::string& clip, const std::string& terrain = "") {
    return write("x.json", R"({"output": "out", "clip": {"generator": "path", )" + clip + "}" +
                               (terrain.empty() ? "" : R"(, "terrain": )" + terrain) + "}");
  };
  fs::path f = scene(R"("points": [[0, 0]], "speed": [[0, 300]])");
  expectError("render " + quote(f.string()), f.string() + ": clip: points: expected at least two points [x, z] (cm), got 1");
  f = scene(R"("points": [[0, 0], [500, 0], [500, 0], [900, 0]], "speed": [[0, 300]])");
  expectError("render " + quote(f.string()), f.string() +
              ": clip: points[2]: expected a point at least 1 cm from points[1] (a zero-length segment has no heading), got one 0 cm away");
  f = scene(R"("points": [[0, 0], [500, 0]], "speed": [[0, 0]])");
  expectError("render " + quote(f.string()), f.string() + ": clip: speed[0]: expected a speed from 1 to 5000 cm/s, got 0");
  f = scene(R"("points": [[0, 0], [500, 0]], "speed": [[0, -3]])");
  expectError("bake " + quote(f.string()) + " --channels " + quote((dir / "out/c.csv").string()),
              f.string() + ": clip: speed[0]: expected a speed from 1 to 5000 cm/s, got -3");
  f = scene(R"("points": [[0, 0], [500, "a"]], "speed": [[0, 300]])");
  expectError("render " + quote(f.string()), f.string() + ": clip.points[1]: expected a point [x, z] (cm), got an array of 2");
  const std::string path = R"("points": [[0, 0], [900, 0]], "speed": [[0, 300]])";
  f = scene(path, R"({"hills": {"amplitude_cm": -4}})");
  expectError("render " + quote(f.string()), f.string() + ": terrain.hills.amplitude_cm: expected a height from 0 to 5000 cm, got -4");
  f = scene(path, R"({"hills": {"wavelength_cm": 10}})");
  expectError("render " + quote(f.string()), f.string() + ": terrain.hills.wavelength_cm: expected a length from 100 to 1000000 cm, got 10");
  f = scene(path, R"({"file": "ground.glb"})");
  expectError("render " + quote(f.string()),
              f.string() + ": terrain.file: " + (dir / "ground.glb").string() + ": no such file (expected a glTF terrain mesh)");
  write("ground.glb", "not a glb");
  f = scene(path, R"({"file": "ground.glb", "hills": {}})");
  expectError("render " + quote(f.string()), f.string() + ": terrain.file: expected either \"file\" or \"hills\", not both");
  f = scene(path, R"({"hills": {"octaves": "many"}})");
  expectError("render " + quote(f.string()), f.string() + ": terrain.hills.octaves: expected a whole number, got \"many\"");
}

}  // namespace
}  // namespace stirrup::test

namespace stirrup::test {
namespace {

// A mapping that names a joint its file lacks is found when the shot loads its characters, after the
// output folder is known: the error is one line naming the mapping, the role and the joint, and the
// render leaves no empty output folder behind (the folder, and the missing parent made for it, are
// taken back).
TEST_F(SceneErrors, ABadMappingIsOneLineAndLeavesNoEmptyOutputFolder) {
  const fs::path rider = dir / "rider.glb", mapping = dir / "rider-map.json";
  ASSERT_EQ(runStirrup("character make humanoid --names mixamo -o " + quote(rider.string())).exit_code, 0);
  ASSERT_EQ(runStirrup("character map " + quote(rider.string()) + " --as rider -o " + quote(mapping.string())).exit_code, 0);
  std::string text = readText(mapping);
  const std::string joint = "\"mixamorig:LeftForeArm\"";
  ASSERT_NE(text.find(joint), std::string::npos) << text;
  text.replace(text.find(joint), joint.size(), "\"mixamorig:LeftElbowX\"");
  write("rider-map.json", text);
  const fs::path scene = write("mapped.json", R"({"name": "mapped", "clip": {"generator": "trot"}, "characters": {"horse": )" +
                                                  std::string("\"") + STIRRUP_SOURCE_DIR + R"(/scenes/characters/horse.glb", )" +
                                                  R"("rider": {"file": "rider.glb", "mapping": "rider-map.json"}}, "frames": "1-2", )" +
                                                  R"("resolution": [64, 36], "output": "out/shots"})");
  expectError("render " + quote(scene.string()),
              mapping.string() + ": roles.lElbow: no joint named \"mixamorig:LeftElbowX\" in " + rider.string() +
                  " (change it to one of the file's joints: stirrup character map " + rider.string() +
                  " --as rider lists them with the roles they seem to play)");
}

// Limits a horse has (docs/horse-limits.md): a path no horse can ride is refused when the scene loads,
// by every command that loads it; --allow-impossible renders it with one warning a frame.
TEST_F(SceneErrors, APathBeyondAHorsesLimitsIsRefused) {
  const fs::path f = write("fast.json", R"({"output": "out", "frames": "1-2", "resolution": [32, 18],
      "clip": {"generator": "path", "points": [[0, 0], [5000, 0]], "speed": [[0, 2500]]}})");
  const std::string message = f.string() + ": clip.speed: segment 0 from 0.00 s: a speed of 2500 cm/s, beyond the 1966 cm/s "
                              "no horse has been timed above (the record, 70.76 km/h) (allow_impossible or "
                              "--allow-impossible renders it anyway)";
  expectError("render " + quote(f.string()), message);
  expectError("bake " + quote(f.string()) + " --channels " + quote((dir / "out/c.csv").string()), message);
}

TEST_F(SceneErrors, AllowImpossibleRendersWithAWarningEachFrame) {
  const fs::path f = write("fast.json", R"({"output": "out", "frames": "1-2", "resolution": [32, 18], "quality": "draft",
      "clip": {"generator": "path", "points": [[0, 0], [5000, 0]], "speed": [[0, 2500]]}})");
  const CommandResult r = runStirrup("render " + quote(f.string()) + " --allow-impossible --out " + quote((dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string limit = ": beyond a horse's limits (allowed): speed: a speed of 2500 cm/s, beyond the 1966 cm/s no horse "
                            "has been timed above (the record, 70.76 km/h)\n";
  EXPECT_EQ(r.err, "warning: " + f.string() + ": frame 1 (0.000 s)" + limit + "warning: " + f.string() + ": frame 2 (0.042 s)" + limit);
  EXPECT_TRUE(fs::exists(dir / "out/fast_side.0001.png"));
  EXPECT_TRUE(fs::exists(dir / "out/fast_side.0002.png"));
  // bake warns once a frame too, whatever it writes.
  const CommandResult b = runStirrup("bake " + quote(f.string()) + " --allow-impossible --channels " + quote((dir / "out/c.csv").string()));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(lineCount(b.err), 2u) << b.err;
}

// A gait no horse could ride at its speed (issue 49): a walk at 900 cm/s is refused with the limit
// named by every command that loads a scene; with --allow-impossible each of them reads it (render
// and rig balance warning once a frame), and `check` loads it on purpose and reports it as a failure.
TEST_F(SceneErrors, AGaitNoHorseRidesIsRefusedByEveryCommandThatLoadsItUnlessAllowed) {
  const fs::path f = write("walk900.json", R"({"output": "out", "frames": "1-2", "resolution": [32, 18], "quality": "draft",
      "clip": {"generator": "walk", "speed_cm_s": 900}})");
  const std::string scene = quote(f.string());
  const std::string limit = "900 cm/s is faster than a horse walks (at most 250 cm/s: horses change to the trot at 160-230 cm/s, "
                            "Froude 0.35, Griffin et al. 2004; a walk held past that, an estimate";
  const std::string message = f.string() + ": clip.speed_cm_s: " + limit + "; allow_impossible or --allow-impossible renders it anyway)";
  // A to composite over the scene's reference, rendered from a scene inside the limits.
  const fs::path a = write("a.json", R"({"frames": "1", "resolution": [32, 18], "quality": "draft", "clip": {"generator": "walk"}})");
  ASSERT_EQ(runStirrup("render " + quote(a.string()) + " --out " + quote((dir / "a").string())).exit_code, 0);
  const std::string layer = "layer " + quote((dir / "a/a_side.0001.png").string()) + " --scene " + scene + " -o " +
                            quote((dir / "l.png").string());
  const std::string csv = quote((dir / "out/c.csv").string());
  const std::vector<std::string> commands = {"render " + scene, "bake " + scene + " --channels " + csv, "clip info " + scene,
                                             "rig balance " + scene, layer, "bench --scene " + scene + " --frames 1 --preset draft"};
  for (const std::string& c : commands) expectError(c, message);

  const std::string warning = ": beyond a horse's limits (allowed): gait speed: clip.speed_cm_s: " + limit + ")\n";
  const CommandResult r = runStirrup("render " + scene + " --allow-impossible --out " + quote((dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "warning: " + f.string() + ": frame 1 (0.000 s)" + warning + "warning: " + f.string() + ": frame 2 (0.042 s)" + warning);
  EXPECT_TRUE(fs::exists(dir / "out/walk900_side.0002.png"));
  const CommandResult balance = runStirrup("rig balance " + scene + " --allow-impossible");
  ASSERT_EQ(balance.exit_code, 0) << balance.err;
  EXPECT_EQ(lineCount(balance.out), 3u) << balance.out;  // the header and two frames
  EXPECT_EQ(lineCount(balance.err), 2u) << balance.err;
  for (const std::string& c : {"bake " + scene + " --channels " + csv, "clip info " + scene})
    EXPECT_EQ(runStirrup(c + " --allow-impossible").exit_code, 0) << c;
  // layer reads the scene, then finds it has no reference block to composite.
  const CommandResult l = runStirrup(layer + " --allow-impossible");
  EXPECT_EQ(l.err, "stirrup: " + f.string() +
                       ": reference: expected a \"reference\" block naming the footage (see docs/layered.md)\n");
  const CommandResult check = runStirrup("check " + scene);
  EXPECT_EQ(check.exit_code, 2) << check.out << check.err;
  EXPECT_NE(check.out.find(f.string() + ": the clip: failure: limit: gait speed (clip.speed_cm_s): " + limit + ")\n"), std::string::npos)
      << check.out;
}

}  // namespace
}  // namespace stirrup::test
