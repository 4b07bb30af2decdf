// stirrup bake end to end: the CSV holds horse and rider channels side by side for every frame.
#include <algorithm>
#include <map>
#include <filesystem>
#include <sstream>
#include <vector>

#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "render/scene.h"
#include "rig/bake.h"
#include "rig/channels.h"
#include "rig/motion/clip_factory.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/rig_profile.h"
#include "tests/render/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string c;
  while (std::getline(ss, c, ',')) cells.push_back(c);
  return cells;
}

TEST(Bake, WritesEveryChannelOfEveryFrame) {
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "test_bake" / "trot.csv";
  fs::remove_all(out.parent_path());
  const CommandResult r = runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json") +
                                     " --frames 1-48x2 --channels " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  std::stringstream csv(readText(out));
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = split(line);
  ASSERT_EQ(header.size(), 2 + rig::kHorseChannelCount + rig::kRiderChannelCount);
  EXPECT_EQ(header[0], "frame");
  EXPECT_EQ(header[1], "time");
  for (auto n : rig::kHorseChannelNames)
    EXPECT_NE(std::find(header.begin(), header.end(), std::string(n)), header.end()) << n;
  for (auto n : rig::kRiderChannelNames)
    EXPECT_NE(std::find(header.begin(), header.end(), std::string(n)), header.end()) << n;

  const auto column = [&](const std::string& n) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), n) - header.begin());
  };
  std::vector<double> lift, frame;
  while (std::getline(csv, line)) {
    const auto cells = split(line);
    ASSERT_EQ(cells.size(), header.size());
    frame.push_back(std::stod(cells[0]));
    lift.push_back(std::stod(cells[column("cog.ty")]));
  }
  ASSERT_EQ(frame.size(), 24u);
  EXPECT_EQ(frame.front(), 1.0);
  EXPECT_EQ(frame.back(), 47.0);
  // The rider bounces at the trot: the lift varies over two seconds of trot.
  const auto [lo, hi] = std::minmax_element(lift.begin(), lift.end());
  EXPECT_GT(*hi - *lo, 0.05);
}

TEST(Bake, HelpDocumentsTheCsv) {
  const CommandResult r = runStirrup("bake --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--channels"), std::string::npos);
  EXPECT_NE(r.out.find("rig-channels.md"), std::string::npos);
}

// stirrup bake -o: one glTF with both characters, their animation and the cameras.
fs::path bakeGlb(const std::string& scene, const std::string& frames) {
  // A folder per scene: CTest runs the tests in parallel, and each clears only its own folder.
  const std::string stem = fs::path(scene).stem().string();
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "test_bake_glb" / stem / (stem + ".glb");
  fs::remove_all(out.parent_path());
  const CommandResult r = runStirrup("bake " + quote(std::string(STIRRUP_SOURCE_DIR "/scenes/") + scene) + " --frames " +
                                     frames + " -o " + quote(out.string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return out;
}

// The Khronos glTF validator (npm gltf-validator, installed by scripts/setup into build/tools) finds no
// errors in a baked rear (follow camera, every joint moving).
TEST(BakeGltf, PassesTheKhronosValidator) {
  if (runCommand("command -v node >/dev/null").exit_code != 0) GTEST_SKIP() << "node is not installed";
  fs::path modules = fs::path(STIRRUP_BINARY_DIR) / "tools" / "node_modules";
  if (!fs::exists(modules / "gltf-validator")) modules = fs::path(STIRRUP_SOURCE_DIR) / "build" / "tools" / "node_modules";
  ASSERT_TRUE(fs::exists(modules / "gltf-validator")) << "gltf-validator is not installed: run scripts/setup";
  const fs::path glb = bakeGlb("rear.json", "1-96x4");
  const CommandResult v = runCommand("node " + quote(STIRRUP_SOURCE_DIR "/tests/render/cli/validate_gltf.js") + " " +
                                     quote(modules.string()) + " " + quote(glb.string()));
  ASSERT_EQ(v.exit_code, 0) << v.err;
  EXPECT_NE(v.out.find("\"errors\":0,"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("\"warnings\":0,"), std::string::npos) << v.out;
}

// Read back with tinygltf, the baked file's joints at sample frames are the rig's pose.
TEST(BakeGltf, RoundTripsTheJointTransforms) {
  const std::string frames = "1-24x3";
  const fs::path glb = bakeGlb("trot.json", frames);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, glb.string())) << err;
  ASSERT_EQ(model.animations.size(), 1u);
  ASSERT_EQ(model.skins.size(), 2u);
  const auto floats = [&](int accessor) {
    const tinygltf::Accessor& a = model.accessors[accessor];
    const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
    std::vector<float> out(a.count * tinygltf::GetNumComponentsInType(a.type));
    std::memcpy(out.data(), model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset, out.size() * 4);
    return out;
  };
  // node -> (translation values, rotation values)
  std::map<int, std::pair<std::vector<float>, std::vector<float>>> tracks;
  const tinygltf::Animation& anim = model.animations[0];
  for (const auto& ch : anim.channels) {
    const std::vector<float> values = floats(anim.samplers[ch.sampler].output);
    (ch.target_path == "translation" ? tracks[ch.target_node].first : tracks[ch.target_node].second) = values;
  }
  const std::vector<float> times = floats(anim.samplers[0].input);

  const render::SceneSpec scene = render::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const rig::RigProfile profile = render::resolveProfile(scene);
  const auto clip = rig::makeClip(scene.clip);
  const rig::Character horse = rig::resolveCharacter(rig::CharacterKind::Horse, scene.horse, scene.horse_mapping);
  const rig::Character rider = rig::resolveCharacter(rig::CharacterKind::Rider, scene.rider, scene.rider_mapping);
  const std::vector<int> list = {1, 4, 7, 10, 13, 16, 19, 22};
  ASSERT_EQ(times.size(), list.size());
  double worst_t = 0.0, worst_r = 0.0;
  int checked = 0;
  for (std::size_t k = 0; k < list.size(); k += 3) {
    const rig::BakedFrame b = rig::bakeFrame(*clip, profile, list[k], render::frameTime(scene, list[k]));
    EXPECT_FLOAT_EQ(times[k], static_cast<float>(b.seconds));
    const rig::MountedPose pose = rig::poseMounted(horse, rider, b.horse, b.rider, profile.rider_unit_cm);
    for (int which = 0; which < 2; ++which) {
      const rig::Character& c = which == 0 ? horse : rider;
      const std::vector<glm::mat4> local = rig::worldToLocal(c.skeleton, which == 0 ? pose.horse : pose.rider);
      const std::vector<int>& joints = model.skins[which].joints;
      ASSERT_EQ(joints.size(), c.skeleton.size());
      for (std::size_t j = 0; j < joints.size(); ++j) {
        const tinygltf::Node& n = model.nodes[joints[j]];
        glm::vec3 t(float(n.translation[0]), float(n.translation[1]), float(n.translation[2]));
        glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));
        if (const auto it = tracks.find(joints[j]); it != tracks.end()) {
          const auto& [tv, rv] = it->second;
          t = glm::vec3(tv[k * 3], tv[k * 3 + 1], tv[k * 3 + 2]);
          q = glm::quat(rv[k * 4 + 3], rv[k * 4], rv[k * 4 + 1], rv[k * 4 + 2]);
        }
        const glm::mat4 m = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(q);
        worst_t = std::max(worst_t, double(glm::length(glm::vec3(m[3]) - glm::vec3(local[j][3]))));
        for (int col = 0; col < 3; ++col)
          worst_r = std::max(worst_r, double(glm::length(glm::vec3(m[col]) - glm::vec3(local[j][col]))));
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 3 * static_cast<int>(horse.skeleton.size() + rider.skeleton.size()));
  EXPECT_LT(worst_t, 1e-3);  // cm
  EXPECT_LT(worst_r, 1e-5);  // rotation matrix columns
  // Every camera of the scene, on a node named after it.
  ASSERT_EQ(model.cameras.size(), scene.cameras.size());
  for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
    const tinygltf::Node* cam = nullptr;
    for (const auto& n : model.nodes)
      if (n.camera == static_cast<int>(i)) cam = &n;
    ASSERT_NE(cam, nullptr);
    EXPECT_EQ(cam->name, "camera:" + scene.cameras[i].name);
    EXPECT_EQ(model.cameras[i].type, scene.cameras[i].orthographic ? "orthographic" : "perspective");
  }
}

}  // namespace
}  // namespace stirrup::test
