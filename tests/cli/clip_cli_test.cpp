// stirrup clip make / clip info, end to end.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

fs::path outDir() {
  const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "test-out" / "clip_cli";
  fs::create_directories(d);
  return d;
}

TEST(ClipCli, MakeWritesAGlbThatInfoReadsBack) {
  const fs::path glb = outDir() / "jump.glb";
  fs::remove(glb);
  const CommandResult make = runStirrup("clip make jump --fence_height_cm 110 --seed 7 --fps 24 -o " + quote(glb.string()));
  ASSERT_EQ(make.exit_code, 0) << make.err;
  ASSERT_TRUE(fs::exists(glb));
  const CommandResult info = runStirrup("clip info " + quote(glb.string()) + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["name"], "jump");
  EXPECT_GT(j["hooves"]["lfHoof"]["peak_height_cm"].get<double>(), 110.0);
  EXPECT_TRUE(j["problems"].empty()) << j["problems"];
}

// A horse's own animation measured as it moves: a trot baked by stirrup is a horse whose file keys its
// joints (no control nodes), read through its roles as a scene's clip reads it; its stride, speed, bounce
// and pitch are the trot's (the posed horse's touchdowns, which land a little after the generator's
// targets, are its own and not judged here).
TEST(ClipCli, InfoOnAHorsesOwnAnimationMeasuresItsJoints) {
  const fs::path baked = outDir() / "own-trot.glb";
  ASSERT_EQ(runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json") + " -o " + quote(baked.string())).exit_code, 0);
  const CommandResult r = runStirrup("clip info " + quote(baked.string()) + " --reference trot");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* line : {"stride frequency (Hz)        1.260   reference 1.24–1.28  ok", "speed (cm/s)                 360.0   reference 350–370  ok",
                           "suspensions per stride       2.00   reference 2  ok", "rear pivot cycles/stride     2.00   reference 2  ok"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
}

TEST(ClipCli, InfoOnAGeneratorShowsTheReference) {
  const CommandResult r = runStirrup("clip info gallop");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("reference: gallop"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("suspensions per stride       1.00   reference 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("footfall order: lbHoof rbHoof lfHoof rfHoof"), std::string::npos) << r.out;
  const CommandResult j = runStirrup("clip info trot --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_EQ(nlohmann::json::parse(j.out)["reference"]["gait"], "trot");
}

// Verdicts: ok / OUTSIDE in the table, booleans in --json; the gallop says which reference its fore
// pair is judged by; the stop's slide is labelled as the stop's, not as a problem.
TEST(ClipCli, InfoPrintsVerdicts) {
  const CommandResult gallop = runStirrup("clip info gallop");
  ASSERT_EQ(gallop.exit_code, 0) << gallop.err;
  EXPECT_NE(gallop.out.find("lfHoof       0.360"), std::string::npos) << gallop.out;
  EXPECT_NE(gallop.out.find("0.39* ok"), std::string::npos) << gallop.out;
  EXPECT_NE(gallop.out.find("Against the table's phases they are 0.14/0.14 away: OUTSIDE"), std::string::npos) << gallop.out;
  EXPECT_NE(gallop.out.find("rear pivot cycles/stride     1.00   reference 1  ok"), std::string::npos) << gallop.out;
  EXPECT_NE(gallop.out.find("verdict: all 14 numbers inside the reference"), std::string::npos) << gallop.out;

  const CommandResult rear = runStirrup("clip info rear --json");
  ASSERT_EQ(rear.exit_code, 0) << rear.err;
  const nlohmann::json ok = nlohmann::json::parse(rear.out);
  EXPECT_TRUE(ok["verdicts"]["rear.peak_pitch_deg"].get<bool>());
  EXPECT_TRUE(ok["verdicts"]["rear.held_s"].get<bool>());
  EXPECT_TRUE(ok["all_ok"].get<bool>());
  const CommandResult steep = runStirrup("clip info rear --angle_deg 75 --json");
  ASSERT_EQ(steep.exit_code, 0) << steep.err;
  const nlohmann::json bad = nlohmann::json::parse(steep.out);
  EXPECT_FALSE(bad["verdicts"]["rear.peak_pitch_deg"].get<bool>());
  EXPECT_FALSE(bad["all_ok"].get<bool>());

  const CommandResult stop = runStirrup("clip info stop");
  ASSERT_EQ(stop.exit_code, 0) << stop.err;
  EXPECT_NE(stop.out.find("stop: slide (cm)             720.0   reference 0–1000  ok"), std::string::npos) << stop.out;
  EXPECT_NE(stop.out.find("slide (the sliding stop's, expected): lbHoof slides"), std::string::npos) << stop.out;
  EXPECT_EQ(stop.out.find("problem:"), std::string::npos) << stop.out;
  const CommandResult jump = runStirrup("clip info jump");
  ASSERT_EQ(jump.exit_code, 0) << jump.err;
  EXPECT_NE(jump.out.find("jump: take-off pitch (deg)"), std::string::npos) << jump.out;
  EXPECT_NE(jump.out.find("reference 18.9–23.9  ok"), std::string::npos) << jump.out;
}

// A path scene measured section by section: each steady stretch against its gait's reference (a left
// lead mirrored), and the whole path on the ground for slides.
TEST(ClipCli, InfoOnAPathSceneMeasuresEachSection) {
  const fs::path scene = outDir() / "path.json";
  {
    std::ofstream(scene) << R"({"output": "out", "clip": {"generator": "path",
      "points": [[0, 0], [2500, 0], [4500, 1500], [4500, 4000], [3000, 5500], [0, 5500]],
      "speed": [[0, 180], [5, 180], [7, 360], [13, 360], [15, 560], [60, 560]]},
      "terrain": {"hills": {"seed": 2, "amplitude_cm": 60, "wavelength_cm": 3000}}})";
  }
  const CommandResult r = runStirrup("clip info " + quote(scene.string()) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  std::vector<std::string> gaits;
  for (const auto& s : j["sections"]) {
    gaits.push_back(s["gait"]);
    ASSERT_FALSE(s["info"].is_null()) << s;
    EXPECT_TRUE(s["info"]["all_ok"].get<bool>()) << s["gait"] << ": " << s["info"]["verdict_details"];
    EXPECT_GT(s["info"]["verdict_details"].size(), 8u);
  }
  EXPECT_EQ(gaits, (std::vector<std::string>{"walk", "trot", "canter"}));
  EXPECT_EQ(j["sections"][2]["lead"], "right") << "the path turns right after the canter begins";
  EXPECT_TRUE(j["path"]["problems"].empty()) << j["path"]["problems"];
  const CommandResult text = runStirrup("clip info " + quote(scene.string()));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("section 2: trot"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("whole path, on the ground:"), std::string::npos) << text.out;
}

// clip info on a crowd measures each pair's own path in turn (--pair N: that pair alone): every
// pair's sections at the trot it rides; --pair out of range, or on a scene of one pair, is one line.
TEST(ClipCli, InfoOnACrowdMeasuresEachPair) {
  const fs::path scene = outDir() / "crowd.json";
  std::ofstream(scene) << R"({"output": "out", "riders": [
    {"points": [[0, -300], [3000, -300]], "speed": [[0, 300]], "seed": 1},
    {"points": [[0, 300], [3000, 300]], "speed": [[0, 300]], "seed": 2, "start_offset_s": 0.5},
    {"points": [[-1200, 0], [1800, 0]], "speed": [[0, 300]], "seed": 3}]})";
  CommandResult r = runStirrup("clip info " + quote(scene.string()) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["pairs"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const nlohmann::json& p = j["pairs"][std::size_t(i)];
    EXPECT_EQ(p["pair"], i);
    EXPECT_EQ(p["name"], "pair0" + std::to_string(i));
    ASSERT_FALSE(p["sections"].empty()) << p;
    for (const auto& s : p["sections"]) EXPECT_EQ(s["gait"], "trot") << "pair " << i;
  }
  EXPECT_EQ(j["pairs"][1]["start_offset_s"], 0.5);
  r = runStirrup("clip info " + quote(scene.string()) + " --pair 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["pairs"].size(), 1u);
  EXPECT_EQ(j["pairs"][0]["pair"], 2);
  r = runStirrup("clip info " + quote(scene.string()) + " --pair 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(scene.string() + " pair01: path"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("pair00"), std::string::npos) << r.out;
  r = runStirrup("clip info " + quote(scene.string()) + " --pair 3");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "stirrup: clip info: --pair: expected a pair index from 0 to 2, got 3\n");
  const std::string trot = std::string(STIRRUP_SOURCE_DIR) + "/scenes/trot.json";
  r = runStirrup("clip info " + quote(trot) + " --pair 0");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "stirrup: clip info: --pair: expected a crowd scene (\"crowd\" or \"riders\"), got one horse and rider in " +
                       trot + "\n");
}

TEST(ClipCli, BadInputIsOneLine) {
  const CommandResult unknown = runStirrup("clip make jump --fence 3 -o " + quote((outDir() / "x.glb").string()));
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_EQ(unknown.err, "stirrup: clip make: fence: unknown field\n");
  const CommandResult gen = runStirrup("clip info pace");
  EXPECT_EQ(gen.exit_code, 1);
  EXPECT_EQ(lineCount(gen.err), 1u) << gen.err;
  EXPECT_NE(gen.err.find("generator"), std::string::npos) << gen.err;
  const CommandResult missing = runStirrup("clip info nowhere.glb");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(lineCount(missing.err), 1u) << missing.err;
}

TEST(ClipCli, FoxThroughTheMapping) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets/fox/Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << fox << " is not there";
  const fs::path mapping = fs::path(STIRRUP_SOURCE_DIR) / "scenes/fox/fox-mapping.json";
  for (const char* animation : {"Walk", "Run"}) {
    const CommandResult r = runStirrup("clip info " + quote(fox.string()) + " --mapping " + quote(mapping.string()) +
                                       " --animation " + animation + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["name"], animation);
    EXPECT_GE(j["strides"].get<int>(), 2);
    for (const char* h : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"})
      EXPECT_GT(j["hooves"][h]["peak_height_cm"].get<double>(), 20.0) << animation << " " << h;
  }
}

TEST(ClipCli, EveryMovementSceneBakes) {
  for (const char* scene : {"walk", "trot", "canter", "gallop", "stop", "jump", "rear", "buck"}) {
    const fs::path csv = outDir() / (std::string(scene) + ".csv");
    const CommandResult r = runStirrup("bake " + quote(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + scene + ".json") +
                                       " --channels " + quote(csv.string()));
    EXPECT_EQ(r.exit_code, 0) << scene << ": " << r.err;
  }
}

// Every scene file in scenes/ and its folders (a JSON object with a "clip") bakes, named by its path there
// with "_" for "/" (fox_fox for fox/fox.json). A scene whose clip is a third-party file outside the
// repository (the Khronos Fox, scenes/fox/) that is not there is SKIPPED, never passed.
std::vector<std::string> sceneFiles() {
  std::vector<std::string> out;
  const fs::path root = fs::path(STIRRUP_SOURCE_DIR) / "scenes";
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.path().extension() != ".json") continue;
    const nlohmann::json j = nlohmann::json::parse(readText(e.path()), nullptr, false);
    if (j.is_object() && j.contains("clip")) out.push_back(fs::relative(e.path(), root).replace_extension().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The clip file a scene names, resolved against the scene's folder (empty for a generator).
fs::path sceneClipFile(const fs::path& scene) {
  const nlohmann::json j = nlohmann::json::parse(readText(scene));
  if (!j["clip"].contains("file")) return {};
  return fs::weakly_canonical(scene.parent_path() / j["clip"]["file"].get<std::string>());
}

// The character files a scene names as {"file": ...} (a user's horse or rider), resolved likewise.
std::vector<fs::path> sceneCharacterFiles(const fs::path& scene) {
  const nlohmann::json j = nlohmann::json::parse(readText(scene));
  std::vector<fs::path> out;
  if (j.contains("characters") && j["characters"].is_object())
    for (const auto& [kind, entry] : j["characters"].items())
      if (entry.is_object() && entry.contains("file"))
        out.push_back(fs::weakly_canonical(scene.parent_path() / entry["file"].get<std::string>()));
  return out;
}

// Whether a (canonical) path lies in the repository: compared folder by folder, since a string prefix
// takes a sibling such as /ci/shared for a file of a checkout at /ci/s.
bool insideTheSourceTree(const fs::path& file) {
  const fs::path source = fs::weakly_canonical(STIRRUP_SOURCE_DIR);
  const fs::path rel = file.lexically_relative(source);
  return !rel.empty() && *rel.begin() != "..";
}

// Skips (GTEST_SKIP) when the scene's clip or a character it rides is a file outside the repository
// that is not there.
#define SKIP_IF_THIRD_PARTY_CLIP_IS_MISSING(scene)                                                          \
  do {                                                                                                      \
    std::vector<fs::path> files = sceneCharacterFiles(scene);                                               \
    files.push_back(sceneClipFile(scene));                                                                  \
    for (const fs::path& third_party : files)                                                               \
      if (!third_party.empty() && !fs::exists(third_party) && !insideTheSourceTree(third_party))            \
        GTEST_SKIP() << (scene).filename().string() << " needs " << third_party << ", which is not there";  \
  } while (0)

class SceneFile : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFile, Bakes) {
  const fs::path scene = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / (GetParam() + ".json");
  SKIP_IF_THIRD_PARTY_CLIP_IS_MISSING(scene);
  const fs::path csv = outDir() / ("scene_" + scene.stem().string() + ".csv");
  fs::remove(csv);
  const CommandResult r = runStirrup("bake " + quote(scene.string()) + " --channels " + quote(csv.string()));
  ASSERT_EQ(r.exit_code, 0) << GetParam() << ": " << r.err;
  EXPECT_TRUE(fs::exists(csv));
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneFile, ::testing::ValuesIn(sceneFiles()), [](const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace(name.begin(), name.end(), '/', '_');
  return name;
});

TEST(SceneFile, TheFoxScenesAreAmongThem) {
  const std::vector<std::string> scenes = sceneFiles();
  for (const char* s : {"fox/fox", "fox/fox_horse", "fox/fox_run", "walk", "buck"})
    EXPECT_NE(std::find(scenes.begin(), scenes.end(), s), scenes.end()) << s;
  EXPECT_EQ(std::find(scenes.begin(), scenes.end(), "fox/fox-mapping"), scenes.end());
}

// A channel CSV as columns by name.
std::map<std::string, std::vector<double>> readColumns(const fs::path& csv) {
  std::istringstream in(readText(csv));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::istringstream h(line); std::getline(h, line, ',');) names.push_back(line);
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t i = 0; i < names.size() && std::getline(row, cell, ','); ++i) cols[names[i]].push_back(std::stod(cell));
  }
  return cols;
}

// scenes/fox/fox.json (Walk) and fox_run.json (Run): the Khronos Fox through scenes/fox/fox-mapping.json
// drives the horse; baked, every hoof leaves the ground and comes back down, more than once.
TEST(ClipCli, FoxScenesBakeWithHoovesThatRiseAndFall) {
  for (const char* name : {"fox", "fox_run"}) {
    const fs::path scene = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "fox" / (std::string(name) + ".json");
    SKIP_IF_THIRD_PARTY_CLIP_IS_MISSING(scene);
    const fs::path csv = outDir() / (std::string(name) + "_hooves.csv");
    const CommandResult r = runStirrup("bake " + quote(scene.string()) + " --channels " + quote(csv.string()));
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const auto cols = readColumns(csv);
    ASSERT_TRUE(cols.count("frame")) << name;
    EXPECT_GE(cols.at("frame").size(), 48u) << name;
    for (const char* hoof : {"lfHoof.ty", "rfHoof.ty", "lbHoof.ty", "rbHoof.ty"}) {
      ASSERT_TRUE(cols.count(hoof)) << name << " " << hoof;
      const std::vector<double>& y = cols.at(hoof);
      int rises = 0;
      bool low = y.front() < 1.0;
      for (double v : y) {
        if (low && v > 10.0) ++rises, low = false;
        else if (!low && v < 1.0) low = true;
      }
      EXPECT_LE(*std::min_element(y.begin(), y.end()), 0.5) << name << " " << hoof << " never lands";
      EXPECT_GT(*std::max_element(y.begin(), y.end()), 20.0) << name << " " << hoof;
      EXPECT_LT(*std::max_element(y.begin(), y.end()), 200.0) << name << " " << hoof;
      EXPECT_GE(rises, 2) << name << " " << hoof << ": steps up and down more than once";
    }
    // The horse travels forward ("speed_cm_s": "auto") and the rider is driven.
    EXPECT_GT(cols.at("lowerBack.rz").size(), 0u);
  }
}

// The same scene copied where the third-party files are not: one line naming the scene file and field.
TEST(ClipCli, FoxSceneWithoutTheSharedAssetsIsAOneLineError) {
  const fs::path dir = outDir() / "fox_alone" / "scenes" / "fox";
  fs::remove_all(dir.parent_path().parent_path());
  fs::create_directories(dir);
  for (const char* f : {"fox.json", "fox-mapping.json"})
    fs::copy_file(fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "fox" / f, dir / f);
  const CommandResult r = runStirrup("bake " + quote((dir / "fox.json").string()) + " --channels " +
                                     quote((dir / "fox.csv").string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find((dir / "fox.json").string() + ": clip.file: no such file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "fox.csv"));
}

}  // namespace
}  // namespace stirrup::test
