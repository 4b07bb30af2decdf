// stirrup bake -o: one glTF with both characters, their animation and the cameras, as another tool reads
// it (the Khronos validator, tinygltf, the glTF 2.0 camera conventions); a shot over hills with its ground.
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
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_character.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "scene/camera.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "scene/view.h"
#include "tests/cli/bake_support.h"
#include "tests/cli/baked_file.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// The Khronos glTF validator (npm gltf-validator, installed by scripts/setup into build/tools) finds no
// errors in a baked rear (follow camera, every joint moving).
TEST(BakeGltf, PassesTheKhronosValidator) {
  const fs::path glb = bakeGlb("rear.json", "1-96x4");
  bool skipped = false;
  const std::string problems = validatorProblems(glb, skipped);
  if (skipped) GTEST_SKIP() << problems;
  EXPECT_EQ(problems, "");
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

  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const auto clip = scene::makeClip(scene.clip);
  const rig::Character horse = rig::resolveCharacter(rig::CharacterKind::Horse, scene.horse, scene.horse_mapping);
  const rig::Character rider = rig::resolveCharacter(rig::CharacterKind::Rider, scene.rider, scene.rider_mapping);
  const std::vector<int> list = {1, 4, 7, 10, 13, 16, 19, 22};
  ASSERT_EQ(times.size(), list.size());
  double worst_t = 0.0, worst_r = 0.0;
  int checked = 0;
  for (std::size_t k = 0; k < list.size(); k += 3) {
    const rig::BakedFrame b = rig::bakeFrame(*clip, profile, list[k], scene::frameTime(scene, list[k]));
    EXPECT_FLOAT_EQ(times[k], static_cast<float>(b.seconds));
    const rig::MountedPose pose = rig::poseMounted(horse, rider, b.horse, b.rider, profile);
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
    scene::CameraSpec spec = scene.cameras[i];
    scene::applyViewPreset(spec);  // a view sets its own projection
    EXPECT_EQ(model.cameras[i].type, spec.orthographic ? "orthographic" : "perspective");
  }
}

// The bar: through each exported camera, the file's horse and rider land within half a pixel
// of where stirrup's render camera puts its own, on every frame of every view of every default scene.
class BakedCameras : public testing::TestWithParam<std::string> {};

TEST_P(BakedCameras, ProjectTheCharactersLikeTheRender) {
  const std::string name = GetParam();
  const fs::path file = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / (name + ".json");
  // A scene playing a third-party clip from ../shared (the Fox) is skipped where that folder is absent;
  // loading it would already fail on the missing file.
  {
    std::ifstream in(file);
    const nlohmann::json raw = nlohmann::json::parse(in);
    if (raw.contains("clip") && raw["clip"].is_object() && raw["clip"].contains("file")) {
      const fs::path clip = file.parent_path() / raw["clip"]["file"].get<std::string>();
      if (!fs::exists(clip)) GTEST_SKIP() << name << " plays " << clip << ", which is not there (../shared/assets)";
    }
    // Likewise a scene riding a third-party character (the Fox as a horse).
    if (raw.contains("characters") && raw["characters"].is_object())
      for (const auto& [kind, entry] : raw["characters"].items())
        if (entry.is_object() && entry.contains("file")) {
          const fs::path character = file.parent_path() / entry["file"].get<std::string>();
          if (!fs::exists(character)) GTEST_SKIP() << name << " rides " << character << ", which is not there (../shared/assets)";
        }
  }
  const scene::SceneSpec scene = scene::loadScene(file);
  const fs::path glb = bakeGlb(name + ".json", scene.frames);
  const tinygltf::Model model = readGlbModel(glb);
  const AnimatedNodes nodes(model);
  const std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
  ASSERT_EQ(nodes.times.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k)  // frame 1 at t = 0, for every track
    ASSERT_FLOAT_EQ(nodes.times[k], float((frames[k] - 1) / scene.fps)) << "frame " << frames[k];
  // The characters' bodies (the horse's tack is in nodes of its own beside its body's).
  const int horse_mesh = nodeNamed(model, "horse:horse_mesh"), rider_mesh = nodeNamed(model, "rider:rider_mesh");
  ASSERT_GE(horse_mesh, 0);
  ASSERT_GE(rider_mesh, 0);
  constexpr std::size_t kStride = 5;
  std::vector<std::vector<glm::dvec3>> file_points(frames.size());  // both characters, metres

  const rig::RigProfile profile = scene::resolveProfile(scene);
  ASSERT_EQ(model.cameras.size(), scene.cameras.size());
  for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
    SCOPED_TRACE(name + " camera " + scene.cameras[i].name);
    render::Shot shot(scene, profile, scene.cameras[i], 1);
    const int node = nodeNamed(model, "camera:" + scene.cameras[i].name);
    ASSERT_GE(node, 0);
    ASSERT_EQ(model.nodes[node].camera, static_cast<int>(i));
    const tinygltf::Camera& cam = model.cameras[i];
    ASSERT_TRUE(cam.extras.Has("width") && cam.extras.Has("height"));
    const int width = cam.extras.Get("width").GetNumberAsInt(), height = cam.extras.Get("height").GetNumberAsInt();
    EXPECT_EQ(width, scene.width);
    EXPECT_EQ(height, scene.height);
    double worst = 0.0;
    std::size_t projected = 0;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      // A held pose shows the held frame's characters at every frame: compare with the file's at it.
      const int hold = shot.camera().hold_frame;
      const std::size_t pose_key =
          hold > 0 ? static_cast<std::size_t>(std::find(frames.begin(), frames.end(), hold) - frames.begin()) : k;
      ASSERT_LT(pose_key, frames.size());
      // Every kStride-th vertex of the horse's body node, then of the rider's, each against the vertex of
      // stirrup's mesh it was written from.
      const std::vector<std::uint32_t> body = bodyVertices(shot.characters().horseAt(0, 0).mesh);
      if (file_points[pose_key].empty()) {
        const std::vector<glm::dvec3> h = nodes.skinned(horse_mesh, pose_key, 1), r = nodes.skinned(rider_mesh, pose_key, 1);
        ASSERT_EQ(h.size(), body.size());
        for (std::size_t v = 0; v < h.size(); v += kStride) file_points[pose_key].push_back(h[v]);
        for (std::size_t v = 0; v < r.size(); v += kStride) file_points[pose_key].push_back(r[v]);
      }
      std::vector<glm::dvec3> all_horse, rider, horse;
      shot.characterPoints(frames[k], 1, all_horse, rider);
      for (std::size_t v = 0; v < body.size(); v += kStride) horse.push_back(all_horse.at(body[v]));
      for (std::size_t v = 0; v < rider.size(); v += kStride) horse.push_back(rider[v]);
      ASSERT_EQ(horse.size(), file_points[pose_key].size());
      const scene::Camera rc = shot.cameraAtFrame(frames[k]);
      const glm::dmat4 world = nodes.world(node, k);
      for (std::size_t p = 0; p < horse.size(); ++p) {
        const glm::dvec2 a = stirrupPixel(rc, horse[p], width, height);
        const glm::dvec2 b = gltfPixel(cam, world, file_points[pose_key][p], width, height);
        worst = std::max(worst, glm::length(a - b));
        ++projected;
      }
    }
    EXPECT_GT(projected, 1000u);
    EXPECT_LT(worst, 0.5) << "pixels, worst point";
    std::printf("%s %s: worst %.4f px over %zu points\n", name.c_str(), scene.cameras[i].name.c_str(), worst, projected);
  }
}

// Each character under its own root node (scale 0.01: centimetres to metres), which is its skin's
// skeleton: a DCC builds one armature per character. No shared parent; cameras are roots of their own.
TEST(BakeGltf, OneSkeletonPerCharacter) {
  const tinygltf::Model model = readGlbModel(bakeGlb("jump.json", "1-24x4"));
  const AnimatedNodes nodes(model);
  EXPECT_EQ(nodeNamed(model, "stirrup_cm"), -1);
  ASSERT_EQ(model.skins.size(), 2u);
  const std::vector<std::string> roots = {"horse", "rider"};
  std::map<int, int> owner;  // node -> 0 horse, 1 rider, 2 camera
  for (std::size_t s = 0; s < 2; ++s) {
    const int root = nodeNamed(model, roots[s]);
    ASSERT_GE(root, 0) << roots[s];
    EXPECT_EQ(model.skins[s].skeleton, root);
    EXPECT_EQ(nodes.parent[root], -1);
    EXPECT_EQ(model.nodes[root].scale, (std::vector<double>{0.01, 0.01, 0.01}));
    EXPECT_NE(std::find(model.scenes[0].nodes.begin(), model.scenes[0].nodes.end(), root), model.scenes[0].nodes.end());
    for (int j : model.skins[s].joints) {
      int top = j;
      while (nodes.parent[top] >= 0) top = nodes.parent[top];
      EXPECT_EQ(top, root) << model.nodes[j].name;
      owner[j] = static_cast<int>(s);
    }
  }
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    if (model.nodes[n].camera >= 0) {
      EXPECT_EQ(nodes.parent[n], -1) << model.nodes[n].name;
      owner[static_cast<int>(n)] = 2;
    }
  // One animation, its channels grouped horse, rider, cameras (Blender 3.4 makes one action per
  // armature and camera from it, all playing).
  ASSERT_EQ(model.animations.size(), 1u);
  int last = 0;
  std::set<int> seen;
  for (const tinygltf::AnimationChannel& ch : model.animations[0].channels) {
    ASSERT_TRUE(owner.count(ch.target_node)) << model.nodes[ch.target_node].name;
    EXPECT_GE(owner[ch.target_node], last) << model.nodes[ch.target_node].name;
    last = owner[ch.target_node];
    seen.insert(last);
  }
  EXPECT_EQ(seen, (std::set<int>{0, 1, 2}));  // the jump's follow cameras move
}

// The list above is every scene shipped in scenes/ and its folders (a new scene file must join it), but
// the crowds, whose cameras BakeGltf.ACrowdBakesEveryPairWithItsCameras checks.
TEST(BakeGltf, CameraTestCoversEveryDefaultScene) {
  std::set<std::string> shipped;
  const fs::path root = fs::path(STIRRUP_SOURCE_DIR) / "scenes";
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string text = e.path().extension() == ".json" ? readText(e.path()) : "";
    if (text.find("\"cameras\"") != std::string::npos && text.find("\"crowd\"") == std::string::npos &&
        text.find("\"riders\"") == std::string::npos)
      shipped.insert(fs::relative(e.path(), root).replace_extension().string());
  }
  EXPECT_EQ(shipped, (std::set<std::string>{"buck", "canter", "cross_country", "figure_eight", "fox/fox", "fox/fox_horse", "fox/fox_run",
                                            "gallop", "gallop_layered", "jump", "rear", "stop", "trail", "trot", "walk"}));
}

// Over a terrain the baked file holds the ground (node "ground", scale 0.01, its mesh in cm): its
// vertices on the scene's hills, covering the track, facing up; the Khronos validator passes it.
TEST(BakeGltf, AShotOverHillsCarriesItsGround) {
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "test_bake_glb" / "trail_ground" / "trail.glb";
  fs::remove_all(out.parent_path());
  const CommandResult r = runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/trail.json") + " --frames 1-609x60 -o " +
                                     quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tinygltf::Model model = readGlbModel(out);
  const int root = nodeNamed(model, "ground"), mesh_node = nodeNamed(model, "ground_mesh");
  ASSERT_GE(root, 0);
  ASSERT_GE(mesh_node, 0);
  EXPECT_EQ(model.nodes[root].scale, (std::vector<double>{0.01, 0.01, 0.01}));
  EXPECT_EQ(model.nodes[root].children, std::vector<int>{mesh_node});
  const tinygltf::Primitive& prim = model.meshes.at(std::size_t(model.nodes[mesh_node].mesh)).primitives.at(0);
  const tinygltf::Accessor& pa = model.accessors.at(std::size_t(prim.attributes.at("POSITION")));
  const tinygltf::BufferView& pv = model.bufferViews.at(std::size_t(pa.bufferView));
  std::vector<float> p(pa.count * 3);
  std::memcpy(p.data(), model.buffers[0].data.data() + pv.byteOffset + pa.byteOffset, p.size() * sizeof(float));
  const scene::SceneSpec scene = scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trail.json");
  ASSERT_TRUE(scene.terrain);
  double worst = 0, lo_x = 1e30, hi_x = -1e30, lo_y = 1e30, hi_y = -1e30;
  for (std::size_t i = 0; i < pa.count; ++i) {
    worst = std::max(worst, std::abs(p[3 * i + 1] - scene.terrain->height(p[3 * i], p[3 * i + 2])));
    lo_x = std::min<double>(lo_x, p[3 * i]), hi_x = std::max<double>(hi_x, p[3 * i]);
    lo_y = std::min<double>(lo_y, p[3 * i + 1]), hi_y = std::max<double>(hi_y, p[3 * i + 1]);
  }
  EXPECT_LT(worst, 0.01) << "cm: the file's ground is the scene's";
  EXPECT_GT(hi_y - lo_y, 200.0) << "the hills are in it";
  const auto clip = scene::makeSceneClip(scene);
  EXPECT_LT(lo_x, clip->sample(0).travel_cm - 1000.0);
  EXPECT_GT(hi_x, clip->sample(clip->duration()).travel_cm + 1000.0);
  EXPECT_GT(model.accessors.at(std::size_t(prim.indices)).count, 30000u);

  bool skipped = false;
  const std::string problems = validatorProblems(out, skipped);
  if (skipped) GTEST_SKIP() << problems;
  EXPECT_EQ(problems, "");
}

INSTANTIATE_TEST_SUITE_P(DefaultScenes, BakedCameras,
                         testing::Values("buck", "canter", "cross_country", "figure_eight", "fox/fox", "fox/fox_horse", "fox/fox_run",
                                         "gallop", "gallop_layered", "jump", "rear", "stop", "trail", "trot", "walk"));

}  // namespace
}  // namespace stirrup::test
