// The tack in Blender (docs/blender.md, "The tack"): after Ride, the saddle, pad, bridle, bit, stirrup leathers
// and irons and the reins stirrup fits the horse are in the collection "stirrup tack", where stirrup's full
// bake of the same shot puts them; the reins run from the bit to her hands; a second Ride replaces the tack and
// nothing else; Check measures her hands and feet on it; what cannot be, is refused in one line. On Rigify's
// generated horse with Rigify's generated human (.blend files, as an animator has them) and on Rigify's horse
// meta-rig with Rigify's human imported from glTF. Skipped, with a message, where `blender` is not installed.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/io/character_mapping_json.h"
#include "rig/mapping/character_mapping.h"
#include "tests/cli/blender_addon_support.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

constexpr double kTackCm = 0.5;  // the issue's bar: the tack's vertices within 0.5 cm of the full bake's
const std::set<std::string> kParts = {"saddle", "saddle pad", "bridle", "bit", "stirrup leather.L", "stirrup leather.R",
                                      "stirrup iron.L", "stirrup iron.R", "reins"};

// After kAddonEnable: what the tack tests read back in Blender. args: OUT_DIR and the characters' files.
constexpr const char* kTackHelpers = R"(
def tack_parts():
    c = bpy.data.collections.get("stirrup tack")
    return [] if c is None else [o for o in c.objects if o.type == "MESH"]

def tack_vertices(frames, stride=10):
    """Every stride-th vertex of every part as Blender evaluates it (modifiers and all), Blender's world, at each frame."""
    out = {}
    for f in frames:
        scene.frame_set(f)
        dg = bpy.context.evaluated_depsgraph_get()
        for o in tack_parts():
            ev = o.evaluated_get(dg)
            m = ev.to_mesh()
            out.setdefault(o.get("stirrup_tack"), {})[str(f)] = [list(ev.matrix_world @ m.vertices[i].co) for i in range(0, len(m.vertices), stride)]
            ev.to_mesh_clear()
    return out

def min_cm(points, p):
    return min((Vector(q) - p).length for q in points) * 100.0

def reins_reach(frames, hands):
    """How far (cm) the reins come to each of her hands and to the bit, at each frame: the nearest vertex of the
    reins to each hand's joint, and to the bit's vertices."""
    out = []
    for f in frames:
        scene.frame_set(f)
        dg = bpy.context.evaluated_depsgraph_get()
        parts = {o.get("stirrup_tack"): o.evaluated_get(dg) for o in tack_parts()}
        reins = [parts["reins"].matrix_world @ v.co for v in parts["reins"].to_mesh().vertices]
        bit = [parts["bit"].matrix_world @ v.co for v in parts["bit"].to_mesh().vertices]
        row = [min_cm(reins, rider.matrix_world @ rider.pose.bones[h].head) for h in hands]
        row.append(min(min_cm(reins, b) for b in bit[::4]))
        out.append(row)
    return out
)";

// The full bake's tack (work/ride-shot.glb, written by Ride) at Blender's `frame`, every stride-th vertex of each
// part, in Blender's world: the bake's metres under its centimetre root, to stirrup's cm, to the horse's file
// by the horse's mapping, to Blender's axes.
std::map<std::string, std::vector<glm::dvec3>> bakedTack(const fs::path& work, int frame, std::size_t stride) {
  tinygltf::Model model;
  tinygltf::TinyGLTF io;
  std::string err, warn;
  std::map<std::string, std::vector<glm::dvec3>> out;
  if (!io.LoadBinaryFromFile(&model, &err, &warn, (work / "ride-shot.glb").string())) {
    ADD_FAILURE() << err;
    return out;
  }
  const glm::dmat4 h = rig::mappingToRig(rig::loadCharacterMapping((work / "horse-map.json").string(), rig::CharacterKind::Horse));
  const glm::dmat4 to_file = glm::inverse(h);
  const AnimatedNodes nodes(model);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.mesh < 0 || !node.extras.Has("stirrup_tack")) continue;
    for (const glm::dvec3& p : nodes.skinned(int(n), std::size_t(frame - 1), stride, true)) {
      const glm::dvec3 f = glm::dvec3(to_file * glm::dvec4(p * 100.0, 1.0));
      out[node.extras.Get("stirrup_tack").Get<std::string>()].push_back({f.x, -f.z, f.y});  // glTF's axes to Blender's
    }
  }
  return out;
}

struct TackCase {
  std::string name;
  std::string horse_blend;  // a .blend to open (the generated horse), or empty: the horse meta-rig imported
};

void PrintTo(const TackCase& c, std::ostream* os) { *os << c.name; }

class BlenderTack : public ::testing::TestWithParam<TackCase> {};

// Ride brings the tack, where the full bake puts it, moving as it does; the reins in her hands; Check measures
// her hands and feet; a second Ride replaces the tack, leaving the user's own objects.
TEST_P(BlenderTack, RideBringsTheTackWhereTheBakePutsIt) {
  SKIP_WITHOUT_BLENDER();
  BlenderMade horses, rider_blend, rider_glb, metarig;
  const fs::path horses_dir = blenderRigifyHorses(&horses);
  const fs::path rider = blenderRigifyRiderBlend(&rider_blend);
  const fs::path rider_file = blenderRigifyRider(&rider_glb);
  const fs::path metarig_dir = fs::path(STIRRUP_BINARY_DIR) / "test_blender_addon" / "fixture-horse";
  const fs::path script = STIRRUP_SOURCE_DIR "/tests/blender/rigify-horse";
  metarig = madeByBlender(metarig_dir, script, quote(script.string()) + " " + quote((metarig_dir / "horse.glb").string()) + " --form metarig --bones all --walk");
  ASSERT_TRUE(horses.ok && rider_blend.ok && metarig.ok) << horses.log << rider_blend.log << metarig.log;
  const bool generated = !GetParam().horse_blend.empty();
  const fs::path dir = addonTestDir("tack-" + GetParam().name);
  const std::string setup = generated ? std::string(kRiderBesideTheHorse) + R"(
hands = ["DEF-palm.02.L", "DEF-palm.02.R"]
)"
                                      : R"(
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
def load(path):
    before = set(bpy.data.objects)
    bpy.ops.import_scene.gltf(filepath=path)
    return [o for o in bpy.data.objects if o not in before and o.type == "ARMATURE"][0]
horse, rider = load(args[2]), load(args[3])
hands = ["DEF-palm.02.L", "DEF-palm.02.R"]
)";
  const AddonRun run = runAddon(dir, std::string(kTackHelpers) + setup + R"(
scene.frame_start, scene.frame_end = 1, 48
s.horse, s.rider = horse, rider
mine = bpy.data.objects.new("my lamp post", None)
scene.collection.objects.link(mine)
result["ride"] = attempt(bpy.ops.stirrup.ride)
result["said"] = s.last_ride
c = bpy.data.collections.get("stirrup tack")
result["parts"] = sorted(o.get("stirrup_tack", "") for o in tack_parts())
result["fits"] = sorted({o.get("stirrup_fits", "") for o in tack_parts()})
result["vertices"] = tack_vertices([1, 17, 33])
result["reach"] = reins_reach([1, 17, 33], hands)
s.live = True  # Live poses the tack's points with her, the ride's layer muted
result["live_error_on"] = live.last_error()
result["live_vertices"] = tack_vertices([17, 33])
result["live_reach"] = reins_reach([17, 33], hands)
s.live = False
result["live_error"] = live.last_error()
result["check"] = attempt(bpy.ops.stirrup.check)
result["unmeasured"] = s.check_unmeasured
result["findings"] = sorted({f.rule for f in s.findings})
saddle = [o for o in tack_parts() if o.get("stirrup_tack") == "saddle"][0]
saddle.location.z += 0.2  # the animator moves the saddle: hers until she rides again
result["collections_before"] = sorted(c.name for c in bpy.data.collections)
result["again"] = attempt(bpy.ops.stirrup.ride)
result["parts_again"] = sorted(o.get("stirrup_tack", "") for o in tack_parts())
result["collections"] = sorted(c.name for c in bpy.data.collections)
result["mine_kept"] = "my lamp post" in bpy.data.objects
result["saddle_back"] = [o for o in tack_parts() if o.get("stirrup_tack") == "saddle"][0].location.z
)",
                                 quote(rider.string()) + " " + quote((metarig_dir / "horse.glb").string()) + " " + quote(rider_file.string()),
                                 generated ? horses_dir / GetParam().horse_blend : fs::path());
  ASSERT_RAN(run);
  const nlohmann::json& r = run.result;
  ASSERT_TRUE(r["ride"].contains("ok")) << r["ride"];
  EXPECT_NE(r["said"].get<std::string>().find("the tack in the collection \"stirrup tack\""), std::string::npos) << r["said"];
  EXPECT_EQ(r["parts"].get<std::set<std::string>>(), kParts);
  EXPECT_EQ(r["fits"].size(), 1u) << r["fits"];
  // Where the bake puts each part, at three frames.
  double worst = 0.0;
  std::string where;
  std::size_t compared = 0;
  for (const int frame : {1, 17, 33}) {
    const auto baked = bakedTack(dir / "work", frame, 10);
    for (const auto& [part, points] : baked) {
      const nlohmann::json& shown = r["vertices"][part][std::to_string(frame)];
      ASSERT_EQ(shown.size(), points.size()) << part;
      for (std::size_t i = 0; i < points.size(); ++i) {
        const double d = glm::length(glm::dvec3(shown[i][0], shown[i][1], shown[i][2]) - points[i]) * 100.0;
        if (d > worst) worst = d, where = part + " at frame " + std::to_string(frame);
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 300u);
  EXPECT_LT(worst, kTackCm) << "cm, " << where;
  std::printf("%s: tack %zu vertices, worst %.4f cm (%s)\n", GetParam().name.c_str(), compared, worst, where.c_str());
  // The reins in her hands and at the bit.
  for (const nlohmann::json& row : r["reach"]) {
    EXPECT_LT(row[0].get<double>(), 3.0) << "the reins reach her left hand";
    EXPECT_LT(row[1].get<double>(), 3.0) << "the reins reach her right hand";
    EXPECT_LT(row[2].get<double>(), 1.0) << "the reins meet the bit";
  }
  // Live: the tack where the ride put it (the same computation, stirrup's live session), the reins in her hands.
  EXPECT_EQ(r["live_error_on"], "") << r["live_error_on"];
  EXPECT_EQ(r["live_error"], "") << r["live_error"];
  double live_worst = 0.0;
  std::size_t live_compared = 0;
  for (const auto& [part, frames] : r["live_vertices"].items())
    for (const auto& [frame, points] : frames.items()) {
      const nlohmann::json& ridden = r["vertices"][part][frame];
      ASSERT_EQ(points.size(), ridden.size()) << part;
      for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3 a(points[i][0], points[i][1], points[i][2]), b(ridden[i][0], ridden[i][1], ridden[i][2]);
        live_worst = std::max(live_worst, glm::length(a - b) * 100.0);
        ++live_compared;
      }
    }
  EXPECT_GT(live_compared, 200u);
  EXPECT_LT(live_worst, kTackCm) << "cm, Live's tack against the ride's";
  std::printf("%s: Live's tack %zu vertices, worst %.4f cm from the ride's\n", GetParam().name.c_str(), live_compared, live_worst);
  for (const nlohmann::json& row : r["live_reach"]) {
    EXPECT_LT(row[0].get<double>(), 3.0) << "Live: the reins reach her left hand";
    EXPECT_LT(row[1].get<double>(), 3.0) << "Live: the reins reach her right hand";
  }
  // Check measures her hands and feet on the tack, and finds them on it.
  ASSERT_TRUE(r["check"].contains("ok")) << r["check"];
  for (const char* rule : {"hand-off-rein", "foot-off-stirrup"}) {
    EXPECT_EQ(r["unmeasured"].get<std::string>().find(rule), std::string::npos) << rule << " not measured: " << r["unmeasured"];
    EXPECT_FALSE(r["findings"].get<std::set<std::string>>().count(rule)) << rule;
  }
  // A second Ride: the tack replaced (the moved saddle back where stirrup fits it), nothing else touched.
  ASSERT_TRUE(r["again"].contains("ok")) << r["again"];
  EXPECT_EQ(r["parts_again"].get<std::set<std::string>>(), kParts);
  EXPECT_EQ(r["collections"], r["collections_before"]) << "one tack collection, the others untouched";
  EXPECT_EQ(std::count(r["collections"].begin(), r["collections"].end(), "stirrup tack"), 1) << r["collections"];
  EXPECT_TRUE(r["mine_kept"].get<bool>());
  EXPECT_NEAR(r["saddle_back"].get<double>(), 0.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Rigify, BlenderTack,
                         ::testing::Values(TackCase{"generated", "ik.blend"}, TackCase{"metarig", ""}),
                         [](const ::testing::TestParamInfo<TackCase>& i) { return i.param.name; });

// What cannot be ridden with tack is refused in one line and the scene left as it was: the horse's mapping
// without its head (no bridle to hang), the tack's collection renamed, or emptied.
TEST(BlenderTack, BadTackInputIsRefusedInOneLine) {
  SKIP_WITHOUT_BLENDER();
  BlenderMade horses, rider_blend;
  const fs::path horses_dir = blenderRigifyHorses(&horses);
  const fs::path rider = blenderRigifyRiderBlend(&rider_blend);
  ASSERT_TRUE(horses.ok && rider_blend.ok) << horses.log << rider_blend.log;
  const fs::path dir = addonTestDir("tack-bad");
  const AddonRun run = runAddon(dir, std::string(kTackHelpers) + kRiderBesideTheHorse + R"(
scene.frame_start, scene.frame_end = 1, 24
s.horse, s.rider = horse, rider
tried = {}
result["ride"] = attempt(bpy.ops.stirrup.ride)
def state():
    c = [c for c in bpy.data.collections if c.get("stirrup_tack")]
    return [sorted(o.name for o in c[0].objects) if c else [], c[0].name if c else "", len(bpy.data.actions)]
c = bpy.data.collections["stirrup tack"]
c.name = "my tack"
before = state()
tried["renamed"] = attempt(bpy.ops.stirrup.ride)
result["renamed_untouched"] = state() == before
c.name = "stirrup tack"
for o in list(c.objects):
    bpy.data.objects.remove(o)
before = state()
tried["emptied"] = attempt(bpy.ops.stirrup.ride)
tried["emptied, check"] = attempt(bpy.ops.stirrup.check)
result["emptied_untouched"] = state() == before
bpy.data.collections.remove(c)
head = [r for r in s.horse_map.roles if r.role == "head"]
s.horse_map.roles.remove(list(s.horse_map.roles).index(head[0]))
before = state()
tried["no head"] = attempt(bpy.ops.stirrup.ride)
result["no_head_untouched"] = state() == before
result["tried"] = tried
)",
                                 quote(rider.string()), horses_dir / "ik.blend");
  ASSERT_RAN(run);
  ASSERT_TRUE(run.result["ride"].contains("ok")) << run.result["ride"];
  const nlohmann::json& tried = run.result["tried"];
  const std::map<std::string, std::string> says = {
      {"renamed", "the tack's collection was renamed \"my tack\""},
      {"emptied", "is empty of its tack"},
      {"emptied, check", "holds no tack rig"},
      {"no head", "head"},
  };
  expectOneLineErrors(tried, says);
  for (const char* k : {"renamed_untouched", "emptied_untouched", "no_head_untouched"}) EXPECT_TRUE(run.result[k].get<bool>()) << k;
}

}  // namespace
}  // namespace stirrup::test
