// A troop of the user's own horse (issue 60; docs/crowds.md, "Your own horses"), end to end through the
// program: Blender's Rigify horse (the generated rig, deform bones, its saddle and keyed walk:
// tests/blender/rigify-horse) in a crowd of 8, with mixed riders: the crowd's generated riders at
// their own proportions and Blender's Rigify human (tests/blender/rigify-rider), six pairs walking
// the lead's path on the generated gait and two playing the horse's own keyed walk from their slots.
// The scene loads (every pair seated on its horse as a single pair is), checks clean, bakes (every pair's
// armatures, the user's joints), the bake checks clean as the scene does, and a frame renders. The oracle
// for "its own walk, as keyed" is Blender's evaluation of the walk (the script's --expected file).
// Skipped, with a message, where `blender` is not installed.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "tests/blender_fixture.h"
#include "tests/cli/baked_file.h"
#include "tests/cli/run_command.h"
#include "tests/test_files.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 24;

// The crowd: 2 files, 4 ranks, walking 180 cm/s along +X on flat ground, all starting in step (no start
// offset, so a pair's frame F plays the walk's frame F); pairs 0-2 generated riders on the generated walk,
// 3-5 the Rigify rider on it, 6 a generated rider and 7 the Rigify rider on the horse's own walk.
nlohmann::json troop(const fs::path& horse, const fs::path& horse_map, const fs::path& rider, const fs::path& rider_map) {
  const nlohmann::json h = {{"file", horse.string()}, {"mapping", horse_map.string()}};
  const nlohmann::json r = {{"file", rider.string()}, {"mapping", rider_map.string()}};
  return {{"name", "troop"},
          {"crowd",
           {{"pairs", 8},
            {"seed", 11},
            {"lead", {{"points", {{0, 0}, {3000, 0}}}, {"speed", {{0, 180}, {10, 180}}}}},
            {"formation", {{"files", 2}, {"file_spacing_cm", 450}, {"rank_spacing_cm", 1000}, {"jitter_cm", 10}}},
            {"profiles", {{"thesis", 1}, {"english", 1}}},
            {"characters",
             {{{"pairs", "0-2"}, {"horse", h}},
              {{"pairs", "3-5"}, {"horse", h}, {"rider", r}},
              {{"pairs", "6"}, {"horse", h}, {"animation", "Walk"}},
              {{"pairs", "7"}, {"horse", h}, {"rider", r}, {"animation", "Walk"}}}}}},
          {"fps", 24},
          {"frames", "1-" + std::to_string(kFrames)},
          {"resolution", {160, 90}},
          {"cameras", {{{"name", "persp"}, {"view", "persp"}}}}};
}

TEST(OwnTroop, EightRigifyHorsesWithMixedRidersBakeRenderAndCheckClean) {
  if (!blenderInstalled()) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)";
  BlenderMade made;
  const fs::path horse_dir = blenderRigifyHorse("generated-deform-saddle", "--form generated --bones deform --saddle", &made);
  ASSERT_TRUE(made.ok) << "tests/blender/rigify-horse failed: " << made.log;
  const fs::path rider = blenderRigifyRider(&made);
  ASSERT_TRUE(made.ok) << "tests/blender/rigify-rider failed: " << made.log;
  const fs::path dir = freshTestDir("test_own_troop", "troop");
  const fs::path horse = horse_dir / "horse.glb", horse_map = dir / "horse-map.json", rider_map = dir / "rider-map.json";
  ASSERT_EQ(runStirrup("character map " + quote(horse.string()) + " --as horse -o " + quote(horse_map.string())).exit_code, 0);
  ASSERT_EQ(runStirrup("character map " + quote(rider.string()) + " --as rider -o " + quote(rider_map.string())).exit_code, 0);
  const fs::path scene = dir / "troop.json";
  std::ofstream(scene) << troop(horse, horse_map, rider, rider_map).dump(2);

  // The scene checks clean: no hoof slides, sinks or over-reaches; every rider in her seat, hands and feet.
  const CommandResult check = runStirrup("check " + quote(scene.string()) + " --json");
  ASSERT_LT(check.exit_code, 3) << check.err;
  const nlohmann::json c = nlohmann::json::parse(check.out);
  EXPECT_EQ(check.exit_code, 0) << check.out;
  EXPECT_EQ(c["pairs"], 8);
  EXPECT_EQ(c["failures"], 0);
  EXPECT_EQ(c["warnings"], 0);
  EXPECT_EQ(c["unmeasured"], nlohmann::json::array()) << c["unmeasured"];

  // Baked: two armatures a pair, the horses with the user's joints, the riders mixed.
  const fs::path baked = dir / "troop.glb";
  const CommandResult bake = runStirrup("bake " + quote(scene.string()) + " -o " + quote(baked.string()));
  ASSERT_EQ(bake.exit_code, 0) << bake.err;
  const tinygltf::Model m = readGlbModel(baked);
  std::map<std::string, std::set<std::string>> joints;  // armature -> its joints' names
  for (const tinygltf::Skin& s : m.skins)
    for (const int j : s.joints) joints[m.nodes[std::size_t(s.skeleton)].name].insert(m.nodes[std::size_t(j)].name);
  ASSERT_EQ(joints.size(), 16u);
  for (int p = 0; p < 8; ++p) {
    const std::string name = "pair0" + std::to_string(p);
    EXPECT_TRUE(joints[name + "_horse"].count("DEF-spine.001")) << name << ": the Rigify horse's joints";
    const bool rigify_rider = p == 3 || p == 4 || p == 5 || p == 7;
    EXPECT_EQ(joints[name + "_rider"].count("DEF-spine") == 1, rigify_rider) << name;
  }
  // The bake checks as the scene does: clean.
  const CommandResult file = runStirrup("check " + quote(baked.string()) + " --json");
  EXPECT_EQ(file.exit_code, 0) << file.out << file.err;
  const nlohmann::json f = nlohmann::json::parse(file.out);
  for (const char* rule : {"hoof-slide", "hoof-in-ground", "rider-in-horse", "hand-off-rein", "foot-off-stirrup", "trunk-balance"})
    EXPECT_EQ(f["rules"][rule], c["rules"][rule]) << rule;

  // Pairs 6 and 7 walk as the horse's file keys it, from their slots: every joint moves from frame 1 to
  // frame F as Blender moves it, up and along the ground (the walk placed facing the lead's way is turned
  // by the little its fitted heading differs from it: the moves are compared by their lengths).
  const AnimatedNodes nodes(m);
  ASSERT_EQ(nodes.times.size(), std::size_t(kFrames));
  const nlohmann::json blender = nlohmann::json::parse(readText(horse_dir / "blender.json"));
  const nlohmann::json horse_mapping = nlohmann::json::parse(readText(horse_map));
  const glm::dvec3 fwd(horse_mapping["forward"][0], horse_mapping["forward"][1], horse_mapping["forward"][2]);
  const glm::dvec3 up(horse_mapping["up"][0], horse_mapping["up"][1], horse_mapping["up"][2]);
  const auto toRig = [&](const nlohmann::json& p) {  // a place in glTF metres, in stirrup's axes and cm
    const glm::dvec3 q = glm::dvec3(p[0], p[1], p[2]) * 100.0;
    return glm::dvec3(glm::dot(q, fwd), glm::dot(q, up), glm::dot(q, glm::cross(fwd, up)));
  };
  std::map<int, const nlohmann::json*> by_frame;  // Blender's frame F is the shot's frame F
  for (const nlohmann::json& frame : blender["frames"]) by_frame[frame["frame"].get<int>()] = &frame["joints"];
  ASSERT_TRUE(by_frame.count(1));
  double worst = 0;
  int compared = 0;
  for (const std::string pair : {"pair06_horse", "pair07_horse"}) {
    std::map<std::string, int> node;
    for (const tinygltf::Skin& s : m.skins)
      if (m.nodes[std::size_t(s.skeleton)].name == pair)
        for (const int j : s.joints) node[m.nodes[std::size_t(j)].name] = j;
    for (int f = 2; f <= kFrames; ++f) {
      ASSERT_TRUE(by_frame.count(f)) << "Blender's frame " << f;
      for (const auto& [name, p] : by_frame[f]->items()) {
        ASSERT_TRUE(node.count(name)) << pair << " has no joint " << name;
        const std::size_t key = std::size_t(f - 1);
        const glm::dvec3 moved = (glm::dvec3(nodes.world(node[name], key)[3]) - glm::dvec3(nodes.world(node[name], 0)[3])) * 100.0;
        const glm::dvec3 want = toRig(p) - toRig((*by_frame[1])[name]);
        worst = std::max({worst, std::abs(moved.y - want.y), std::abs(std::hypot(moved.x, moved.z) - std::hypot(want.x, want.z))});
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 2 * (kFrames - 1) * 60);
  EXPECT_LT(worst, 0.5) << "cm";

  // A frame renders (the troop seen whole).
  const CommandResult render = runStirrup("render " + quote(scene.string()) + " --camera persp --frames 12 --preset draft --out " +
                                          quote((dir / "out").string()));
  EXPECT_EQ(render.exit_code, 0) << render.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "troop_persp.0012.png"));
  std::printf("a troop of 8 Rigify horses: clean in the scene and its bake; the own walk as keyed within %.4f cm (%d joint moves)\n",
              worst, compared);
}

}  // namespace
}  // namespace stirrup::test
