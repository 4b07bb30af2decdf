// stirrup bake of a crowd: coarser levels of detail, every pair's armatures and the cameras in one file,
// and what Blender makes of it.
#include <algorithm>
#include <map>
#include <set>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "render/shot.h"
#include "rig/bake.h"
#include "rig/channels.h"
#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/motion/crowd.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "scene/camera.h"
#include "scene/clip_factory.h"
#include "scene/detail_level.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "tests/cli/bake_support.h"
#include "tests/cli/baked_file.h"
#include "tests/cli/blender_script.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// --detail bakes a crowd's meshes coarser: every pair's horse and rider with exactly the vertices of its
// characters built at that level's cell, the same animation to the value, a fraction of the file. A
// single pair, --channels and --rider-only refuse it; 3 is out of range.
TEST(BakeGltf, ACrowdBakesAtACoarserDetail) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_bake_detail";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene_file = dir / "crowd.json";
  std::ofstream(scene_file) << R"({"riders": [
    {"points": [[0, -300], [3000, -300]], "speed": [[0, 300]], "seed": 1, "withers_height_cm": 150},
    {"points": [[0, 300], [3000, 300]], "speed": [[0, 300]], "seed": 2, "rider_height_cm": 185}]})";
  const scene::SceneSpec scene = scene::loadScene(scene_file);
  std::uintmax_t bytes[3] = {};
  std::vector<float> rotations[3];
  for (int level : {0, 2}) {
    SCOPED_TRACE("level " + std::to_string(level));
    const fs::path glb = dir / ("crowd" + std::to_string(level) + ".glb");
    const CommandResult r = runStirrup("bake " + quote(scene_file.string()) + " --frames 1-6 --detail " +
                                       std::to_string(level) + " -o " + quote(glb.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    bytes[level] = fs::file_size(glb);
    const tinygltf::Model model = readGlbModel(glb);
    std::set<int> positions;  // a character's primitives share one POSITION accessor
    for (const tinygltf::Mesh& mesh : model.meshes)
      for (const tinygltf::Primitive& prim : mesh.primitives) positions.insert(prim.attributes.at("POSITION"));
    std::size_t vertices = 0;
    for (int a : positions) vertices += model.accessors.at(std::size_t(a)).count;
    std::size_t built = 0;
    for (const rig::PairSpec& spec : scene.pairs) {
      rig::HorseParams hp = spec.horse();
      rig::RiderParams rp = spec.rider();
      hp.cell *= scene::kDetailCellFactor[level];
      rp.cell *= scene::kDetailCellFactor[level];
      built += writtenVertices(rig::buildHorse(hp).mesh) + writtenVertices(rig::buildRider(rp, hp.mount).mesh);
    }
    EXPECT_EQ(vertices, built);
    ASSERT_EQ(model.animations.size(), 1u);
    rotations[level] = accessorData<float>(model, model.animations[0].samplers[1].output);
  }
  EXPECT_EQ(rotations[0], rotations[2]);
  EXPECT_LT(bytes[2] * 4, bytes[0]) << bytes[2] << " bytes at quarter detail, " << bytes[0] << " at full";
  const CommandResult single = runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json") + " --frames 1-2 --detail 1 -o " +
                                          quote((dir / "trot.glb").string()));
  EXPECT_EQ(single.exit_code, 1);
  EXPECT_EQ(lineCount(single.err), 1u) << single.err;
  EXPECT_NE(single.err.find("--detail 1: expected 0 unless -o bakes a crowd"), std::string::npos) << single.err;
  EXPECT_FALSE(fs::exists(dir / "trot.glb"));
  const CommandResult channels = runStirrup("bake " + quote(scene_file.string()) + " --frames 1-2 --detail 2 --channels " +
                                            quote((dir / "c.csv").string()));
  EXPECT_EQ(channels.exit_code, 1);
  EXPECT_NE(channels.err.find("--detail 2: expected 0"), std::string::npos) << channels.err;
  const CommandResult three = runStirrup("bake " + quote(scene_file.string()) + " --detail 3 -o " + quote((dir / "x.glb").string()));
  EXPECT_NE(three.exit_code, 0);
  EXPECT_NE(three.err.find("--detail"), std::string::npos) << three.err;
}

// Bakes the cavalry (scenes/cavalry.json: 30 pairs) at every 40th frame into `dir`: the glTF and the
// channels, once for the tests below (a bake of 30 pairs at full detail takes half a minute).
struct CavalryBake {
  fs::path dir, glb, csv;
  std::vector<int> frames = {1, 41, 81, 121, 161, 201};
};
CavalryBake bakeCavalry(const std::string& folder) {
  CavalryBake b;
  b.dir = fs::path(STIRRUP_BINARY_DIR) / "test_bake_glb" / folder;
  fs::remove_all(b.dir);
  b.glb = b.dir / "cavalry.glb";
  b.csv = b.dir / "channels" / "cavalry.csv";
  const CommandResult r = runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/cavalry.json") + " --frames 1-240x40 -o " +
                                     quote(b.glb.string()) + " --channels " + quote(b.csv.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return b;
}

// A crowd bakes into one file: two armatures a pair (pair00_horse ... pair29_rider, each a root of
// scale 0.01 that is its skin's skeleton), their joints named as the characters' skeletons name them; each pair's joints at
// every key where the rig's own jobs put them (its clip from rig::makePairClip at the shot's time plus its
// start phase, its profile, its characters at its proportions), so two pairs stand and move apart;
// both cameras, and through each the pairs land within half a pixel of where the render puts them;
// --channels writes one file a pair; the Khronos validator finds no error or warning.
TEST(BakeGltf, ACrowdBakesEveryPairWithItsCameras) {
  const CavalryBake bake = bakeCavalry("cavalry");
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/cavalry.json");
  ASSERT_EQ(scene.pairs.size(), 30u);
  const tinygltf::Model model = readGlbModel(bake.glb);
  const AnimatedNodes nodes(model);
  ASSERT_EQ(model.skins.size(), 60u);
  ASSERT_EQ(model.animations.size(), 1u);
  ASSERT_EQ(nodes.times.size(), bake.frames.size());

  // Each character's own joint names: those the shipped characters' files have (trot.json rides them).
  const tinygltf::Model one = readGlbModel(bakeGlb("trot.json", "1-2"));
  const auto jointNames = [](const tinygltf::Model& m, int skin) {
    std::vector<std::string> names;
    for (int n : m.skins.at(std::size_t(skin)).joints) names.push_back(m.nodes.at(std::size_t(n)).name);
    return names;
  };
  char name[32];
  for (int i = 0; i < 30; ++i) {
    for (int which = 0; which < 2; ++which) {
      std::snprintf(name, sizeof name, "pair%02d_%s", i, which == 0 ? "horse" : "rider");
      const int root = nodeNamed(model, name);
      ASSERT_GE(root, 0) << name;
      EXPECT_EQ(nodes.parent[std::size_t(root)], -1) << name;
      EXPECT_EQ(model.nodes[std::size_t(root)].scale, (std::vector<double>{0.01, 0.01, 0.01})) << name;
      int skin = -1;
      for (std::size_t s = 0; s < model.skins.size(); ++s)
        if (model.skins[s].skeleton == root) skin = int(s);
      ASSERT_GE(skin, 0) << name;
      EXPECT_EQ(model.skins[std::size_t(skin)].name.rfind(name, 0), 0u) << model.skins[std::size_t(skin)].name;
      EXPECT_EQ(jointNames(model, skin), jointNames(one, which)) << name;
    }
  }

  // Pairs 0, 17 and 29 posed here by the rig's own jobs: every joint's world matrix at every key.
  double worst_t = 0.0;
  for (int i : {0, 17, 29}) {
    const rig::PairSpec& spec = scene.pairs[std::size_t(i)];
    scene::SceneSpec named = scene;
    named.profile = spec.profile;
    const rig::RigProfile profile = scene::resolveProfile(named);
    const auto clip = rig::makePairClip(spec, scene.terrain, "test");
    const rig::HorseParams hp = spec.horse();
    const rig::Character horse = rig::buildHorse(hp), rider = rig::buildRider(spec.rider(), hp.mount);
    std::snprintf(name, sizeof name, "pair%02d_", i);
    for (std::size_t k = 0; k < bake.frames.size(); ++k) {
      const double t = (bake.frames[k] - 1) / scene.fps;
      const rig::BakedFrame b = rig::bakeFrame(*clip, profile, bake.frames[k], t + spec.clip_offset_s);
      const rig::MountedPose pose = rig::poseMounted(horse, rider, b.horse, b.rider, profile);
      for (int which = 0; which < 2; ++which) {
        const tinygltf::Skin* skin = nullptr;
        for (const tinygltf::Skin& s : model.skins)
          if (model.nodes[std::size_t(s.skeleton)].name == std::string(name) + (which == 0 ? "horse" : "rider")) skin = &s;
        ASSERT_NE(skin, nullptr);
        const std::vector<glm::mat4>& world = which == 0 ? pose.horse : pose.rider;
        ASSERT_EQ(skin->joints.size(), world.size());
        for (std::size_t j = 0; j < world.size(); ++j) {
          const glm::dmat4 file = nodes.world(skin->joints[j], k);
          worst_t = std::max(worst_t, glm::length(glm::dvec3(file[3]) * 100.0 - glm::dvec3(world[j][3])));
        }
      }
    }
  }
  EXPECT_LT(worst_t, 1e-2) << "cm";

  // Two pairs stand apart and move apart: their horses' roots at a key, and how far each goes between keys.
  const auto horseRoot = [&](int pair, std::size_t key) {
    std::snprintf(name, sizeof name, "pair%02d_horse", pair);
    const int root = nodeNamed(model, name);
    return glm::dvec3(nodes.world(model.nodes[std::size_t(root)].children.at(0), key)[3]) * 100.0;
  };
  EXPECT_GT(glm::length(horseRoot(0, 2) - horseRoot(29, 2)), 400.0);
  EXPECT_GT(glm::length((horseRoot(0, 3) - horseRoot(0, 2)) - (horseRoot(29, 3) - horseRoot(29, 2))), 1.0);

  // Every camera, through which the file's pairs land where the render puts its own (full detail,
  // as Shot::pairPoints gives them): the followed pair for the follow camera; three pairs for the view.
  ASSERT_EQ(model.cameras.size(), 2u);
  const rig::RigProfile profile = scene::resolveProfile(scene);
  for (std::size_t c = 0; c < scene.cameras.size(); ++c) {
    const scene::CameraSpec& spec = scene.cameras[c];
    SCOPED_TRACE("camera " + spec.name);
    render::Shot shot(scene, profile, spec, 0);
    const int node = nodeNamed(model, "camera:" + spec.name);
    ASSERT_GE(node, 0);
    const tinygltf::Camera& cam = model.cameras.at(std::size_t(model.nodes[std::size_t(node)].camera));
    const std::vector<int> pairs = spec.follow_pair >= 0 ? std::vector<int>{spec.follow_pair} : std::vector<int>{0, 17, 29};
    double worst = 0.0;
    std::size_t projected = 0;
    for (std::size_t k : {std::size_t(0), std::size_t(3)}) {
      const scene::Camera rc = shot.cameraAtFrame(bake.frames[k]);
      const glm::dmat4 world = nodes.world(node, k);
      for (int pair : pairs) {
        // Every 25th vertex of the horse's body node and of the rider's, each against the vertex of
        // stirrup's mesh it was written from.
        std::vector<glm::dvec3> all_horse, all_rider, horse, file;
        shot.pairPoints(pair, bake.frames[k], 1, all_horse, all_rider);
        const std::vector<std::uint32_t> body = bodyVertices(shot.characters().horseAt(pair, 0).mesh);
        for (const char* who : {"horse", "rider"}) {
          std::snprintf(name, sizeof name, "pair%02d_%s:%s_mesh", pair, who, who);
          const int mesh = nodeNamed(model, name);
          ASSERT_GE(mesh, 0) << name;
          const std::vector<glm::dvec3> points = nodes.skinned(mesh, k, 1);
          const bool is_horse = who[0] == 'h';
          ASSERT_EQ(points.size(), is_horse ? body.size() : all_rider.size()) << name;
          for (std::size_t v = 0; v < points.size(); v += 25)
            file.push_back(points[v]), horse.push_back(is_horse ? all_horse.at(body[v]) : all_rider[v]);
        }
        for (std::size_t p = 0; p < horse.size(); ++p) {
          const glm::dvec2 a = stirrupPixel(rc, horse[p], scene.width, scene.height);
          const glm::dvec2 b = gltfPixel(cam, world, file[p], scene.width, scene.height);
          worst = std::max(worst, glm::length(a - b));
          ++projected;
        }
      }
    }
    EXPECT_GT(projected, 1000u);
    EXPECT_LT(worst, 0.5) << "pixels, worst point";
    std::printf("cavalry %s: worst %.4f px over %zu points\n", spec.name.c_str(), worst, projected);
  }
  std::printf("cavalry joints: worst %.6f cm\n", worst_t);

  // --channels: one file a pair, each a single pair's CSV with that pair's bake.
  for (int i = 0; i < 30; ++i) {
    std::snprintf(name, sizeof name, "cavalry_pair%02d.csv", i);
    EXPECT_TRUE(fs::exists(bake.csv.parent_path() / name)) << name;
  }
  {
    const rig::PairSpec& spec = scene.pairs[17];
    scene::SceneSpec named = scene;
    named.profile = spec.profile;
    const rig::RigProfile pair_profile = scene::resolveProfile(named);
    const auto clip = rig::makePairClip(spec, scene.terrain, "test");
    std::stringstream csv(readText(bake.csv.parent_path() / "cavalry_pair17.csv"));
    std::string line;
    std::getline(csv, line);
    const std::vector<std::string> header = split(line);
    ASSERT_EQ(header.size(), 2 + rig::kHorseChannelCount + rig::kRiderChannelCount);
    for (int f : bake.frames) {
      ASSERT_TRUE(std::getline(csv, line));
      const std::vector<std::string> cells = split(line);
      ASSERT_EQ(cells.size(), header.size());
      const double t = (f - 1) / scene.fps;
      const rig::BakedFrame b = rig::bakeFrame(*clip, pair_profile, f, t + spec.clip_offset_s);
      EXPECT_EQ(std::stod(cells[0]), f);
      EXPECT_EQ(std::stod(cells[1]), t);
      for (std::size_t c = 0; c < rig::kHorseChannelCount; ++c) EXPECT_EQ(std::stod(cells[2 + c]), b.horse.controls.value[c]);
      for (std::size_t c = 0; c < rig::kRiderChannelCount; ++c)
        EXPECT_EQ(std::stod(cells[2 + rig::kHorseChannelCount + c]), b.rider.value[c]);
    }
  }

  bool skipped = false;
  const std::string problems = validatorProblems(bake.glb, skipped);
  if (skipped) GTEST_SKIP() << problems << " (the file was checked)";
  EXPECT_EQ(problems, "");
}

// What Blender 3.4 makes of a baked file (headless): every armature object with its action; the world
// place of each asked armature's bone at each asked Blender frame; and asked points (Blender's world:
// metres, Z up) projected through asked cameras at asked frames, Blender's way (world_to_camera_view
// at the camera's extras width x height), as pixels.
constexpr const char* kBlenderReadBake = R"(
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector
glb, ask, answer = args
import_glb(glb)
scene = bpy.context.scene
ask = json.load(open(ask))
out = {"armatures": {}, "bones": {}, "pixels": []}
for o in bpy.data.objects:
    if o.type == "ARMATURE":
        ad = o.animation_data
        out["armatures"][o.name] = ad.action.name if ad and ad.action else None
for f in ask["frames"]:
    scene.frame_set(f)
    for name in ask["armatures"]:
        o = bpy.data.objects[name]
        p = o.matrix_world @ o.pose.bones[ask["bone"]].head
        out["bones"].setdefault(name, []).append([p.x, p.y, p.z])
for job in ask["projections"]:
    scene.frame_set(job["frame"])
    cam = bpy.data.objects[job["camera"]]
    w, h = job["width"], job["height"]
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = w, h, 100
    px = []
    for p in job["points"]:
        a = world_to_camera_view(scene, cam, Vector(p))
        px.append([a.x * w, (1 - a.y) * h])
    out["pixels"].append(px)
json.dump(out, open(answer, "w"))
)";

// Blender 3.4 opens the cavalry's bake as 60 armatures (pair00_horse ... pair29_rider), each with its
// own action; two pairs' horses stand apart and move differently (each within a millimetre of where the
// file's own keys put it); and through each imported camera, the followed pair (pair 17, and for the
// crowd's view pairs 0 and 29 too) lands within half a pixel of where stirrup's render camera puts it.
TEST(BakeGltf, BlenderOpensACrowdBakeAsItsArmatures) {
  if (!blenderInstalled()) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)";
  const CavalryBake bake = bakeCavalry("cavalry_blender");
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/cavalry.json");
  const tinygltf::Model model = readGlbModel(bake.glb);
  const AnimatedNodes nodes(model);
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const std::vector<std::size_t> keys = {1, 4};  // stirrup frames 41 and 161: Blender frames 40 and 160
  const auto blender = [](const glm::dvec3& gltf_m) { return glm::dvec3(gltf_m.x, -gltf_m.z, gltf_m.y); };

  nlohmann::json ask = {{"frames", nlohmann::json::array()}, {"armatures", {"pair00_horse", "pair29_horse"}},
                        {"bone", "root"}, {"projections", nlohmann::json::array()}};
  for (std::size_t k : keys) ask["frames"].push_back(bake.frames[k] - 1);
  std::vector<std::vector<glm::dvec2>> expected;  // stirrup's pixels, one list a projection
  for (const scene::CameraSpec& spec : scene.cameras) {
    render::Shot shot(scene, profile, spec, 0);
    for (std::size_t k : keys) {
      const scene::Camera rc = shot.cameraAtFrame(bake.frames[k]);
      nlohmann::json points = nlohmann::json::array();
      std::vector<glm::dvec2> pixels;
      for (int pair : spec.follow_pair >= 0 ? std::vector<int>{spec.follow_pair} : std::vector<int>{0, 17, 29}) {
        std::vector<glm::dvec3> horse, rider;
        shot.pairPoints(pair, bake.frames[k], 40, horse, rider);
        horse.insert(horse.end(), rider.begin(), rider.end());
        for (const glm::dvec3& p : horse) {
          const glm::dvec3 b = blender(p * 0.01);
          points.push_back({b.x, b.y, b.z});
          pixels.push_back(stirrupPixel(rc, p, scene.width, scene.height));
        }
      }
      ask["projections"].push_back({{"camera", "camera:" + spec.name}, {"frame", bake.frames[k] - 1}, {"width", scene.width},
                                    {"height", scene.height}, {"points", points}});
      expected.push_back(pixels);
    }
  }
  const fs::path ask_file = bake.dir / "ask.json", answer_file = bake.dir / "answer.json", script = bake.dir / "read_bake.py";
  std::ofstream(ask_file) << ask.dump();
  const CommandResult r = runBlenderScript(script, kBlenderReadBake,
                                           quote(bake.glb.string()) + " " + quote(ask_file.string()) + " " + quote(answer_file.string()) +
                                               " >/dev/null 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(answer_file)) << "Blender wrote no answer";
  const nlohmann::json answer = nlohmann::json::parse(readText(answer_file));

  // 60 armatures, pair by pair, each with an action of its own.
  std::set<std::string> armatures, actions;
  for (const auto& [name, action] : answer["armatures"].items()) {
    armatures.insert(name);
    if (action.is_string()) actions.insert(action.get<std::string>());
  }
  std::set<std::string> expected_armatures;
  char name[32];
  for (int i = 0; i < 30; ++i)
    for (const char* who : {"horse", "rider"}) {
      std::snprintf(name, sizeof name, "pair%02d_%s", i, who);
      expected_armatures.insert(name);
    }
  EXPECT_EQ(armatures, expected_armatures);
  EXPECT_EQ(actions.size(), 60u) << "one action an armature";

  // The horses' root bones where the file's keys put them, apart, and moving differently.
  std::vector<std::vector<glm::dvec3>> roots;  // [pair 0, pair 29][key], Blender metres
  for (const char* armature : {"pair00_horse", "pair29_horse"}) {
    const int root = nodeNamed(model, armature);
    ASSERT_GE(root, 0);
    const int joint = model.nodes[std::size_t(root)].children.at(0);
    ASSERT_EQ(model.nodes[std::size_t(joint)].name, "root");
    roots.emplace_back();
    for (std::size_t n = 0; n < keys.size(); ++n) {
      const nlohmann::json& p = answer["bones"][armature][n];
      const glm::dvec3 in_blender(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
      EXPECT_LT(glm::length(in_blender - blender(glm::dvec3(nodes.world(joint, keys[n])[3]))), 1e-3) << armature << " key " << n;
      roots.back().push_back(in_blender);
    }
  }
  EXPECT_GT(glm::length(roots[0][0] - roots[1][0]), 4.0) << "metres apart";
  EXPECT_GT(glm::length((roots[0][1] - roots[0][0]) - (roots[1][1] - roots[1][0])), 0.01) << "metres: they move differently";

  // Through Blender's cameras, where stirrup's render puts the pairs.
  ASSERT_EQ(answer["pixels"].size(), expected.size());
  double worst = 0.0;
  std::size_t projected = 0;
  for (std::size_t j = 0; j < expected.size(); ++j) {
    ASSERT_EQ(answer["pixels"][j].size(), expected[j].size());
    for (std::size_t p = 0; p < expected[j].size(); ++p) {
      const glm::dvec2 b(answer["pixels"][j][p][0].get<double>(), answer["pixels"][j][p][1].get<double>());
      worst = std::max(worst, glm::length(b - expected[j][p]));
      ++projected;
    }
  }
  EXPECT_GT(projected, 1000u);
  EXPECT_LT(worst, 0.5) << "pixels, worst point";
  std::printf("cavalry in Blender: %zu armatures, worst %.4f px over %zu points\n", armatures.size(), worst, projected);
}

}  // namespace
}  // namespace stirrup::test
