// stirrup bake with a user's characters: a textured horse keeps its texture, a user's rider her joints'
// names.
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

#include "rig/characters/horse_tack.h"
#include "tests/cli/baked_file.h"
#include "tests/cli/run_command.h"
#include "tests/cli/bake_support.h"
#include "tests/cli/own_horse_bake.h"
#include "tests/fox_horse.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// A textured user horse (the Khronos Fox, its joints mapped to the horse roles) baked with the
// default rider: the file holds the Fox's image (its PNG bytes as the Fox holds them), a horse
// material whose base colour texture is that image, TEXCOORD_0 on every horse vertex, and an
// untextured rider as before; the Khronos validator finds no errors or warnings in it.
TEST(BakeGltf, ATexturedUserHorseKeepsItsTexture) {
  const fs::path fox = stirrup::test::foxGlb();
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_bake_glb" / "fox_horse";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "fox-horse.json") << stirrup::test::foxHorseMapping().dump(1);
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(STIRRUP_SOURCE_DIR "/scenes/walk.json"));
  scene["characters"] = {{"horse", {{"file", fox.string()}, {"mapping", "fox-horse.json"}}}, {"rider", "default"}};
  std::ofstream(dir / "fox_walk.json") << scene.dump(1);
  const fs::path glb = dir / "fox_walk.glb";
  const CommandResult r = runStirrup("bake " + quote((dir / "fox_walk.json").string()) + " --frames 1-12 -o " + quote(glb.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const tinygltf::Model model = readGlbModel(glb);
  tinygltf::Model source;
  {
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&source, &err, &warn, fox.string())) << err;
  }
  const auto viewBytes = [](const tinygltf::Model& m, int view) {
    const tinygltf::BufferView& v = m.bufferViews.at(std::size_t(view));
    const auto* p = m.buffers.at(std::size_t(v.buffer)).data.data() + v.byteOffset;
    return std::vector<unsigned char>(p, p + v.byteLength);
  };
  ASSERT_EQ(model.images.size(), 1u);
  EXPECT_EQ(model.images[0].mimeType, "image/png");
  EXPECT_EQ(viewBytes(model, model.images[0].bufferView), viewBytes(source, source.images.at(0).bufferView));
  const int horse_node = nodeNamed(model, "horse:horse_mesh"), rider_node = nodeNamed(model, "rider:rider_mesh");
  ASSERT_GE(horse_node, 0);
  ASSERT_GE(rider_node, 0);
  const tinygltf::Mesh& horse = model.meshes.at(std::size_t(model.nodes[horse_node].mesh));
  ASSERT_EQ(horse.primitives.size(), 1u);  // the Fox: one material
  const tinygltf::Primitive& prim = horse.primitives[0];
  const int texture = model.materials.at(std::size_t(prim.material)).pbrMetallicRoughness.baseColorTexture.index;
  ASSERT_GE(texture, 0);
  EXPECT_EQ(model.textures.at(std::size_t(texture)).source, 0);
  ASSERT_TRUE(prim.attributes.count("TEXCOORD_0"));
  EXPECT_EQ(model.accessors.at(std::size_t(prim.attributes.at("TEXCOORD_0"))).count,
            model.accessors.at(std::size_t(prim.attributes.at("POSITION"))).count);
  for (const tinygltf::Primitive& p : model.meshes.at(std::size_t(model.nodes[rider_node].mesh)).primitives) {
    EXPECT_FALSE(p.attributes.count("TEXCOORD_0"));
    EXPECT_LT(model.materials.at(std::size_t(p.material)).pbrMetallicRoughness.baseColorTexture.index, 0);
  }

  bool skipped = false;
  const std::string problems = validatorProblems(glb, skipped);
  if (skipped) GTEST_SKIP() << problems << " (the file was checked)";
  EXPECT_EQ(problems, "");
}

// A user's rider keeps her joints' names in both bakes: the file's own, not the roles they play, with
// no prefix, and a joint two roles share (a wrist that is also the hand) named once, as the file
// names it. The full bake adds only the rig's own points (stirrup_*); --rider-only writes the file's
// joints alone.
TEST(BakeGltf, AUsersRiderKeepsHerJointNames) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_bake_glb" / "user_names";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path glb = dir / "rider.glb", mapping = dir / "rider-map.json";
  ASSERT_EQ(runStirrup("character make humanoid --names mixamo --pose a --shared-wrist-hand -o " + quote(glb.string())).exit_code, 0);
  const CommandResult mapped = runStirrup("character map " + quote(glb.string()) + " --as rider -o " + quote(mapping.string()));
  ASSERT_EQ(mapped.exit_code, 0) << mapped.err;
  // The file's wrist is its hand: the mapping names it for both roles, as a user may write it.
  nlohmann::json map = nlohmann::json::parse(std::ifstream(mapping));
  nlohmann::json& roles = map["roles"];
  roles["lHand"] = roles["lWrist"];
  roles["rHand"] = roles["rWrist"];
  std::ofstream(mapping) << map.dump(1);
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(STIRRUP_SOURCE_DIR "/scenes/trot.json"));
  scene["characters"] = {{"horse", "default"}, {"rider", {{"file", glb.string()}, {"mapping", mapping.string()}}}};
  std::ofstream(dir / "trot.json") << scene.dump(1);
  std::set<std::string> file_joints;
  {
    const tinygltf::Model source = readGlbModel(glb);
    for (const int n : source.skins.at(0).joints) file_joints.insert(source.nodes.at(std::size_t(n)).name);
  }
  ASSERT_TRUE(file_joints.count(roles["lWrist"].get<std::string>()));
  const auto skinJoints = [](const tinygltf::Model& m, int skin) {
    std::set<std::string> names;
    for (const int n : m.skins.at(std::size_t(skin)).joints) names.insert(m.nodes.at(std::size_t(n)).name);
    return names;
  };

  CommandResult r = runStirrup("bake " + quote((dir / "trot.json").string()) + " --frames 1-6 -o " + quote((dir / "shot.glb").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tinygltf::Model shot = readGlbModel(dir / "shot.glb");
  ASSERT_EQ(shot.skins.size(), 2u);
  const int rider_skin = shot.skins[0].name.rfind("rider:", 0) == 0 ? 0 : 1;
  std::set<std::string> rig_points;
  for (const std::string& name : skinJoints(shot, rider_skin))
    if (!file_joints.count(name)) rig_points.insert(name);
  for (const std::string& name : rig_points) EXPECT_EQ(name.rfind("stirrup_", 0), 0u) << name << " is neither hers nor a rig point";
  std::set<std::string> written = skinJoints(shot, rider_skin);
  for (const std::string& name : file_joints) EXPECT_TRUE(written.count(name)) << name << " lost its name in the bake";

  r = runStirrup("bake " + quote((dir / "trot.json").string()) + " --frames 1-6 --rider-only -o " + quote((dir / "motion.glb").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(skinJoints(readGlbModel(dir / "motion.glb"), 0), file_joints);
}

// A user's horse (Blender's Rigify horse, no tack of its own) baked whole: the tack the rig made for it is
// a mesh node a part beside the body's, each skinned by the horse's skin, saying which horse it fits (its
// armature and its file), in the rig's tack colours; the tack's rig points are joints of the horse's skin,
// keyed at every frame; the Khronos validator finds nothing wrong. `stirrup check` of the file reads the
// whole horse back and measures her hands on the reins and her feet in the irons: clean, none unmeasured.
TEST(BakeGltf, AUsersHorseGetsItsTackAsAPartANodeAndIsCheckedAtHandsAndFeet) {
  if (!blenderInstalled()) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)";
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_bake_glb" / "own_horse_tack";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const OwnHorseBake own = bakeOwnHorse(dir);
  ASSERT_FALSE(own.baked.empty()) << own.why;
  const tinygltf::Model model = readGlbModel(own.baked);
  const AnimatedNodes nodes(model);
  const int horse_root = nodeNamed(model, "horse");
  ASSERT_GE(horse_root, 0);
  int skin = -1;
  for (std::size_t k = 0; k < model.skins.size(); ++k)
    if (model.skins[k].skeleton == horse_root) skin = int(k);
  ASSERT_GE(skin, 0);
  const std::vector<int>& joints = model.skins[std::size_t(skin)].joints;
  for (const char* tack : {"saddle", "lStirrup", "rStirrup", "lRein", "rRein"}) {
    const auto j = std::find_if(joints.begin(), joints.end(), [&](int n) { return model.nodes[std::size_t(n)].name == tack; });
    ASSERT_NE(j, joints.end()) << tack << " is not a joint of the horse's skin";
    EXPECT_TRUE(nodes.keys.count({*j, "translation"})) << tack << " is not keyed";
  }
  const rig::HorseTackParams tack_params;
  std::size_t parts = 0, tack_vertices = 0;
  for (const tinygltf::Node& node : model.nodes) {
    if (node.skin != skin || node.name == "horse:horse_mesh") continue;
    ++parts;
    EXPECT_EQ(node.extras.Get("stirrup_tack").Get<std::string>(), node.name);
    EXPECT_EQ(node.extras.Get("stirrup_fits").Get<std::string>(), "horse");
    EXPECT_EQ(node.extras.Get("stirrup_fits_file").Get<std::string>(), own.horse.string());
    for (const tinygltf::Primitive& prim : model.meshes.at(std::size_t(node.mesh)).primitives) {
      tack_vertices += model.accessors.at(std::size_t(prim.attributes.at("POSITION"))).count;
      const std::vector<double>& c = model.materials.at(std::size_t(prim.material)).pbrMetallicRoughness.baseColorFactor;
      const glm::vec3 colour{float(c[0]), float(c[1]), float(c[2])};
      EXPECT_TRUE(colour == tack_params.leather || colour == tack_params.pad || colour == tack_params.metal) << node.name;
    }
  }
  EXPECT_EQ(parts, 9u) << "saddle, saddle pad, bridle, bit, two leathers, two irons, reins";
  std::printf("the Rigify horse's tack: %zu parts, %zu vertices\n", parts, tack_vertices);
  bool skipped = false;
  const std::string problems = validatorProblems(own.baked, skipped);
  EXPECT_TRUE(skipped || problems.empty()) << problems;

  const CommandResult check = runStirrup("check " + quote(own.baked.string()) + " --json");
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  const nlohmann::json report = nlohmann::json::parse(check.out);
  for (const nlohmann::json& u : report["unmeasured"]) {
    EXPECT_NE(u["rule"], "hand-off-rein") << u.dump();
    EXPECT_NE(u["rule"], "foot-off-stirrup") << u.dump();
  }
  for (const char* rule : {"hand-off-rein", "foot-off-stirrup", "rider-in-horse"}) EXPECT_TRUE(report["rules"].contains(rule)) << rule;
  EXPECT_EQ(report["failures"], 0) << check.out;
}

}  // namespace
}  // namespace stirrup::test
