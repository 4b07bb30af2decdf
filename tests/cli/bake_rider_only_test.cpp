// stirrup bake --rider-only: the rider's skeleton and animation alone, one file a pair in a crowd.
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

#include "rig/io/gltf_character.h"
#include "scene/scene.h"
#include "tests/cli/bake_support.h"
#include "tests/cli/baked_file.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// --rider-only writes the rider's skeleton and animation alone (rig/io/gltf_rider_motion.h has the
// round trip onto a user's rider); without -o it is a one-line error.
TEST(BakeGltf, RiderOnlyWritesTheRiderAlone) {
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / "test_bake_rider_only" / "rider.glb";
  fs::remove_all(out.parent_path());
  const std::string scene = quote(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  CommandResult r = runStirrup("bake " + scene + " --frames 1-12 --rider-only -o " + quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tinygltf::Model model = readGlbModel(out);
  EXPECT_TRUE(model.meshes.empty());
  EXPECT_TRUE(model.cameras.empty());
  ASSERT_EQ(model.skins.size(), 1u);
  ASSERT_EQ(model.animations.size(), 1u);
  const rig::Character rider = rig::resolveCharacter(rig::CharacterKind::Rider, scene::loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json").rider, "");
  ASSERT_EQ(model.skins[0].joints.size(), rider.skeleton.size());
  for (std::size_t j = 0; j < rider.skeleton.size(); ++j)
    EXPECT_EQ(model.nodes[model.skins[0].joints[j]].name, rider.skeleton.joints[j].name);
  EXPECT_EQ(model.animations[0].channels.size(), 2 * rider.skeleton.size());
  EXPECT_EQ(accessorData<float>(model, model.animations[0].samplers[0].input).size(), 12u);

  r = runStirrup("bake " + scene + " --rider-only --channels " + quote((out.parent_path() / "c.csv").string()));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "stirrup: bake: --rider-only: expected -o FILE.glb to write the rider's motion to\n");
  r = runStirrup("bake --help");
  EXPECT_NE(r.out.find("--rider-only"), std::string::npos);
}

// --rider-only on a crowd writes one file a pair (the pair's name before the extension), each the
// rider's skeleton alone, keyed at every frame; two pairs' riders move differently.
TEST(BakeGltf, ACrowdsRiderOnlyIsOneFileAPair) {
  // A folder of its own: RiderOnlyWritesTheRiderAlone empties test_bake_rider_only/ and CTest may run
  // the two at once.
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_bake_rider_only_crowd";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "crowd.json") << R"({"riders": [
    {"points": [[0, -300], [3000, -300]], "speed": [[0, 300]], "seed": 1},
    {"points": [[0, 300], [3000, 300]], "speed": [[0, 300]], "seed": 2, "start_offset_s": 0.5, "rider_height_cm": 185},
    {"points": [[-1200, 0], [1800, 0]], "speed": [[0, 300]], "seed": 3}]})";
  const CommandResult r = runStirrup("bake " + quote((dir / "crowd.json").string()) + " --frames 1-12 --rider-only -o " +
                                     quote((dir / "rider.glb").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "rider.glb"));
  std::vector<std::vector<float>> first_rotation;
  for (const char* name : {"rider_pair00.glb", "rider_pair01.glb", "rider_pair02.glb"}) {
    ASSERT_TRUE(fs::exists(dir / name)) << name;
    const tinygltf::Model model = readGlbModel(dir / name);
    EXPECT_TRUE(model.meshes.empty()) << name;
    EXPECT_TRUE(model.cameras.empty()) << name;
    ASSERT_EQ(model.skins.size(), 1u) << name;
    ASSERT_EQ(model.animations.size(), 1u) << name;
    EXPECT_EQ(accessorData<float>(model, model.animations[0].samplers[0].input).size(), 12u) << name;
    first_rotation.push_back(accessorData<float>(model, model.animations[0].samplers[1].output));
  }
  EXPECT_FALSE(fs::exists(dir / "rider_pair03.glb"));
  EXPECT_NE(first_rotation[0], first_rotation[1]) << "two pairs' riders move alike";
}

}  // namespace
}  // namespace stirrup::test
