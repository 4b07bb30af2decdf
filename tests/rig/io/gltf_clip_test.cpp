#include "rig/io/gltf_clip.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "rig/motion/movement_clips.h"
#include "rig/motion/path_clip.h"
#include "rig/motion/procedural_gait.h"
#include "rig/rider_rig.h"
#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

fs::path tempFile(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("stirrup_gltf_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

const fs::path kFox = fs::path(STIRRUP_SHARED_DIR) / "assets/fox/Fox.glb";
const fs::path kFoxMapping = fs::path(STIRRUP_SOURCE_DIR) / "scenes/fox/fox-mapping.json";

void expectSameFrames(const Clip& a, const Clip& b, double fps, double duration) {
  for (int i = 0; i <= static_cast<int>(duration * fps); ++i) {
    const double t = i / fps;
    const HorseFrame x = a.sample(t), y = b.sample(t);
    // Floats in the file: 1e-4 relative to a few metres of travel, angles to 1e-3 degrees.
    EXPECT_NEAR(x.travel_cm, y.travel_cm, 1e-3 * std::max(1.0, std::abs(x.travel_cm) / 100.0)) << t;
    for (std::size_t c = 0; c < kHorseChannelCount; ++c)
      ASSERT_NEAR(x.controls.value[c], y.controls.value[c], 2e-3) << kHorseChannelNames[c] << " at " << t;
    EXPECT_NEAR(x.neck_rz, y.neck_rz, 2e-3);
    EXPECT_NEAR(x.head_rz, y.head_rz, 2e-3);
    EXPECT_NEAR(x.tail_rz, y.tail_rz, 2e-3);
    EXPECT_NEAR(x.tail_ry, y.tail_ry, 2e-3);
  }
}

TEST(GltfClip, RoundTripGivesTheSameChannels) {
  // The buck exercises every rotation channel (pitch, roll and yaw of the rear pivot, the back arch).
  const MovementClip buck(makeBuck(BuckParams{}));
  for (const char* name : {"buck.glb", "buck.gltf"}) {
    const fs::path file = tempFile(name);
    writeClipGltf(buck, file, {30.0});
    const GltfClip back(file, contractMapping());
    EXPECT_EQ(back.name(), "buck");
    EXPECT_NEAR(back.duration(), std::floor(buck.duration() * 30.0) / 30.0, 1e-5);
    expectSameFrames(buck, back, 30.0, back.duration());
  }
}

// A path clip (issue 15) round trips with its turns: the root node carries the travel frame along the
// ground and its heading, so the file read back follows the same path, and the hoof channels (children
// of the root) stay the same. A straight clip's root still has no rotation channel.
TEST(GltfClip, APathClipsRootCarriesItsTurns) {
  PathClipParams p;
  p.points = {{0, 0}, {1200, 0}, {2000, 500}, {2400, 1300}, {2800, 2100}, {3200, 2900}, {4000, 3400}, {5200, 3400}};
  p.speed = {{0, 560}};
  const PathClip path(p, nullptr, "test");
  const fs::path file = tempFile("path.glb");
  writeClipGltf(path, file, {30.0});
  const GltfClip back(file, contractMapping());
  double turned = 0;
  for (int i = 0; i <= static_cast<int>(back.duration() * 30.0); ++i) {
    const double t = i / 30.0;
    const HorseFrame x = path.sample(t), y = back.sample(t);
    EXPECT_NEAR(x.travel_cm, y.travel_cm, 2e-3) << t;
    EXPECT_NEAR(x.travel_z_cm, y.travel_z_cm, 2e-3) << t;
    EXPECT_NEAR(std::remainder(x.heading_deg - y.heading_deg, 360.0), 0.0, 1e-3) << t;
    for (std::size_t c = 0; c < kHorseChannelCount; ++c)
      ASSERT_NEAR(x.controls.value[c], y.controls.value[c], 2e-3) << kHorseChannelNames[c] << " at " << t;
    turned = std::max(turned, std::abs(y.heading_deg));
  }
  EXPECT_GT(turned, 45.0);
  const tinygltf::Model turning = stirrup::test::readGlbModel(file);
  const auto rootRotations = [](const tinygltf::Model& m) {
    int n = 0;
    for (const auto& ch : m.animations[0].channels) n += ch.target_node == 0 && ch.target_path == "rotation";
    return n;
  };
  EXPECT_EQ(rootRotations(turning), 1);
  const fs::path straight_file = tempFile("trot_straight.glb");
  writeClipGltf(MovementClip(makeBuck(BuckParams{})), straight_file, {30.0});
  EXPECT_EQ(rootRotations(stirrup::test::readGlbModel(straight_file)), 0);
}

// Appends floats to buffer 0 as a new bufferView and accessor; returns the accessor.
int appendFloats(tinygltf::Model& model, const std::vector<float>& data, int type) {
  tinygltf::Buffer& buffer = model.buffers[0];
  while (buffer.data.size() % 4) buffer.data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = data.size() * sizeof(float);
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  buffer.data.insert(buffer.data.end(), bytes, bytes + view.byteLength);
  model.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = type;
  a.count = data.size() / tinygltf::GetNumComponentsInType(type);
  model.accessors.push_back(a);
  return static_cast<int>(model.accessors.size()) - 1;
}

std::vector<float> accessorFloats(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors[index];
  const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
  const int n = tinygltf::GetNumComponentsInType(a.type);
  std::vector<float> out(a.count * n);
  std::memcpy(out.data(), &model.buffers[v.buffer].data[v.byteOffset + a.byteOffset], out.size() * sizeof(float));
  return out;
}

// Every LINEAR translation sampler rewritten as CUBICSPLINE whose tangents on each interval are that
// interval's slope (a different in- and out-tangent at every key): the cubic is then the straight
// line, so the file must play exactly like the LINEAR original. Plus one hand-computed bend: the
// lfHoof track's out-tangents set to +T and in-tangents to −T moves each interval's middle by td·T/4.
TEST(GltfClip, ReadsCubicSplineSamplers) {
  const fs::path linear = tempFile("trot_linear.glb"), cubic = tempFile("trot_cubic.glb"),
                 bent = tempFile("trot_bent.glb");
  writeClipGltf(ProceduralGait(trotParams(), 1.0), linear, {24.0});
  for (int variant = 0; variant < 2; ++variant) {
    tinygltf::Model model = stirrup::test::readGlbModel(linear);
    tinygltf::Animation& anim = model.animations[0];
    for (const tinygltf::AnimationChannel& ch : anim.channels) {
      if (ch.target_path != "translation") continue;
      tinygltf::AnimationSampler& s = anim.samplers[ch.sampler];
      const std::vector<float> t = accessorFloats(model, s.input), v = accessorFloats(model, s.output);
      const bool lf = model.nodes[ch.target_node].name == "lfHoof";
      std::vector<float> out;
      for (std::size_t k = 0; k < t.size(); ++k)
        for (int part = 0; part < 3; ++part)
          for (int j = 0; j < 3; ++j) {
            float x = v[k * 3 + j];
            if (part == 0) x = k == 0 ? 0.0f : (v[k * 3 + j] - v[(k - 1) * 3 + j]) / (t[k] - t[k - 1]);
            if (part == 2) x = k + 1 == t.size() ? 0.0f : (v[(k + 1) * 3 + j] - v[k * 3 + j]) / (t[k + 1] - t[k]);
            if (variant == 1 && lf && part != 1) x = (part == 2 ? 1.0f : -1.0f) * (j == 1 ? 40.0f : 0.0f);
            out.push_back(x);
          }
      s.output = appendFloats(model, out, TINYGLTF_TYPE_VEC3);
      s.interpolation = "CUBICSPLINE";
    }
    stirrup::test::writeGlbModel(model, variant == 0 ? cubic : bent);
  }
  const GltfClip a(linear, contractMapping()), b(cubic, contractMapping()), c(bent, contractMapping());
  for (double t = 0.0; t <= a.duration(); t += 1.0 / 96.0) {
    const HorseFrame x = a.sample(t), y = b.sample(t);
    for (std::size_t ch = 0; ch < kHorseChannelCount; ++ch)
      ASSERT_NEAR(x.controls.value[ch], y.controls.value[ch], 1e-3) << kHorseChannelNames[ch] << " at " << t;
  }
  // Middle of an interval (keys at 1/24 s): +td·T/4 = (1/24)·40/4 cm above the linear value.
  const double mid = 10.5 / 24.0;
  EXPECT_NEAR(c.sample(mid).controls[HorseChannel::lfHoofTy] - a.sample(mid).controls[HorseChannel::lfHoofTy],
              40.0 / 24.0 / 4.0, 1e-3);
  EXPECT_NEAR(c.sample(10.0 / 24.0).controls[HorseChannel::lfHoofTy], a.sample(10.0 / 24.0).controls[HorseChannel::lfHoofTy], 1e-4);
}

// A sparse accessor replaces chosen elements of its base: here key 5 of the lfHoof translation.
TEST(GltfClip, ReadsSparseAccessors) {
  const fs::path dense = tempFile("walk_dense.glb"), sparse = tempFile("walk_sparse.glb");
  writeClipGltf(ProceduralGait(walkParams(), 1.0), dense, {24.0});
  tinygltf::Model model = stirrup::test::readGlbModel(dense);
  int output = -1;
  for (const tinygltf::AnimationChannel& ch : model.animations[0].channels)
    if (ch.target_path == "translation" && model.nodes[ch.target_node].name == "lfHoof")
      output = model.animations[0].samplers[ch.sampler].output;
  ASSERT_GE(output, 0);
  const std::vector<float> base = accessorFloats(model, output);
  const float replacement[3] = {base[15] + 7.0f, base[16] + 11.0f, base[17]};
  const int values = appendFloats(model, {replacement[0], replacement[1], replacement[2]}, TINYGLTF_TYPE_VEC3);
  const uint32_t index = 5;
  tinygltf::Buffer& buffer = model.buffers[0];
  tinygltf::BufferView iv;
  iv.buffer = 0;
  iv.byteOffset = buffer.data.size();
  iv.byteLength = 4;
  buffer.data.insert(buffer.data.end(), reinterpret_cast<const unsigned char*>(&index),
                     reinterpret_cast<const unsigned char*>(&index) + 4);
  model.bufferViews.push_back(iv);
  tinygltf::Accessor& a = model.accessors[output];
  a.sparse.isSparse = true;
  a.sparse.count = 1;
  a.sparse.indices.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  a.sparse.indices.byteOffset = 0;
  a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  a.sparse.values.bufferView = model.accessors[values].bufferView;
  a.sparse.values.byteOffset = 0;
  stirrup::test::writeGlbModel(model, sparse);
  const GltfClip d(dense, contractMapping()), s(sparse, contractMapping());
  const HorseFrame x = d.sample(5.0 / 24.0), y = s.sample(5.0 / 24.0);
  EXPECT_NEAR(y.controls[HorseChannel::lfHoofTx] - x.controls[HorseChannel::lfHoofTx], 7.0, 1e-3);
  EXPECT_NEAR(y.controls[HorseChannel::lfHoofTy] - x.controls[HorseChannel::lfHoofTy], 11.0, 1e-3);
  EXPECT_NEAR(s.sample(4.0 / 24.0).controls[HorseChannel::lfHoofTx], d.sample(4.0 / 24.0).controls[HorseChannel::lfHoofTx], 1e-4);
}

TEST(GltfClip, RejectsUnknownInterpolation) {
  const fs::path good = tempFile("trot_interp.glb"), bad = tempFile("trot_badinterp.glb");
  writeClipGltf(ProceduralGait(trotParams(), 0.5), good, {24.0});
  tinygltf::Model model = stirrup::test::readGlbModel(good);
  model.animations[0].samplers[0].interpolation = "BEZIER";
  stirrup::test::writeGlbModel(model, bad);
  try {
    GltfClip clip(bad, contractMapping());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("interpolation: expected LINEAR, STEP or CUBICSPLINE"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
  }
}

TEST(GltfClip, WritesNamedControlNodesWithLinearSamplers) {
  const fs::path file = tempFile("trot.glb");
  writeClipGltf(ProceduralGait(trotParams(), 2.0), file, {24.0});
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
  std::set<std::string> names;
  for (const auto& n : model.nodes) names.insert(n.name);
  for (const char* c : {"lfHoof", "rfHoof", "lbHoof", "rbHoof", "rearPivot", "backMid", "neck", "head", "tail"})
    EXPECT_TRUE(names.count(c)) << c;
  ASSERT_EQ(model.animations.size(), 1u);
  for (const auto& s : model.animations[0].samplers) EXPECT_EQ(s.interpolation, "LINEAR");
  EXPECT_EQ(model.accessors[model.animations[0].samplers[0].input].count, 49u);  // 2 s at 24 fps
}

TEST(GltfClip, RenamedThroughAMappingDrivesTheRiderTheSameWay) {
  const MovementClip jump(makeJump(JumpParams{}));
  const fs::path file = tempFile("jump.glb"), renamed = tempFile("renamed.glb"), mapping = tempFile("map.json");
  writeClipGltf(jump, file, {30.0});
  // Another tool renames every node and moves the rest pose: each node gets its own rest translation
  // and rest rotation, and its animation is moved by the same (keys translated by the offset, rotation
  // keys turned by the rest rotation), so the file plays the same motion from a different rest pose.
  // The mapping undoes the names; the rest pose must be taken from the file.
  tinygltf::Model model = stirrup::test::readGlbModel(file);
  nlohmann::json nodes;
  std::map<int, glm::dvec3> offset;
  std::map<int, glm::dquat> turn;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    tinygltf::Node& n = model.nodes[i];
    nodes[n.name] = "Bone_" + n.name;
    n.name = "Bone_" + n.name;
    const double k = static_cast<double>(i + 1);
    offset[int(i)] = {3.0 * k, -2.0 + 1.5 * k, 7.0 - k};
    turn[int(i)] = glm::angleAxis(0.1 * k, glm::normalize(glm::dvec3(1.0, k, 2.0)));
    n.translation = {offset[int(i)].x, offset[int(i)].y, offset[int(i)].z};
    n.rotation = {turn[int(i)].x, turn[int(i)].y, turn[int(i)].z, turn[int(i)].w};
  }
  const fs::path rest_only = tempFile("rest_only.glb");
  stirrup::test::writeGlbModel(model, rest_only);
  int lf_node = -1;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].name == "Bone_lfHoof") lf_node = int(i);
  ASSERT_GE(lf_node, 0);
  tinygltf::Animation& anim = model.animations[0];
  int moved = 0, turned = 0;
  for (const tinygltf::AnimationChannel& ch : anim.channels) {
    tinygltf::AnimationSampler& s = anim.samplers[ch.sampler];
    std::vector<float> v = accessorFloats(model, s.output);
    if (ch.target_path == "translation") {
      const glm::dvec3 o = offset.at(ch.target_node);
      for (std::size_t k = 0; k + 2 < v.size(); k += 3)
        for (int j = 0; j < 3; ++j) v[k + j] = static_cast<float>(v[k + j] + o[j]);
      s.output = appendFloats(model, v, TINYGLTF_TYPE_VEC3);
      ++moved;
    } else if (ch.target_path == "rotation") {
      const glm::dquat q0 = turn.at(ch.target_node);
      for (std::size_t k = 0; k + 3 < v.size(); k += 4) {
        const glm::dquat q = q0 * glm::dquat(v[k + 3], v[k], v[k + 1], v[k + 2]);
        v[k] = float(q.x), v[k + 1] = float(q.y), v[k + 2] = float(q.z), v[k + 3] = float(q.w);
      }
      s.output = appendFloats(model, v, TINYGLTF_TYPE_VEC4);
      ++turned;
    }
  }
  ASSERT_GE(moved, 6);   // the travel root, four hooves and the rear pivot
  ASSERT_GE(turned, 5);  // rear pivot, back, neck, head, tail
  stirrup::test::writeGlbModel(model, renamed);
  std::ofstream(mapping) << nlohmann::json({{"mode", "controls"}, {"nodes", nodes}}).dump();
  const GltfClip a(file, contractMapping()), b(renamed, loadClipMapping(mapping));
  // Control: the rest pose moved but the animation not (rest_only) reads as the motion less the offset,
  // so a reader that ignored the file's rest pose could not pass the comparison below.
  const GltfClip c(rest_only, loadClipMapping(mapping));
  const int lf = lf_node;
  for (double t : {0.0, 0.5, 1.3}) {
    const HorseFrame fa = a.sample(t), fc = c.sample(t);
    EXPECT_NEAR(fc.controls[HorseChannel::lfHoofTx], fa.controls[HorseChannel::lfHoofTx] - offset.at(lf).x, 1e-3) << t;
    EXPECT_NEAR(fc.controls[HorseChannel::lfHoofTy], fa.controls[HorseChannel::lfHoofTy] - offset.at(lf).y, 1e-3) << t;
  }
  for (double t = 0.0; t < a.duration(); t += 0.1) {
    const HorseFrame fa = a.sample(t), fb = b.sample(t);
    // Floats in the file: a few 1e-5 of the moved values.
    EXPECT_NEAR(fa.travel_cm, fb.travel_cm, 1e-3) << t;
    for (std::size_t c = 0; c < kHorseChannelCount; ++c)
      ASSERT_NEAR(fa.controls.value[c], fb.controls.value[c], 2e-3) << kHorseChannelNames[c] << " at " << t;
    EXPECT_NEAR(fa.neck_rz, fb.neck_rz, 2e-3) << t;
    EXPECT_NEAR(fa.head_rz, fb.head_rz, 2e-3) << t;
    EXPECT_NEAR(fa.tail_rz, fb.tail_rz, 2e-3) << t;
    EXPECT_NEAR(fa.tail_ry, fb.tail_ry, 2e-3) << t;
    const RiderChannels ra = evaluateRider(fa.controls, RigProfile::thesis());
    const RiderChannels rb = evaluateRider(fb.controls, RigProfile::thesis());
    const RiderChannels rj = evaluateRider(jump.sample(t).controls, RigProfile::thesis());
    for (std::size_t c = 0; c < kRiderChannelCount; ++c) {
      EXPECT_NEAR(ra.value[c], rb.value[c], 1e-3 + 1e-4 * std::abs(ra.value[c])) << kRiderChannelNames[c] << " at " << t;
      EXPECT_NEAR(ra.value[c], rj.value[c], 0.05 + 0.02 * std::abs(rj.value[c])) << kRiderChannelNames[c] << " at " << t;
    }
  }
}

TEST(GltfClip, TheJumpsFenceTravelsWithTheClip) {
  const MovementClip jump(makeJump(JumpParams{}));
  ASSERT_EQ(jump.obstacles().size(), 1u);
  const fs::path file = tempFile("jump_fence.glb");
  writeClipGltf(jump, file, {24.0});
  const GltfClip back(file, contractMapping());
  ASSERT_EQ(back.obstacles().size(), 1u);
  const Obstacle& a = jump.obstacles()[0];
  const Obstacle& b = back.obstacles()[0];
  EXPECT_DOUBLE_EQ(b.travel_cm, a.travel_cm);
  EXPECT_DOUBLE_EQ(b.height_cm, a.height_cm);
  EXPECT_DOUBLE_EQ(b.width_cm, a.width_cm);
  EXPECT_DOUBLE_EQ(b.depth_cm, a.depth_cm);
  // A clip with nothing to clear reads back with nothing.
  const fs::path trot = tempFile("trot_nofence.glb");
  writeClipGltf(ProceduralGait(trotParams(), 1.0), trot);
  EXPECT_TRUE(GltfClip(trot, contractMapping()).obstacles().empty());
}

TEST(GltfClip, ABadObstacleIsAOneLineErrorNamingTheField) {
  const fs::path file = tempFile("jump_fence.gltf");
  writeClipGltf(MovementClip(makeJump(JumpParams{})), file, {24.0});
  nlohmann::json gltf;
  std::ifstream(file) >> gltf;
  ASSERT_TRUE(gltf["nodes"][0]["extras"].contains("obstacles"));
  const nlohmann::json good = gltf;
  gltf["nodes"][0]["extras"]["obstacles"][0]["height_cm"] = "tall";
  std::ofstream(file) << gltf.dump();
  try {
    GltfClip clip(file, contractMapping());
    FAIL() << "a fence height that is not a number was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("node \"horse\": extras.obstacles[0].height_cm: expected a number"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
  gltf = good;
  gltf["nodes"][0]["extras"]["obstacles"][0].erase("travel_cm");
  std::ofstream(file) << gltf.dump();
  EXPECT_THROW(GltfClip(file, contractMapping()), InputError);
  gltf = good;
  gltf["nodes"][0]["extras"]["obstacles"][0]["width_cm"] = -3;
  std::ofstream(file) << gltf.dump();
  EXPECT_THROW(GltfClip(file, contractMapping()), InputError);
}

TEST(GltfClip, AMissingNodeIsAOneLineErrorNamingIt) {
  const fs::path file = tempFile("trot2.glb"), mapping = tempFile("bad.json");
  writeClipGltf(ProceduralGait(trotParams(), 1.0), file);
  std::ofstream(mapping) << R"({"nodes": {"lfHoof": "lfHoof", "rfHoof": "rfHoof", "lbHoof": "LeftHindHoof", "rbHoof": "rbHoof"}})";
  try {
    GltfClip clip(file, loadClipMapping(mapping));
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("nodes.lbHoof: no node named \"LeftHindHoof\""), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
  std::ofstream(mapping) << R"({"nodes": {"lfHoof": "a", "rfHoof": "b", "lbHoof": "c", "rbHoof": "d", "hoofy": "e"}})";
  EXPECT_THROW(loadClipMapping(mapping), InputError);
}

TEST(GltfClip, FoxWalkAndRunGiveHoofHeightsThatRiseAndFall) {
  if (!fs::exists(kFox)) GTEST_SKIP() << kFox << " is not there";
  ClipMapping m = loadClipMapping(kFoxMapping);
  for (const char* animation : {"Walk", "Run"}) {
    m.animation = animation;
    const GltfClip fox(kFox, m);
    EXPECT_EQ(fox.name(), animation);
    ASSERT_GT(fox.duration(), 0.5);
    // Every hoof leaves the ground and comes back within one cycle, at horse scale.
    for (HorseChannel ty : {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy, HorseChannel::lbHoofTy, HorseChannel::rbHoofTy}) {
      double lo = 1e9, hi = -1e9;
      int rises = 0;
      bool low = true;
      // The first cycle settles the high/low state; count rises over the next two.
      for (double t = 0.0; t < 3.0 * fox.duration(); t += 0.005) {
        const double y = fox.sample(t).controls[ty];
        lo = std::min(lo, y);
        hi = std::max(hi, y);
        if (low && y > 10.0) rises += t >= fox.duration(), low = false;
        if (!low && y < 1.0) low = true;
      }
      EXPECT_EQ(lo, 0.0) << animation << " " << name(ty);
      EXPECT_GT(hi, 20.0) << animation << " " << name(ty);
      EXPECT_LT(hi, 200.0) << animation << " " << name(ty);
      EXPECT_EQ(rises, 2) << animation << " " << name(ty) << ": one step per cycle";
    }
    // The travel keeps the supporting hoof still on average: the clip moves forward.
    EXPECT_GT(fox.sample(fox.duration()).travel_cm, 100.0);
    // It drives the rider without error and with finite values.
    for (double t = 0.0; t < fox.duration(); t += 0.05) {
      const RiderChannels r = evaluateRider(fox.sample(t).controls, RigProfile::thesis());
      for (double v : r.value) ASSERT_TRUE(std::isfinite(v));
    }
  }
}

TEST(GltfClip, FoxWithAMisnamedNodeNamesIt) {
  if (!fs::exists(kFox)) GTEST_SKIP() << kFox << " is not there";
  ClipMapping m = loadClipMapping(kFoxMapping);
  m.nodes["lfHoof"] = "b_LeftHand_11";
  try {
    GltfClip fox(kFox, m);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nodes.lfHoof: no node named \"b_LeftHand_11\""), std::string::npos) << e.what();
  }
  m = loadClipMapping(kFoxMapping);
  m.animation = "Trot";
  EXPECT_THROW(GltfClip(kFox, m), InputError);
}

TEST(GltfClip, ASceneClipCanBeAFileWithAMapping) {
  const fs::path file = tempFile("scene_clip.glb");
  const MovementClip rear(makeRear(RearParams{}));
  writeClipGltf(rear, file, {30.0});
  // Paths resolve against the scene's folder.
  nlohmann::json j = {{"file", file.filename().string()}};
  JsonObjectReader r("scenes/x.json", "clip", j);
  const scene::ClipSpec spec = scene::parseClipSpec(r, file.parent_path());
  const auto clip = scene::makeClip(spec);
  EXPECT_NEAR(clip->sample(2.0).controls[HorseChannel::rearPivotRz], rear.sample(2.0).controls[HorseChannel::rearPivotRz], 1e-3);
  // A missing file, an unknown field: one line naming the file and field.
  nlohmann::json missing = {{"file", "nowhere.glb"}};
  JsonObjectReader r2("scenes/x.json", "clip", missing);
  try {
    scene::parseClipSpec(r2, file.parent_path());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("scenes/x.json: clip.file: no such file", 0), 0u) << e.what();
  }
  nlohmann::json extra = {{"file", file.filename().string()}, {"fence_height_cm", 90}};
  JsonObjectReader r3("scenes/x.json", "clip", extra);
  EXPECT_THROW(scene::parseClipSpec(r3, file.parent_path()), InputError);
  if (!fs::exists(kFox)) GTEST_SKIP() << kFox << " is not there";
  nlohmann::json fox = {{"file", kFox.string()}, {"mapping", kFoxMapping.string()}, {"animation", "Run"}};
  JsonObjectReader r4("scenes/x.json", "clip", fox);
  const auto run = scene::makeClip(scene::parseClipSpec(r4, "."));
  EXPECT_EQ(run->name(), "Run");
}

}  // namespace
}  // namespace stirrup::rig
