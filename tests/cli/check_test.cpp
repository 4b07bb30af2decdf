// stirrup check (cli/cmd_check.cpp) end to end: a fault planted in a scene, a glTF clip or a baked shot
// (stirrup bake -o, and Blender's re-export of one) is found by its rule, every default scene and its
// bake check clean, and the reports (text, JSON, JUnit, HTML) and exit status CI gates on (0 clean,
// 1 warnings, 2 failures, 3 cannot check).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <cstring>
#include <numbers>
#include <filesystem>
#include <iterator>
#include <memory>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <tuple>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/clip.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_clip.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "tests/cli/blender_script.h"
#include "tests/cli/own_horse_bake.h"
#include "tests/cli/run_command.h"
#include "tests/scene_folder.h"
#include "tests/test_files.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

std::string lastLine(const std::string& s) {
  const std::size_t end = s.size() && s.back() == '\n' ? s.size() - 1 : s.size();
  const std::size_t start = s.rfind('\n', end == 0 ? 0 : end - 1);
  return s.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1));
}

class CheckCli : public SceneFolderTest {
 protected:
  CheckCli() : SceneFolderTest("test_check") {}
};

// A path faster than any horse: a failure on every frame, naming the limit, the field and the segment;
// exit 2. (Galloping at 2500 cm/s the hooves also fall short of the clip's far-flung targets.)
TEST_F(CheckCli, AnImpossiblePathFailsEveryFrame) {
  const fs::path f = write("fast.json", R"({"frames": "1-2", "clip": {"generator": "path", "points": [[0, 0], [5000, 0]], "speed": [[0, 2500]]}})");
  const CommandResult r = runStirrup("check " + quote(f.string()));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const std::string limit = ": failure: limit: speed (clip.speed, segment 0): a speed of 2500 cm/s, beyond the 1966 cm/s no horse has "
                            "been timed above (the record, 70.76 km/h)\n";
  EXPECT_NE(r.out.find(f.string() + ": frame 1 (0.000 s)" + limit), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(f.string() + ": frame 2 (0.042 s)" + limit), std::string::npos) << r.out;
  EXPECT_EQ(lastLine(r.out).rfind(f.string() + ": 2 frames, 1 pair: ", 0), 0u) << r.out;

  const CommandResult j = runStirrup("check " + quote(f.string()) + " --json");
  EXPECT_EQ(j.exit_code, 2);
  const nlohmann::json report = nlohmann::json::parse(j.out);
  EXPECT_EQ(report["status"], 2);
  EXPECT_EQ(report["rules"]["limit"]["failures"], 2);
  ASSERT_EQ(report["paths"].size(), 1u);
  ASSERT_EQ(report["paths"][0]["breaches"].size(), 1u);
  EXPECT_EQ(report["paths"][0]["breaches"][0]["limit"], "speed");
  EXPECT_EQ(report["paths"][0]["breaches"][0]["value"], 2500.0);
  int limit_findings = 0;
  for (const auto& e : report["findings"]) limit_findings += e["rule"] == "limit" && e["where"] == "speed" && e["bound"] == 1966.0;
  EXPECT_EQ(limit_findings, 2);
}

// A user's horse clip made elsewhere, as glTF: the default trot (from `clip make`) with one fault planted.
class PlantedFault : public rig::Clip {
 public:
  enum class Fault { None, Skate, Sink, Fast };
  PlantedFault(std::unique_ptr<rig::Clip> clip, Fault fault) : clip_(std::move(clip)), fault_(fault) {}
  std::string name() const override { return clip_->name(); }
  double duration() const override { return clip_->duration(); }
  rig::HorseFrame sample(double t) const override {
    rig::HorseFrame f = clip_->sample(t);
    using C = rig::HorseChannel;
    switch (fault_) {
      case Fault::None: break;
      // The left fore swings 12 cm to and fro once a second, down or not: it skates, at most 75.4 cm/s
      // (2 pi 12), 3.14 cm a frame at 24 fps.
      case Fault::Skate: f.controls[C::lfHoofTx] += 12.0 * std::sin(2.0 * std::numbers::pi * t); break;
      // Every hoof's stance 5 cm below the ground (a clip keyed on a ground 5 cm too low).
      case Fault::Sink:
        for (C ty : {C::lfHoofTy, C::rfHoofTy, C::lbHoofTy, C::rbHoofTy})
          if (f.controls[ty] <= 0.0) f.controls[ty] = -5.0;
        break;
      // The travel eight times as fast (2900 cm/s), hooves carried along: faster than any horse.
      case Fault::Fast: f.travel_cm *= 8.0; break;
    }
    return f;
  }

 private:
  std::unique_ptr<rig::Clip> clip_;
  Fault fault_;
};

fs::path writeClip(const fs::path& file, PlantedFault::Fault fault) {
  rig::GltfWriteOptions w;
  w.fps = 120;  // keyed finely, so the stance edges keep their time (LINEAR keys at 24 fps shorten the stance)
  rig::writeClipGltf(PlantedFault(scene::makeClip(scene::ClipSpec{}), fault), file, w);
  return file;
}

int count(const nlohmann::json& report, const std::string& rule, const std::string& where = "") {
  int n = 0;
  for (const auto& e : report["findings"]) n += e["rule"] == rule && (where.empty() || e["where"] == where) && e["severity"] != "note";
  return n;
}

// The clip as made is clean, and within the trot's reference.
TEST_F(CheckCli, AGltfTrotClipChecksClean) {
  const fs::path clip = writeClip(dir / "trot.glb", PlantedFault::Fault::None);
  const CommandResult r = runStirrup("check " + quote(clip.string()) + " --reference trot --json");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["failures"], 0);
  EXPECT_EQ(report["warnings"], 0);
  EXPECT_TRUE(report["gait"].is_object());
}

TEST_F(CheckCli, ASkatingHoofIsFoundInAGltfClip) {
  const fs::path clip = writeClip(dir / "skate.glb", PlantedFault::Fault::Skate);
  const CommandResult r = runStirrup("check " + quote(clip.string()) + " --json");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_GT(count(report, "hoof-slide", "lf"), 0);
  EXPECT_EQ(count(report, "hoof-slide") - count(report, "hoof-slide", "lf"), 0) << "only the left fore skates";
  double worst = 0;
  for (const auto& e : report["findings"])
    if (e["rule"] == "hoof-slide") worst = std::max(worst, e["value"].get<double>());
  EXPECT_LE(worst, 3.14 + 0.35);  // the swing's fastest, and what a sole moves a frame unforced
  EXPECT_GE(worst, 2.5);          // sampled near its fastest
}

TEST_F(CheckCli, HoovesSunkIntoTheGroundAreFoundInAGltfClip) {
  const fs::path clip = writeClip(dir / "sink.glb", PlantedFault::Fault::Sink);
  const CommandResult r = runStirrup("check " + quote(clip.string()) + " --json");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  for (const char* hoof : {"lf", "rf", "lb", "rb"}) EXPECT_GT(count(report, "hoof-in-ground", hoof), 0) << hoof;
  for (const auto& e : report["findings"]) {
    if (e["rule"] == "hoof-in-ground") {
      EXPECT_LE(e["value"].get<double>(), 5.3) << e.dump();  // 5 cm keyed, the sole's rounding
    }
  }
}

TEST_F(CheckCli, AClipFasterThanAnyHorseBreaksTheSpeedLimit) {
  const fs::path clip = writeClip(dir / "fast.glb", PlantedFault::Fault::Fast);
  const CommandResult r = runStirrup("check " + quote(clip.string()) + " --json");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_GT(count(report, "limit", "speed"), 0);
}

// JUnit XML: well formed (Python's parser reads it), a failing case for the rule broken, passing ones
// for the others; HTML: a page and a thumbnail of a flagged frame, 320 x 180.
TEST_F(CheckCli, JUnitAndHtmlReportsOfAFaultyClip) {
  const fs::path clip = writeClip(dir / "skate.glb", PlantedFault::Fault::Skate);
  const fs::path xml = dir / "check.xml", html = dir / "report";
  const CommandResult r = runStirrup("check " + quote(clip.string()) + " --junit " + quote(xml.string()) + " --html " + quote(html.string()));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  ASSERT_TRUE(fs::exists(xml));
  EXPECT_EQ(std::system(("python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' " + quote(xml.string())).c_str()), 0);
  std::ifstream in(xml);
  const std::string x((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t slide = x.find("<testcase classname=\"skate\" name=\"hoof-slide\">");
  ASSERT_NE(slide, std::string::npos) << x;
  EXPECT_EQ(x.find("<failure type=\"hoof-slide\"", slide), x.find("<failure", slide));
  const std::size_t hand = x.find("<testcase classname=\"skate\" name=\"hand-off-rein\">");
  ASSERT_NE(hand, std::string::npos);
  EXPECT_LT(x.find("</testcase>", hand), x.find("<failure", hand));  // no failure inside it
  EXPECT_NE(x.find("tests=\"9\" failures=\""), std::string::npos);

  std::ifstream page(html / "index.html");
  const std::string h((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(h.find("hoof-slide (lf)"), std::string::npos);
  const std::size_t img = h.find("<img src=\"");
  ASSERT_NE(img, std::string::npos);
  const std::string png = h.substr(img + 10, h.find('"', img + 10) - img - 10);
  std::ifstream p(html / png, std::ios::binary);
  ASSERT_TRUE(p) << png;
  unsigned char head[24] = {};
  p.read(reinterpret_cast<char*>(head), 24);
  EXPECT_EQ(head[1], 'P');
  EXPECT_EQ((head[16] << 24) | (head[17] << 16) | (head[18] << 8) | head[19], 320);  // IHDR width
  EXPECT_EQ((head[20] << 24) | (head[21] << 16) | (head[22] << 8) | head[23], 180);
  EXPECT_NE(h.find("<svg"), std::string::npos);
}

// Every default scene checks clean (exit 0): no limit broken, no hoof sliding, over-reaching or in the
// ground, the rider nowhere in the horse, hands on the reins, feet in the stirrups, trunk in its band.
// Long scenes every 8th frame and the frame after it (so slides are measured), to keep CI short; the
// crowd (ride_out) every 24th. The Fox scenes are left out: the Khronos Fox's in-place cycle skates
// under the mapping (as `clip info` reports), and check says so.
class DefaultSceneChecks : public ::testing::TestWithParam<const char*> {};
TEST_P(DefaultSceneChecks, Clean) {
  const std::string name = GetParam();
  const std::string scene = (fs::path(STIRRUP_SOURCE_DIR) / "scenes" / (name + ".json")).string();
  std::string frames;
  if (name == "cross_country") frames = " --frames 1-687x8,2-687x8";
  if (name == "figure_eight") frames = " --frames 1-530x8,2-530x8";
  if (name == "trail") frames = " --frames 1-609x8,2-609x8";
  if (name == "ride_out") frames = " --frames 1-528x24,2-528x24";
  const CommandResult r = runStirrup("check " + quote(scene) + frames);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(lastLine(r.out).find(": 0 failures, 0 warnings, "), std::string::npos) << lastLine(r.out);
}
INSTANTIATE_TEST_SUITE_P(Scenes, DefaultSceneChecks,
                         ::testing::Values("walk", "trot", "canter", "gallop", "gallop_layered", "stop", "jump", "rear", "buck",
                                           "cross_country", "figure_eight", "trail", "ride_out"),
                         [](const ::testing::TestParamInfo<const char*>& i) { return std::string(i.param); });

// The Khronos Fox's walk (a third-party in-place cycle, read as a horse clip by scenes/fox/fox-mapping.json)
// skates: `clip info` reports each hoof sliding while down, and check finds the same hooves sliding.
TEST_F(CheckCli, TheFoxWalkSkatesWhereClipInfoSaysSo) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets/fox/Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "the Khronos Fox is not in the data folder (" << fox.string() << ")";
  const std::string scene = (fs::path(STIRRUP_SOURCE_DIR) / "scenes/fox/fox.json").string();
  const CommandResult info = runStirrup("clip info " + quote(scene) + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json measured = nlohmann::json::parse(info.out);
  const CommandResult r = runStirrup("check " + quote(scene) + " --json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  int skating = 0;
  for (const char* h : {"lf", "rf", "lb", "rb"}) {
    const double slide_mm = measured["hooves"][std::string(h) + "Hoof"]["max_slide_mm_per_frame"].get<double>();
    if (slide_mm < 30.0) continue;  // 3 cm a frame: check's failure bound
    ++skating;
    EXPECT_GT(count(report, "hoof-slide", h), 0) << h << " slides " << slide_mm << " mm a frame";
  }
  EXPECT_GT(skating, 0);
}

// A baked shot (stirrup bake -o) is measured on its own joints and meshes: `bakeShot` bakes a scene's
// frames into the test's folder.
fs::path bakeShot(const fs::path& dir, const std::string& scene, const std::string& frames) {
  const fs::path glb = dir / (fs::path(scene).stem().string() + ".glb");
  const CommandResult r = runStirrup("bake " + quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes" / scene).string()) + " --frames " + frames +
                                     " -o " + quote(glb.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return glb;
}

int nodeNamed(const tinygltf::Model& m, const std::string& name) {
  for (std::size_t n = 0; n < m.nodes.size(); ++n)
    if (m.nodes[n].name == name) return int(n);
  return -1;
}

// The frames with a finding of `rule` (notes aside), and the largest value found.
std::set<int> framesOf(const nlohmann::json& report, const std::string& rule, double* worst = nullptr, double* least = nullptr) {
  std::set<int> frames;
  for (const auto& e : report["findings"]) {
    if (e["rule"] != rule || e["severity"] == "note") continue;
    frames.insert(e["frame"].get<int>());
    if (worst) *worst = std::max(*worst, e["value"].get<double>());
    if (least) *least = std::min(*least, e["value"].get<double>());
  }
  return frames;
}

const std::vector<std::string> kRiderRules = {"rider-in-horse", "hand-off-rein", "foot-off-stirrup", "trunk-balance"};

// The trot baked and checked: read as a shot of one pair with the bake's 24 frames, its own joints
// measured: clean, as the scene it was baked from is; over-reach and limits said to be unmeasured.
TEST_F(CheckCli, ABakedTrotIsMeasuredAsAShot) {
  const fs::path glb = bakeShot(dir, "trot.json", "1-24");
  const CommandResult r = runStirrup("check " + quote(glb.string()));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            glb.string() + ": a baked shot: 1 pair (horse and rider), 24 frames at 24 fps, animation \"trot\"; ground: flat (the file has "
                           "no ground mesh: a node named \"ground\")");
  EXPECT_NE(r.out.find(glb.string() + ": not measured: over-reach: "), std::string::npos) << r.out;
  EXPECT_EQ(lastLine(r.out), glb.string() + ": 24 frames, 1 pair: 0 failures, 0 warnings, 0 notes");
  const CommandResult scene = runStirrup("check " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json") + " --frames 1-24 --json");
  EXPECT_EQ(scene.exit_code, 0) << scene.err;
  const CommandResult shot = runStirrup("check " + quote(glb.string()) + " --json");
  const nlohmann::json s = nlohmann::json::parse(shot.out), c = nlohmann::json::parse(scene.out);
  EXPECT_EQ(s["read_as"], "shot");
  EXPECT_EQ(c["read_as"], "scene");
  EXPECT_EQ(s["frames"], c["frames"]);
  EXPECT_EQ(s["frames"], 24);

  // Its armatures renamed and its role tables dropped (as another tool might): two skins the automatic
  // mapping finds a horse and a rider in, by the joints' names, the same shot.
  tinygltf::Model m = readGlbModel(glb);
  m.nodes[std::size_t(nodeNamed(m, "horse"))].name = "Hengst";
  m.nodes[std::size_t(nodeNamed(m, "rider"))].name = "Reiterin";
  for (tinygltf::Node& n : m.nodes)
    if (n.skin >= 0) n.extras = tinygltf::Value();
  const fs::path renamed = dir / "renamed.glb";
  writeGlbModel(m, renamed);
  const CommandResult other = runStirrup("check " + quote(renamed.string()));
  EXPECT_EQ(other.exit_code, 0) << other.out << other.err;
  EXPECT_EQ(other.out.substr(0, other.out.find('\n')),
            renamed.string() + ": a baked shot: 1 pair (Hengst and Reiterin), 24 frames at 24 fps, animation \"trot\"; ground: flat (the "
                               "file has no ground mesh: a node named \"ground\")");
}

// A crowd's bake (ride_out, 8 pairs, its first 12 frames) over the scene's own ground: every pair by
// the name the file gives it, clean; --pairs picks pairs by those names' numbers.
TEST_F(CheckCli, ABakedCrowdIsMeasuredPairByPair) {
  const fs::path glb = bakeShot(dir, "ride_out.json", "1-12");
  const std::string scene = quote(STIRRUP_SOURCE_DIR "/scenes/ride_out.json");
  const CommandResult r = runStirrup("check " + quote(glb.string()) + " --scene " + scene + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["frames"], 12);
  EXPECT_EQ(report["pairs"], 8);
  EXPECT_EQ(report["failures"], 0);
  EXPECT_EQ(report["warnings"], 0);
  EXPECT_EQ(report["pair_names"][3]["name"], "pair03");
  EXPECT_EQ(report["pair_names"][3]["pair"], 3);
  const CommandResult three = runStirrup("check " + quote(glb.string()) + " --scene " + scene + " --pairs 3,5");
  EXPECT_EQ(three.exit_code, 0) << three.err;
  EXPECT_EQ(lastLine(three.out), glb.string() + ": 12 frames, 2 pairs: 0 failures, 0 warnings, 0 notes");
  // Without --scene, on the ground the bake holds (its node "ground"): clean too, and the report says so.
  const CommandResult own = runStirrup("check " + quote(glb.string()) + " --json");
  EXPECT_EQ(own.exit_code, 0) << own.out << own.err;
  const nlohmann::json on_file = nlohmann::json::parse(own.out);
  EXPECT_EQ(on_file["ground"], "file");
  EXPECT_NE(on_file["described"].get<std::string>().find("; ground: the file's ground mesh ("), std::string::npos) << on_file["described"];
  // Its ground taken out (a tool that drops it), the ground is flat: the hooves of pairs on the hills (2
  // and 7) are in the ground, but the riders' rules do not depend on it: none has a finding.
  tinygltf::Model m = readGlbModel(glb);
  for (tinygltf::Node& n : m.nodes)
    if (n.name == "ground" || n.name == "ground_mesh") n.name = "terrain" + n.name.substr(6);
  const fs::path bare = dir / "bare.glb";
  writeGlbModel(m, bare);
  const nlohmann::json flat = nlohmann::json::parse(runStirrup("check " + quote(bare.string()) + " --pairs 2,7 --json").out);
  EXPECT_EQ(flat["ground"], "flat");
  EXPECT_GT(framesOf(flat, "hoof-in-ground").size(), 0u);
  for (const std::string& rule : kRiderRules) EXPECT_EQ(framesOf(flat, rule).size(), 0u) << rule;
}

// One truth (issue 60): `check SHOT.glb` of a scene's bake finds what `check SCENE.json` finds over the
// same frames, for every rule both measure (a bake has no targets or path: over-reach and limits are the
// scene's alone), pair by pair: on flat ground (trot), on hills (cross_country: the stretch from 11 s
// where hooves land and lift on the slopes; the file's own ground mesh), and for a crowd on hills
// (cavalry, 30 pairs). The counts are equal, and the frames they fall on.
struct Agreement {
  const char* scene;
  const char* frames;
  const char* ground;  // what the file check stands on
};
class FileCheckAgrees : public CheckCli, public ::testing::WithParamInterface<Agreement> {};

TEST_P(FileCheckAgrees, WithTheScenesCheckOverTheSameFrames) {
  const Agreement& a = GetParam();
  const fs::path glb = bakeShot(dir, std::string(a.scene) + ".json", a.frames);
  const CommandResult scene = runStirrup("check " + quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes" / a.scene).string() + ".json") +
                                         " --frames " + a.frames + " --json");
  const CommandResult file = runStirrup("check " + quote(glb.string()) + " --json");
  ASSERT_LT(scene.exit_code, 3) << scene.err;
  ASSERT_LT(file.exit_code, 3) << file.err;
  const nlohmann::json c = nlohmann::json::parse(scene.out), f = nlohmann::json::parse(file.out);
  EXPECT_EQ(f["read_as"], "shot");
  EXPECT_EQ(f["ground"], a.ground);
  EXPECT_EQ(f["frames"], c["frames"]);
  EXPECT_EQ(f["pairs"], c["pairs"]);
  // (pair, rule, severity) -> the frames of its findings (the file's frame 1 is the bake's first frame).
  const int first = scene::parseFrameList(a.frames, "frames").front();
  const auto byRule = [](const nlohmann::json& report, int frame_shift) {
    std::map<std::tuple<int, std::string, std::string>, std::multiset<int>> out;
    for (const auto& e : report["findings"]) {
      const std::string rule = e["rule"];
      if (rule == "over-reach" || rule == "limit" || e["severity"] == "note") continue;
      out[{e["pair"].get<int>(), rule, e["severity"].get<std::string>()}].insert(e["frame"].get<int>() + frame_shift);
    }
    return out;
  };
  EXPECT_EQ(byRule(f, first - 1), byRule(c, 0));
  int counted = 0;
  for (const char* rule : {"hoof-slide", "hoof-in-ground", "rider-in-horse", "hand-off-rein", "foot-off-stirrup", "trunk-balance"}) {
    EXPECT_EQ(f["rules"][rule], c["rules"][rule]) << rule;
    counted += c["rules"][rule]["failures"].get<int>() + c["rules"][rule]["warnings"].get<int>();
  }
  std::printf("%s frames %s: the scene's check and its bake's agree, %d findings each (ground: %s)\n", a.scene, a.frames, counted, a.ground);
}

INSTANTIATE_TEST_SUITE_P(Scenes, FileCheckAgrees,
                         ::testing::Values(Agreement{"trot", "1-24", "flat"}, Agreement{"cross_country", "265-312", "file"},
                                           Agreement{"cavalry", "1-12", "file"}),
                         [](const ::testing::TestParamInfo<Agreement>& i) { return std::string(i.param.scene); });

// The rider moved 15 cm down into the horse at frames 5-8 by editing the bake's keys of her root joint
// (the pelvis, in centimetres under the rider's metre node): rider-in-horse fails at those frames and no
// other; her hands leave the reins by the 15 cm planted.
TEST_F(CheckCli, ARiderKeyedIntoTheHorseFailsRiderInHorseAtThoseFrames) {
  const fs::path glb = bakeShot(dir, "trot.json", "1-12");
  tinygltf::Model m = readGlbModel(glb);
  const int pelvis = nodeNamed(m, "pelvis");
  ASSERT_GE(pelvis, 0);
  bool moved = false;
  for (const tinygltf::AnimationChannel& ch : m.animations.at(0).channels) {
    if (ch.target_node != pelvis || ch.target_path != "translation") continue;
    const tinygltf::Accessor& a = m.accessors[std::size_t(m.animations[0].samplers[std::size_t(ch.sampler)].output)];
    const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
    auto* keys = reinterpret_cast<float*>(m.buffers[0].data.data() + v.byteOffset + a.byteOffset);
    for (int frame = 5; frame <= 8; ++frame) keys[(frame - 1) * 3 + 1] -= 15.0f;  // y of frame F's key
    moved = true;
  }
  ASSERT_TRUE(moved) << "the bake keys no translation of the pelvis";
  const fs::path sunk = dir / "sunk.glb";
  writeGlbModel(m, sunk);
  const CommandResult r = runStirrup("check " + quote(sunk.string()) + " --json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  double deepest = 0, shallowest = 1e9, hand = 0, hand_least = 1e9;
  EXPECT_EQ(framesOf(report, "rider-in-horse", &deepest, &shallowest), (std::set<int>{5, 6, 7, 8}));
  for (const auto& e : report["findings"])
    if (e["rule"] == "rider-in-horse") {
      EXPECT_NEAR(e["time_s"].get<double>(), (e["frame"].get<int>() - 1) / 24.0, 1e-9) << e.dump();
    }
  // As text, its time in seconds (frame 5: 4 frames at 24 fps).
  const CommandResult text = runStirrup("check " + quote(sunk.string()));
  EXPECT_NE(text.out.find(sunk.string() + ": frame 5 (0.167 s): failure: rider-in-horse: "), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("inf s"), std::string::npos) << text.out;
  EXPECT_GE(shallowest, 10.0);      // the failure bound: a limb through the barrel
  EXPECT_LE(deepest, 15.0 + 0.5);   // no deeper than moved (the bake's own contact is under half a centimetre)
  EXPECT_EQ(framesOf(report, "hand-off-rein", &hand, &hand_least), (std::set<int>{5, 6, 7, 8}));
  EXPECT_NEAR(hand, 15.0, 0.05);
  EXPECT_NEAR(hand_least, 15.0, 0.05);
  int failures = 0;
  for (const auto& e : report["findings"])
    if (e["rule"] == "rider-in-horse") {
      failures += e["severity"] == "failure";
      EXPECT_EQ(e["where"], "pelvis") << e.dump();  // the seat goes in first
    }
  EXPECT_EQ(failures, 4);
  std::printf("rider keyed 15 cm down at frames 5-8: rider-in-horse %.2f to %.2f cm\n", shallowest, deepest);
}

// What Blender 3.4 makes of a bake: imported, exported again by its glTF exporter as it is, and again with
// the rider armature moved 15 cm down (Blender's Z) and custom properties kept (the role table with it).
constexpr const char* kBlenderReExport = R"(
src, untouched, moved = args
import_glb(src)
bpy.ops.export_scene.gltf(filepath=untouched, export_format="GLB")
bpy.data.objects["rider"].location.z -= 0.15
bpy.ops.export_scene.gltf(filepath=moved, export_format="GLB", export_extras=True)
)";

// The round trip through Blender: its re-export (armatures named after the nodes, no skin skeleton, the
// meshes under the armatures, no cameras, one animation) reads as the same shot and is clean; the rider
// moved 15 cm into the horse fails rider-in-horse on every frame.
TEST_F(CheckCli, BlendersReExportOfABakeIsMeasuredAndARiderMovedIntoTheHorseFails) {
  if (!blenderInstalled()) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)";
  const fs::path glb = bakeShot(dir, "trot.json", "1-24");
  const fs::path untouched = dir / "untouched.glb", moved = dir / "moved.glb";
  const CommandResult b = runBlenderScript(dir / "reexport.py", kBlenderReExport,
                                           quote(glb.string()) + " " + quote(untouched.string()) + " " + quote(moved.string()));
  ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
  const tinygltf::Model m = readGlbModel(untouched);
  EXPECT_EQ(m.asset.generator.rfind("Khronos glTF Blender I/O", 0), 0u) << m.asset.generator;
  ASSERT_EQ(m.skins.size(), 2u);
  for (const tinygltf::Skin& skin : m.skins) EXPECT_EQ(skin.skeleton, -1);
  const int horse = nodeNamed(m, "horse");
  ASSERT_GE(horse, 0);
  EXPECT_NE(std::find(m.nodes[std::size_t(horse)].children.begin(), m.nodes[std::size_t(horse)].children.end(), nodeNamed(m, "horse:horse_mesh")),
            m.nodes[std::size_t(horse)].children.end());
  EXPECT_TRUE(m.cameras.empty());
  // Kept, the role table comes back as written, but Blender lists the joints depth first: the indices
  // point at other joints, the names (stirrup_role_joints) at the right ones.
  const tinygltf::Model kept = readGlbModel(moved), baked = readGlbModel(glb);
  const auto jointNames = [](const tinygltf::Model& model, int skin) {
    std::vector<std::string> names;
    for (const int n : model.skins.at(std::size_t(skin)).joints) names.push_back(model.nodes[std::size_t(n)].name);
    return names;
  };
  EXPECT_TRUE(kept.nodes[std::size_t(nodeNamed(kept, "rider:rider_mesh"))].extras.Has("stirrup_role_joints"));
  EXPECT_NE(jointNames(kept, 1), jointNames(baked, 1));

  const CommandResult bake = runStirrup("check " + quote(glb.string()) + " --json");
  const CommandResult clean = runStirrup("check " + quote(untouched.string()) + " --json");
  EXPECT_EQ(bake.exit_code, 0) << bake.out << bake.err;
  EXPECT_EQ(clean.exit_code, 0) << clean.out << clean.err;
  const nlohmann::json c = nlohmann::json::parse(clean.out);
  EXPECT_EQ(c["read_as"], "shot");
  EXPECT_EQ(c["frames"], 24);
  for (const std::string& rule : kRiderRules) EXPECT_EQ(framesOf(c, rule).size(), 0u) << rule;

  const CommandResult sunk = runStirrup("check " + quote(moved.string()) + " --json");
  EXPECT_EQ(sunk.exit_code, 2) << sunk.err;
  const nlohmann::json s = nlohmann::json::parse(sunk.out);
  double deepest = 0, shallowest = 1e9, hand = 0;
  std::set<int> every;
  for (int f = 1; f <= 24; ++f) every.insert(f);
  EXPECT_EQ(framesOf(s, "rider-in-horse", &deepest, &shallowest), every);
  EXPECT_GE(shallowest, 10.0);
  EXPECT_LE(deepest, 15.0 + 0.5);
  framesOf(s, "hand-off-rein", &hand);
  EXPECT_NEAR(hand, 15.0, 0.05);
  std::printf("Blender's re-export: %s; rider moved 15 cm: rider-in-horse %.2f to %.2f cm\n", c["described"].get<std::string>().c_str(),
              shallowest, deepest);
}

// Blender 3.4's re-export of the cross-country bake, as it is (issue 60): its ground comes back as the node
// "ground" holding "ground_mesh", and the shot checks clean on it over hills and a gait change, as the
// scene and its bake do (FileCheckAgrees), with the same counts as the bake.
constexpr const char* kBlenderAsItIs = R"(
src, out = args
import_glb(src)
bpy.ops.export_scene.gltf(filepath=out, export_format="GLB")
)";

TEST_F(CheckCli, BlendersReExportOfTheCrossCountryBakeChecksCleanOnItsOwnGround) {
  if (!blenderInstalled()) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)";
  const fs::path glb = bakeShot(dir, "cross_country.json", "265-312");
  const fs::path again = dir / "cross_country_from_blender.glb";
  const CommandResult b = runBlenderScript(dir / "as_it_is.py", kBlenderAsItIs, quote(glb.string()) + " " + quote(again.string()));
  ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
  const tinygltf::Model m = readGlbModel(again);
  EXPECT_EQ(m.asset.generator.rfind("Khronos glTF Blender I/O", 0), 0u) << m.asset.generator;
  ASSERT_GE(nodeNamed(m, "ground_mesh"), 0);
  const CommandResult r = runStirrup("check " + quote(again.string()) + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["read_as"], "shot");
  EXPECT_EQ(report["ground"], "file");
  EXPECT_EQ(report["frames"], 48);
  EXPECT_EQ(report["failures"], 0);
  EXPECT_EQ(report["warnings"], 0);
  const nlohmann::json bake = nlohmann::json::parse(runStirrup("check " + quote(glb.string()) + " --json").out);
  for (const char* rule : {"hoof-slide", "hoof-in-ground", "rider-in-horse", "hand-off-rein", "foot-off-stirrup", "trunk-balance"})
    EXPECT_EQ(report["rules"][rule], bake["rules"][rule]) << rule;
  std::printf("Blender's re-export of cross_country 265-312: %s\n", report["described"].get<std::string>().c_str());
}

// What cannot be checked is one line naming the file and what is missing, exit 3: a horse without its
// rider, a rider whose role table lacks her pelvis, an animation keying no joint of the pair.
TEST_F(CheckCli, BadBakedShotsAreOneLineErrors) {
  const fs::path glb = bakeShot(dir, "trot.json", "1-4");
  const auto broken = [&](const std::string& name, const std::function<void(tinygltf::Model&)>& change) {
    tinygltf::Model m = readGlbModel(glb);
    change(m);
    const fs::path f = dir / name;
    writeGlbModel(m, f);
    const CommandResult r = runStirrup("check " + quote(f.string()));
    EXPECT_EQ(r.exit_code, 3) << r.out;
    EXPECT_EQ(r.out, "");
    return r.err;
  };
  const std::string lone = (dir / "lone.glb").string();
  EXPECT_EQ(broken("lone.glb", [](tinygltf::Model& m) { m.nodes[std::size_t(nodeNamed(m, "rider"))].name = "jockey"; }),
            "stirrup: " + lone + ": the horse \"horse\" has no rider (expected a skinned armature \"rider\" beside it)\n");
  const std::string no_pelvis = (dir / "no_pelvis.glb").string();
  EXPECT_EQ(broken("no_pelvis.glb",
                   [](tinygltf::Model& m) {
                     tinygltf::Node& mesh = m.nodes[std::size_t(nodeNamed(m, "rider:rider_mesh"))];
                     tinygltf::Value::Object extras = mesh.extras.Get<tinygltf::Value::Object>();
                     for (const char* table : {"stirrup_roles", "stirrup_role_joints"}) {
                       tinygltf::Value::Object roles = extras[table].Get<tinygltf::Value::Object>();
                       roles.erase("pelvis");
                       extras[table] = tinygltf::Value(roles);
                     }
                     mesh.extras = tinygltf::Value(extras);
                   }),
            "stirrup: " + no_pelvis + ": the rider \"rider\" (skins[1]): role pelvis: missing from the file's role table (expected a joint of the rider)\n");
  const std::string still = (dir / "still.glb").string();
  EXPECT_EQ(broken("still.glb",
                   [](tinygltf::Model& m) {
                     std::vector<tinygltf::AnimationChannel> cameras;
                     for (const tinygltf::AnimationChannel& ch : m.animations[0].channels)
                       if (m.nodes[std::size_t(ch.target_node)].name.rfind("camera:", 0) == 0) cameras.push_back(ch);
                     m.animations[0].channels = cameras;
                   }),
            "stirrup: " + still + ": the animation \"trot\" keys no joint of the horse \"horse\" or the rider \"rider\" (expected the shot's motion keyed on their joints)\n");
  // A frame the file does not key.
  const CommandResult past = runStirrup("check " + quote(glb.string()) + " --frames 3-9");
  EXPECT_EQ(past.exit_code, 3);
  EXPECT_EQ(past.err, "stirrup: --frames: " + glb.string() + " keys frames 1-4, got 5\n");
}

TEST_F(CheckCli, ASceneThatCannotBeCheckedExitsThree) {
  const std::string f = (dir / "absent.json").string();
  const CommandResult r = runStirrup("check " + quote(f));
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.err, "stirrup: " + f + ": cannot open the file (expected a readable JSON file)\n");
}

// A bake of a user's horse (tests/cli/own_horse_bake.h) rewritten as the Blender add-on exports a shot
// whose horse carries the tack: the tack's joints are bones of a tack armature of their own ("stirrup
// tack", its bones renamed as a user would name them), merged into the horse's skin, the role tables by
// the joints' names alone (stirrup_role_joints, the tack roles naming those bones), no skin skeleton, and
// Blender's generator. Read as a shot, the horse's tack roles are those joints: her hands and feet are
// measured against them (clean), and the left rein's end keyed 15 cm off at frames 5-8 fails
// hand-off-rein at those frames, by 15 cm, and no other.
void blenderTackShot(const fs::path& baked, const fs::path& out, const std::function<void(tinygltf::Model&, const std::map<std::string, int>&)>& edit) {
  tinygltf::Model m = readGlbModel(baked);
  const rig::GltfAnimation animation = rig::GltfAnimation::together(m, baked.string());
  const int horse_root = nodeNamed(m, "horse");
  int skin = -1;
  for (std::size_t k = 0; k < m.skins.size(); ++k)
    if (m.skins[k].skeleton == horse_root) skin = int(k);
  ASSERT_GE(skin, 0);
  const std::map<std::string, std::string> renamed = {
      {"saddle", "Saddle"}, {"lStirrup", "stirrup.L"}, {"rStirrup", "stirrup.R"}, {"lRein", "rein_end.L"}, {"rRein", "rein_end.R"}};
  std::map<std::string, int> tack;  // role -> joint node
  for (const int j : m.skins[std::size_t(skin)].joints)
    if (renamed.count(m.nodes[std::size_t(j)].name)) tack[m.nodes[std::size_t(j)].name] = j;
  ASSERT_EQ(tack.size(), 5u);
  // The saddle (the tack's top bone) under an armature of its own, keyed against it at every key.
  const int saddle = tack.at("saddle"), under = animation.parents()[std::size_t(saddle)];
  std::vector<int>& siblings = m.nodes[std::size_t(under)].children;
  siblings.erase(std::remove(siblings.begin(), siblings.end(), saddle), siblings.end());
  tinygltf::Node armature;
  armature.name = "stirrup tack";
  armature.scale = {0.01, 0.01, 0.01};
  armature.children = {saddle};
  m.nodes.push_back(armature);
  m.scenes.at(0).nodes.push_back(int(m.nodes.size()) - 1);
  std::vector<float> t, r;
  const double fps = m.scenes.at(0).extras.Get("fps").GetNumberAsDouble();
  for (int k = 0; k <= int(std::lround(animation.duration() * fps)); ++k) {
    const glm::dmat4 local = glm::scale(glm::dmat4(1.0), glm::dvec3(100.0)) * animation.worlds(k / fps)[std::size_t(saddle)];
    const glm::dquat q = glm::normalize(glm::quat_cast(glm::dmat3(local)));
    t.insert(t.end(), {float(local[3][0]), float(local[3][1]), float(local[3][2])});
    r.insert(r.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
  }
  m.nodes[std::size_t(saddle)].translation = {t[0], t[1], t[2]};
  m.nodes[std::size_t(saddle)].rotation = {r[0], r[1], r[2], r[3]};
  for (const tinygltf::AnimationChannel& ch : m.animations.at(0).channels) {
    if (ch.target_node != saddle) continue;
    const std::vector<float>& values = ch.target_path == "translation" ? t : r;
    const tinygltf::Accessor& a = m.accessors[std::size_t(m.animations[0].samplers[std::size_t(ch.sampler)].output)];
    const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
    ASSERT_EQ(a.count * (ch.target_path == "translation" ? 3u : 4u), values.size());
    std::memcpy(m.buffers[0].data.data() + v.byteOffset + a.byteOffset, values.data(), values.size() * sizeof(float));
  }
  for (const auto& [role, node] : tack) m.nodes[std::size_t(node)].name = renamed.at(role);
  for (tinygltf::Node& n : m.nodes) {
    if (n.skin < 0 || !n.extras.IsObject() || !n.extras.Has("stirrup_roles")) continue;
    tinygltf::Value::Object extras = n.extras.Get<tinygltf::Value::Object>();
    extras.erase("stirrup_roles");
    tinygltf::Value::Object by_name = extras["stirrup_role_joints"].Get<tinygltf::Value::Object>();
    if (n.skin == skin)
      for (const auto& [role, name] : renamed) by_name[role] = tinygltf::Value(name);
    extras["stirrup_role_joints"] = tinygltf::Value(by_name);
    n.extras = tinygltf::Value(extras);
  }
  for (tinygltf::Skin& k : m.skins) k.skeleton = -1;
  m.asset.generator = "Khronos glTF Blender I/O v3.4.50";
  edit(m, tack);
  writeGlbModel(m, out);
}

TEST_F(CheckCli, ABlenderShotWhoseHorseNamesItsTackJointsIsMeasuredAtThem) {
  if (!blenderInstalled()) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)";
  const OwnHorseBake own = bakeOwnHorse(dir);
  ASSERT_FALSE(own.baked.empty()) << own.why;
  const fs::path named = dir / "named_tack.glb", off = dir / "rein_off.glb";
  blenderTackShot(own.baked, named, [](tinygltf::Model&, const std::map<std::string, int>&) {});
  const CommandResult clean = runStirrup("check " + quote(named.string()) + " --json");
  EXPECT_EQ(clean.exit_code, 0) << clean.out << clean.err;
  const nlohmann::json c = nlohmann::json::parse(clean.out);
  for (const nlohmann::json& u : c["unmeasured"]) EXPECT_TRUE(u["rule"] != "hand-off-rein" && u["rule"] != "foot-off-stirrup") << u.dump();
  for (const std::string& rule : kRiderRules) EXPECT_EQ(framesOf(c, rule).size(), 0u) << rule << ": " << clean.out;

  blenderTackShot(own.baked, off, [](tinygltf::Model& m, const std::map<std::string, int>& tack) {
    for (const tinygltf::AnimationChannel& ch : m.animations.at(0).channels) {
      if (ch.target_node != tack.at("lRein") || ch.target_path != "translation") continue;
      const tinygltf::Accessor& a = m.accessors[std::size_t(m.animations[0].samplers[std::size_t(ch.sampler)].output)];
      const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
      auto* keys = reinterpret_cast<float*>(m.buffers[0].data.data() + v.byteOffset + a.byteOffset);
      for (int frame = 5; frame <= 8; ++frame) keys[(frame - 1) * 3 + 1] += 15.0f;  // 15 cm up the saddle's y
    }
  });
  const CommandResult r = runStirrup("check " + quote(off.string()) + " --json");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  double worst = 0, least = 1e9;
  EXPECT_EQ(framesOf(report, "hand-off-rein", &worst, &least), (std::set<int>{5, 6, 7, 8}));
  EXPECT_NEAR(worst, 15.0, 0.05);
  EXPECT_NEAR(least, 15.0, 0.05);
  for (const auto& e : report["findings"])
    if (e["rule"] == "hand-off-rein") {
      EXPECT_EQ(e["where"], "left") << e.dump();
    }
  std::printf("the add-on's shot with its tack joints named: hand-off-rein %.2f to %.2f cm at frames 5-8\n", least, worst);
}

}  // namespace
}  // namespace stirrup::test
