// stirrup character make: the default characters the build makes (scenes/characters/*.glb) are the
// generator's output byte for byte, made the same twice, and bad parameters
// are one-line errors. `character make humanoid` (standing test characters in other tools' style)
// writes files the Khronos validator passes, shaped by its options, byte for byte the same each run.
// tests/blender/rigify-rider, where Blender is installed, makes a rider in Blender itself (Rigify's
// human meta-rig, generated, skinned, textured) and this file checks what it exported. `character map`
// prints what it chose, writes a mapping file the importer takes, renders its preview through the
// normal pipeline, and says in one line what it cannot do; a scene naming a file alone maps it on load.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <OpenImageIO/imageio.h>

#include "rig/io/character_mapping_json.h"
#include "rig/io/gltf_character.h"
#include "rig/mapping/character_mapping.h"
#include "tests/cli/run_command.h"
#include "tests/test_files.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

std::vector<char> readBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

fs::path tempDir(const std::string& name) { return stirrup::test::freshTestDir("test_character", name); }

// The build made scenes/characters/KIND.glb (CMakeLists.txt, the `characters` target); two more runs of the
// generator make the same bytes as each other and as the build's file (what the build makes is all there
// is: the goldens pin how it looks).
void expectTheBuildsCharacterIsTheGenerators(const std::string& kind) {
  const fs::path built = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "characters" / (kind + ".glb");
  ASSERT_TRUE(fs::is_regular_file(built)) << built << ": the build makes it (the characters target)";
  std::vector<std::vector<char>> made;
  for (const char* run : {"a", "b"}) {
    const fs::path out = tempDir(kind + run) / (kind + ".glb");
    const CommandResult r = runStirrup("character make " + kind + " -o " + quote(out.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    made.push_back(readBytes(out));
    // No temporary file is left behind.
    EXPECT_EQ(std::distance(fs::directory_iterator(out.parent_path()), fs::directory_iterator()), 1);
  }
  EXPECT_GT(made[0].size(), 100000u);
  EXPECT_LT(made[0].size(), 4u << 20);  // a few MB at most
  EXPECT_TRUE(made[0] == made[1]) << kind << ": two runs of the generator made different bytes";
  EXPECT_TRUE(made[0] == readBytes(built)) << built << " differs from what the generator makes (rebuild: the characters target)";
}

TEST(CharacterMake, TheBuildsHorseIsTheGeneratorsByteForByte) { expectTheBuildsCharacterIsTheGenerators("horse"); }
TEST(CharacterMake, TheBuildsRiderIsTheGeneratorsByteForByte) { expectTheBuildsCharacterIsTheGenerators("rider"); }

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

// ---- character make humanoid

// The Khronos validator's one-line JSON report on a file (tests/cli/validate_gltf.js), or "" with
// a skip reason.
std::string validate(const fs::path& glb, std::string& skip) {
  if (runCommand("command -v node >/dev/null").exit_code != 0) {
    skip = "node is not installed";
    return "";
  }
  fs::path modules = fs::path(STIRRUP_BINARY_DIR) / "tools" / "node_modules";
  if (!fs::exists(modules / "gltf-validator")) modules = fs::path(STIRRUP_SOURCE_DIR) / "build" / "tools" / "node_modules";
  if (!fs::exists(modules / "gltf-validator")) {
    skip = "gltf-validator is not installed: run scripts/setup";
    return "";
  }
  const CommandResult v = runCommand("node " + quote(STIRRUP_SOURCE_DIR "/tests/cli/validate_gltf.js") + " " +
                                     quote(modules.string()) + " " + quote(glb.string()));
  EXPECT_EQ(v.exit_code, 0) << v.err;
  return v.out;
}

// Every convention, every rest pose and the layout options: no errors, no warnings; VRM's one info is
// the validator not knowing VRMC_vrm (UNSUPPORTED_EXTENSION).
TEST(CharacterMakeHumanoid, FilesPassTheKhronosValidator) {
  const fs::path dir = tempDir("humanoid_valid");
  const std::vector<std::string> variants = {
      "--names mixamo",
      "--names rigify --pose a --spine-joints 6 --cell 3",
      "--names unreal --pose relaxed --shared-wrist-hand --no-toes --cell 3",
      "--names vrm --spine-joints 2 --cell 3",
      "--names humanik --neck-joints 2 --split-limbs --no-clavicles --cell 3",
      "--names none --seed 5 --end-joints --joint-axes world --no-fingers --cell 3"};
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const fs::path out = dir / ("v" + std::to_string(i) + ".glb");
    const CommandResult r = runStirrup("character make humanoid " + variants[i] + " -o " + quote(out.string()));
    ASSERT_EQ(r.exit_code, 0) << variants[i] << ": " << r.err;
    std::string skip;
    const std::string report = validate(out, skip);
    if (!skip.empty()) GTEST_SKIP() << skip;
    EXPECT_NE(report.find("\"errors\":0,"), std::string::npos) << variants[i] << ": " << report;
    EXPECT_NE(report.find("\"warnings\":0,"), std::string::npos) << variants[i] << ": " << report;
    const bool vrm = variants[i].find("vrm") != std::string::npos;
    EXPECT_NE(report.find(vrm ? "\"infos\":1," : "\"infos\":0,"), std::string::npos) << variants[i] << ": " << report;
  }
}

struct WrittenHumanoid {
  tinygltf::Model model;
  std::map<std::string, int> node;
  std::vector<int> parent;
  glm::dvec3 world(const std::string& name) const {
    glm::dmat4 m(1.0);
    for (int n = node.at(name); n >= 0; n = parent[n]) {
      const tinygltf::Node& nd = model.nodes[n];
      glm::dmat4 l(1.0);
      if (nd.translation.size() == 3) l = glm::translate(l, glm::dvec3(nd.translation[0], nd.translation[1], nd.translation[2]));
      if (nd.rotation.size() == 4) l *= glm::mat4_cast(glm::dquat(nd.rotation[3], nd.rotation[0], nd.rotation[1], nd.rotation[2]));
      m = l * m;
    }
    return glm::dvec3(m[3]);
  }
  // Joints strictly between `from` and its ancestor `to`.
  int between(const std::string& from, const std::string& to) const {
    int n = 0;
    for (int p = parent[node.at(from)]; p >= 0; p = parent[p], ++n)
      if (model.nodes[p].name == to) return n;
    return -1;
  }
};

WrittenHumanoid makeHumanoid(const std::string& options, const std::string& name) {
  const fs::path out = tempDir("humanoid_" + name) / (name + ".glb");
  const CommandResult r = runStirrup("character make humanoid " + options + " -o " + quote(out.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("standing humanoid"), std::string::npos) << r.out;
  WrittenHumanoid h;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&h.model, &err, &warn, out.string())) << err;
  h.parent.assign(h.model.nodes.size(), -1);
  for (std::size_t i = 0; i < h.model.nodes.size(); ++i) {
    h.node[h.model.nodes[i].name] = static_cast<int>(i);
    for (int c : h.model.nodes[i].children) h.parent[c] = static_cast<int>(i);
  }
  return h;
}

TEST(CharacterMakeHumanoid, OptionsShapeTheWrittenSkeleton) {
  {  // --spine-joints 6: six joints from the pelvis to the neck, each with Mixamo's prefix.
    const WrittenHumanoid h = makeHumanoid("--names mixamo --spine-joints 6 --cell 4", "spine6");
    EXPECT_EQ(h.between("mixamorig:Neck", "mixamorig:Hips"), 6);
    EXPECT_TRUE(h.node.count("mixamorig:Spine5"));
    for (int j : h.model.skins.at(0).joints) EXPECT_EQ(h.model.nodes[j].name.rfind("mixamorig:", 0), 0u);
    EXPECT_EQ(h.model.skins.at(0).joints.size(), 46u);  // 43 with three spine joints, three more
  }
  {  // --shared-wrist-hand: no hand joint in the palm; the finger hangs from the hand at the wrist.
    const WrittenHumanoid h = makeHumanoid("--names mixamo --shared-wrist-hand --no-toes --cell 4", "shared");
    EXPECT_FALSE(h.node.count("mixamorig:LeftInHandMiddle"));
    EXPECT_EQ(h.model.nodes[h.parent[h.node.at("mixamorig:LeftHandIndex1")]].name, "mixamorig:LeftHand");
    EXPECT_FALSE(h.node.count("mixamorig:LeftToeBase"));
    EXPECT_EQ(h.model.nodes[h.parent[h.node.at("mixamorig:LeftToe_End")]].name, "mixamorig:LeftFoot");
  }
  {  // --names rigify --pose a --height 180: DEF- bones, arms 45 degrees down, the head 0.9 x 1.80 m up.
    const WrittenHumanoid h = makeHumanoid("--names rigify --pose a --height 180 --cell 4", "rigify_a");
    const glm::dvec3 d = h.world("DEF-forearm.L") - h.world("DEF-upper_arm.L");
    EXPECT_NEAR(std::asin(-d.y / glm::length(d)) * 180.0 / 3.14159265358979, 45.0, 0.05);
    EXPECT_NEAR(glm::length(d), 0.186 * 1.80, 1e-5);
    EXPECT_NEAR(h.world("DEF-spine.006").y, 0.9 * 1.80, 1e-5);
    EXPECT_EQ(h.model.nodes[h.parent[h.node.at("DEF-spine.006")]].name, "DEF-spine.005");
  }
}

TEST(CharacterMakeHumanoid, SameOptionsSameBytes) {
  const fs::path dir = tempDir("humanoid_bytes");
  const std::string opts = "character make humanoid --names vrm --pose relaxed --seed 3 --cell 3 -o ";
  ASSERT_EQ(runStirrup(opts + quote((dir / "a.glb").string())).exit_code, 0);
  ASSERT_EQ(runStirrup(opts + quote((dir / "b.glb").string())).exit_code, 0);
  ASSERT_EQ(runStirrup("character make humanoid --names vrm --pose relaxed --cell 3 -o " + quote((dir / "c.glb").string())).exit_code, 0);
  EXPECT_TRUE(readBytes(dir / "a.glb") == readBytes(dir / "b.glb"));
  EXPECT_FALSE(readBytes(dir / "a.glb") == readBytes(dir / "c.glb"));  // the seed changes the character
}

TEST(CharacterMakeHumanoid, BadOptionsAreOneLineErrors) {
  const fs::path out = tempDir("humanoid_bad") / "x.glb";
  const std::string cmd = "character make humanoid: ";
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--pose x", "--pose: expected t, a or relaxed, got \"x\""},
           {"--spine-joints 9", "--spine-joints: expected a whole number 1..8, got \"9\""},
           {"--spine-joints 2.5", "--spine-joints: expected a whole number 1..8, got \"2.5\""},
           {"--neck-joints 0", "--neck-joints: expected a whole number 1..2, got \"0\""},
           {"--names maya", "--names: expected mixamo, rigify, unreal, vrm, humanik or none, got \"maya\""},
           {"--height 20", "--height: expected a number 100..250, got \"20\""},
           {"--joint-axes up", "--joint-axes: expected bone or world, got \"up\""},
           {"--spines 3", "--spines: unknown option"},
           {"--pose", "--pose: expected a value"}}) {
    const CommandResult r = runStirrup("character make humanoid " + args + " -o " + quote(out.string()));
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err.rfind("stirrup: " + cmd + expected, 0), 0u) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const CommandResult help = runStirrup("character make --help");
  EXPECT_NE(help.out.find("--shared-wrist-hand"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--names mixamo|rigify|unreal|vrm|humanik|none"), std::string::npos);
}

// ---- tests/blender/rigify-rider: a rider from Blender's own Rigify, exported by Blender's glTF exporter.
TEST(CharacterBlenderRigify, ExportsAnUprightTexturedRiderSkinnedToDefBones) {
  if (runCommand("command -v blender >/dev/null").exit_code != 0)
    GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy): the Rigify rider is not made";
  const fs::path out = tempDir("blender_rigify") / "rigify-rider.glb";
  const CommandResult r = runCommand(quote(STIRRUP_SOURCE_DIR "/tests/blender/rigify-rider") + " " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("rigify-rider: wrote"), std::string::npos) << r.out;
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, out.string())) << err;

  // One skin, every joint one of Rigify's deform bones.
  ASSERT_EQ(m.skins.size(), 1u);
  std::map<std::string, int> joint;
  for (int j : m.skins[0].joints) {
    EXPECT_EQ(m.nodes[j].name.rfind("DEF-", 0), 0u) << m.nodes[j].name;
    joint[m.nodes[j].name] = j;
  }
  for (const char* name : {"DEF-spine", "DEF-spine.001", "DEF-spine.003", "DEF-spine.004", "DEF-spine.006", "DEF-shoulder.L",
                           "DEF-upper_arm.L", "DEF-upper_arm.L.001", "DEF-forearm.L", "DEF-forearm.L.001", "DEF-hand.L",
                           "DEF-thigh.L", "DEF-thigh.L.001", "DEF-shin.L", "DEF-shin.L.001", "DEF-foot.L", "DEF-toe.L",
                           "DEF-thigh.R", "DEF-hand.R", "DEF-toe.R"})
    EXPECT_TRUE(joint.count(name)) << name;

  // World positions of the joints from the file's own transforms.
  std::vector<int> parent(m.nodes.size(), -1);
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    for (int c : m.nodes[i].children) parent[c] = static_cast<int>(i);
  const auto world = [&](const std::string& name) {
    glm::dmat4 w(1.0);
    for (int n = joint.at(name); n >= 0; n = parent[n]) {
      const tinygltf::Node& nd = m.nodes[n];
      glm::dmat4 l(1.0);
      if (nd.translation.size() == 3) l = glm::translate(l, glm::dvec3(nd.translation[0], nd.translation[1], nd.translation[2]));
      if (nd.rotation.size() == 4) l *= glm::mat4_cast(glm::dquat(nd.rotation[3], nd.rotation[0], nd.rotation[1], nd.rotation[2]));
      if (nd.scale.size() == 3) l = glm::scale(l, glm::dvec3(nd.scale[0], nd.scale[1], nd.scale[2]));
      w = l * w;
    }
    return glm::dvec3(w[3]);
  };
  // Upright (+Y up): head above the hips above the feet; the toes ahead of the ankles (+Z); the
  // left side at +X.
  EXPECT_GT(world("DEF-spine.006").y, world("DEF-spine").y + 0.5);
  EXPECT_GT(world("DEF-spine").y, world("DEF-foot.L").y + 0.6);
  EXPECT_GT(world("DEF-toe.L").z, world("DEF-foot.L").z + 0.05);
  EXPECT_GT(world("DEF-thigh.L").x, 0.05);
  EXPECT_LT(world("DEF-thigh.R").x, -0.05);

  // A skinned, textured mesh: 1.5-2.2 m tall, feet near the ground.
  int skinned = 0;
  double lo = 1e9, hi = -1e9;
  for (const tinygltf::Node& n : m.nodes) {
    if (n.mesh < 0 || n.skin != 0) continue;
    for (const tinygltf::Primitive& p : m.meshes[n.mesh].primitives) {
      ++skinned;
      for (const char* a : {"POSITION", "NORMAL", "TEXCOORD_0", "JOINTS_0", "WEIGHTS_0"}) EXPECT_TRUE(p.attributes.count(a)) << a;
      const tinygltf::Accessor& pos = m.accessors.at(p.attributes.at("POSITION"));
      lo = std::min(lo, pos.minValues.at(1));
      hi = std::max(hi, pos.maxValues.at(1));
      ASSERT_GE(p.material, 0);
      const int tex = m.materials.at(p.material).pbrMetallicRoughness.baseColorTexture.index;
      ASSERT_GE(tex, 0);
      const tinygltf::Image& img = m.images.at(m.textures.at(tex).source);
      EXPECT_GT(img.width, 0);
      EXPECT_FALSE(img.image.empty());  // decoded
    }
  }
  EXPECT_GT(skinned, 0);
  EXPECT_GE(hi - lo, 1.5);
  EXPECT_LE(hi - lo, 2.2);
  EXPECT_NEAR(lo, 0.0, 0.05);
}

// ---- character map

fs::path makeMixamoRider(const fs::path& dir) {
  const fs::path glb = dir / "mixamo-rider.glb";
  const CommandResult r = runStirrup("character make humanoid --names mixamo --pose relaxed --cell 4 -o " + quote(glb.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return glb;
}

TEST(CharacterMap, SaysWhatItChoseAndWritesAMappingTheImporterTakes) {
  const fs::path dir = tempDir("map");
  const fs::path glb = makeMixamoRider(dir), json = dir / "rider.json";
  const CommandResult r = runStirrup("character map " + quote(glb.string()) + " --as rider -o " + quote(json.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // quiet but for the report
  EXPECT_EQ(r.out.rfind(glb.string() + " as a rider: mixamo joint names\n", 0), 0u) << r.out;
  for (const char* line : {"  up       +Y  (from the ankles up to the head)\n", "  forward  +Z  (the toes point ahead of the ankles)\n",
                           "    lShoulder   mixamorig:LeftArm            name\n",
                           "    upperChest  mixamorig:Spine2             hierarchy: the spine joint both shoulders hang from\n",
                           "  optional, left to the rig: lowerBack waist chest braid1 braid2 braid3 coatTail\n"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << " in:\n" << r.out;
  EXPECT_NE(r.out.find("100.00 cm per file unit  (height 1.6"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote " + json.string() + "\n"), std::string::npos) << r.out;
  // The file: the importer's own format, which it reads back and loads the character through.
  const rig::CharacterMapping m = rig::loadCharacterMapping(json, rig::CharacterKind::Rider);
  EXPECT_EQ(m.scale_cm, 100.0);
  EXPECT_EQ(m.forward, (std::array<double, 3>{0, 0, 1}));
  EXPECT_EQ(m.roles.at("lHand"), "mixamorig:LeftInHandMiddle");
  EXPECT_EQ(m.roles.size(), 20u);
  const rig::Character c = rig::loadCharacterGltf(glb, rig::CharacterKind::Rider, &m);
  EXPECT_EQ(c.skeleton.joints[c.role("rKnee")].name, "mixamorig:RightLeg");
  const std::string text = readText(json);
  EXPECT_NE(text.find("  \"forward\": [0.0,0.0,1.0],\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    \"pelvis\": \"mixamorig:Hips\",\n"), std::string::npos) << text;
  // --ignore-names maps by the skeleton's shape: the same joints, said so.
  const CommandResult t = runStirrup("character map " + quote(glb.string()) + " --as rider --ignore-names");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("as a rider: by topology (names ignored; they look like mixamo)"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("    lShoulder   mixamorig:LeftArm            topology: arm lengths and spacing (Winter 2009)\n"), std::string::npos) << t.out;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);  // no temporary left
}

TEST(CharacterMap, PreviewRendersTheRiderOnTheDefaultHorse) {
  const fs::path dir = tempDir("map_preview");
  const fs::path glb = makeMixamoRider(dir), png = dir / "preview.png";
  const CommandResult r = runStirrup("character map " + quote(glb.string()) + " --as rider --preview " + quote(png.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("preview: " + png.string() + " (frame 1 of the trot, the rider on the default horse, three-quarter view)\n"),
            std::string::npos) << r.out;
  auto in = OIIO::ImageInput::open(png.string());
  ASSERT_TRUE(in) << png;
  EXPECT_EQ(in->spec().width, 640);
  EXPECT_EQ(in->spec().height, 360);
  in->close();
  // Without -o the preview's mapping file is its own, and gone after.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(CharacterMap, TheFoxMapsAsAHorseAndPreviewsWithTheRigsTack) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  const fs::path dir = tempDir("map_fox");
  const fs::path json = dir / "fox.json", png = dir / "fox.png";
  const CommandResult r = runStirrup("character map " + quote(fox.string()) + " --as horse -o " + quote(json.string()) + " --preview " +
                                     quote(png.string()));
  EXPECT_NE(r.out.find(" as a horse: by topology (no joint names it knows)\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("  not mapped:"), std::string::npos) << r.out;  // the withers and the tack are optional
  EXPECT_NE(r.out.find("2.5400 cm per file unit  (height 79.0 file units, ground to the top of the head, read as inches: 201 cm)"),
            std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(json));
  // Without tack named the rig adds its own (rig/characters/horse_tack.h): the preview is rendered, the
  // Fox under the default rider.
  EXPECT_EQ(r.exit_code, 0) << r.err;
  auto in = OIIO::ImageInput::open(png.string());
  ASSERT_TRUE(in) << png;
  EXPECT_EQ(in->spec().width, 640);
  EXPECT_EQ(in->spec().height, 360);
  in->close();
}

TEST(CharacterMap, BadInputIsAOneLineError) {
  const fs::path dir = tempDir("map_bad");
  const fs::path glb = makeMixamoRider(dir), json = dir / "m.json";
  const std::string g = quote(glb.string());
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"character map " + g + " --as dragon -o " + quote(json.string()), "character map: --as: expected rider or horse, got \"dragon\""},
           {"character map " + quote((dir / "nope.glb").string()) + " --as rider -o " + quote(json.string()),
            (dir / "nope.glb").string() + ": no such file (expected a skinned glTF rider)"},
           {"character map " + g + " --as rider -o " + quote((dir / "m.txt").string()),
            "-o: " + (dir / "m.txt").string() + ": expected a mapping file name ending in .json"},
           {"character map " + g + " --as horse -o " + quote(json.string()),
            glb.string() + ": cannot map as a horse by topology: the limb from \"mixamorig:LeftShoulder\" ends at "
                           "\"mixamorig:LeftHandIndex3\""}}) {
    const CommandResult r = runStirrup(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err.rfind("stirrup: " + expected, 0), 0u) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_FALSE(fs::exists(json)) << args;
  }
  const CommandResult bad_preview = runStirrup("character map " + g + " --as rider --preview " + quote((dir / "p.jpg").string()));
  EXPECT_EQ(bad_preview.exit_code, 1);
  EXPECT_EQ(bad_preview.err, "stirrup: --preview: " + (dir / "p.jpg").string() + ": expected a file name ending in .png\n");
  const CommandResult help = runStirrup("character map --help");
  EXPECT_NE(help.out.find("--ignore-names"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("Mapping by itself"), std::string::npos) << help.out;
}

TEST(CharacterMap, ASceneNamingAFileAloneMapsItOnLoadAndSaysSo) {
  const fs::path dir = tempDir("map_scene");
  makeMixamoRider(dir);
  std::ofstream(dir / "s.json") << R"({"characters": {"rider": "mixamo-rider.glb"}, "frames": "1"})";
  const CommandResult r = runStirrup("bake " + quote((dir / "s.json").string()) + " -o " + quote((dir / "baked.glb").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string file = (dir / "mixamo-rider.glb").string();
  EXPECT_EQ(r.err, file + ": no role table: mapped as a rider by mixamo joint names; up +Y, forward +Z, 100.00 cm per unit (metres)\n"
                   "  15 of 15 roles (stirrup character map " + file + " --as rider lists every choice)\n");
  EXPECT_TRUE(fs::exists(dir / "baked.glb"));
}

}  // namespace
}  // namespace stirrup::test
