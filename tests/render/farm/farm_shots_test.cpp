#include "render/farm/farm_shots.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "render/shot.h"
#include "scene/profile_resolver.h"
#include "tests/input_error.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

FarmRequest request(const fs::path& out, int chunk) {
  FarmRequest r;
  r.out = out;
  r.chunk = chunk;
  r.stirrup = "/opt/stirrup/bin/stirrup";
  r.submitted = "2026-11-25 06:00:00";
  return r;
}

TEST(FarmShots, ARenderShotIsCutIntoChunksOfItsFrames) {
  const fs::path scene = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "trot.json";
  const FarmPlan plan = planRender(request("/shared/trot", 4), scene, "side", "1-10", {"--preset", "draft"});
  EXPECT_EQ(plan.kind, "render");
  ASSERT_EQ(plan.shots.size(), 1u);
  const FarmShot& shot = plan.shots[0];
  EXPECT_EQ(shot.name, "trot_side");
  ASSERT_EQ(shot.chunks.size(), 3u);  // 4 + 4 + 2
  EXPECT_EQ(shot.chunks[2].task, 3);
  EXPECT_EQ(shot.chunks[2].frames, (std::vector<int>{9, 10}));
  EXPECT_EQ(shot.chunks[2].files, (std::vector<std::string>{"trot_side.0009.png", "trot_side.0010.png"}));
  EXPECT_EQ(shot.command, (std::vector<std::string>{"/opt/stirrup/bin/stirrup", "render", scene.string(), "--camera", "side",
                                                    "--out", "/shared/trot", "--preset", "draft", "--resume"}));
  EXPECT_EQ(shot.outputs, std::vector<std::string>{"trot_side.mp4"});
  EXPECT_EQ(plan.finish_command,
            (std::vector<std::string>{"/opt/stirrup/bin/stirrup", "render", scene.string(), "--camera", "side", "--out",
                                      "/shared/trot", "--preset", "draft", "--frames", "1-10", "--encode-only", "--movie",
                                      "/shared/trot/trot_side.mp4"}));
}

// A scene beyond a horse's limits (a walk at 900 cm/s) is refused when the shot is planned, as it would
// be by every task; with --allow-impossible among the render options it is planned, and every task and
// the finishing encode render it with it.
TEST(FarmShots, AnImpossibleSceneIsPlannedOnlyWithAllowImpossible) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / ("test_farm_shots_impossible_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path scene = dir / "walk900.json";
  std::ofstream(scene) << R"({"clip": {"generator": "walk", "speed_cm_s": 900}, "frames": "1-4"})";
  EXPECT_EQ(errorOf([&] { planRender(request("/shared/walk", 2), scene, "side", "", {}); }),
            scene.string() + ": clip.speed_cm_s: 900 cm/s is faster than a horse walks (at most 250 cm/s: horses change to "
            "the trot at 160-230 cm/s, Froude 0.35, Griffin et al. 2004; a walk held past that, an estimate; allow_impossible or "
            "--allow-impossible renders it anyway)");
  const FarmPlan plan = planRender(request("/shared/walk", 2), scene, "side", "", {"--allow-impossible"});
  ASSERT_EQ(plan.shots.size(), 1u);
  EXPECT_EQ(plan.shots[0].chunks.size(), 2u);
  const auto has = [](const std::vector<std::string>& c) { return std::find(c.begin(), c.end(), "--allow-impossible") != c.end(); };
  EXPECT_TRUE(has(plan.shots[0].command));
  EXPECT_TRUE(has(plan.finish_command));
  fs::remove_all(dir);
}

// A view camera framed once into the plan: a chunk rendered with it (stirrup render --camera-plan)
// has every camera and every pixel of the chunk rendered by framing the view itself; the plan's
// command passes it, the manifest gives it back to the bit, and a camera of another camera, scene or
// size is a one-line error naming the file and the field.
TEST(FarmShots, APlannedCameraRendersAChunkByteForByteAsFramingDoes) {
  scene::SceneSpec scene = scene::loadScene(fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "trot.json");
  scene.width = 96, scene.height = 54, scene.samples = 1;
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const scene::CameraSpec& camera = scene::findCamera(scene, "persp");
  ASSERT_FALSE(camera.view.empty());
  const std::optional<PlannedCamera> planned = planCamera(scene, profile, camera, 2);
  ASSERT_TRUE(planned.has_value());
  EXPECT_FALSE(planCamera(scene, profile, [&] { scene::CameraSpec c = camera; c.view.clear(); return c; }()).has_value());

  // Through the manifest, as a task reads it.
  const fs::path out = fs::path(STIRRUP_BINARY_DIR) / ("farm_camera_" + std::to_string(::getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  const FarmPlan plan = planRender(request(out, 2), scene.file, "persp", "10-13", {}, planned);
  const std::vector<std::string>& command = plan.shots[0].command;
  ASSERT_GE(command.size(), 2u);
  EXPECT_EQ(command[command.size() - 2], "--camera-plan");
  EXPECT_EQ(command.back(), manifestFile(out).string());
  writeManifest(plan);
  std::string where;
  const PlannedCamera read = plannedCameraOf(manifestFile(out), "trot_persp", where);
  EXPECT_EQ(where, manifestFile(out).string() + ": shots[0].camera");
  const scene::CameraSpec shown = plannedCameraSpec(scene, profile, camera, read, where);
  EXPECT_TRUE(shown.view.empty());

  Shot framing(scene, profile, camera, 2);
  Shot reading(scene, profile, shown, 2);
  EXPECT_EQ(framing.camera().position, shown.position);
  EXPECT_EQ(framing.camera().target, shown.target);
  for (int frame : plan.shots[0].chunks[1].frames) {  // the second chunk: 12, 13
    const scene::Camera a = framing.cameraAtFrame(frame), b = reading.cameraAtFrame(frame);
    EXPECT_EQ(a.position, b.position) << frame;
    EXPECT_EQ(a.target, b.target) << frame;
    EXPECT_EQ(a.up, b.up) << frame;
    EXPECT_EQ(a.fov_deg, b.fov_deg) << frame;
    const Image x = framing.renderFrame(frame), y = reading.renderFrame(frame);
    ASSERT_EQ(x.rgba.size(), y.rgba.size());
    EXPECT_EQ(0, std::memcmp(x.rgba.data(), y.rgba.data(), x.rgba.size() * sizeof(glm::vec4))) << frame;
    EXPECT_EQ(x.depth, y.depth) << frame;
  }

  const std::string file = manifestFile(out).string();
  EXPECT_EQ(errorOf([&] { plannedCameraSpec(scene, profile, scene::findCamera(scene, "side"), read, where); }),
            file + ": shots[0].camera.name: expected \"side\" (the camera rendered), got \"persp\"");
  scene::SceneSpec bigger = scene;
  bigger.width = 192, bigger.height = 108;
  const std::string key = errorOf([&] { plannedCameraSpec(bigger, profile, camera, read, where); });
  EXPECT_EQ(key.rfind(file + ": shots[0].camera.key: expected ", 0), 0u) << key;
  EXPECT_NE(key.find("submit the farm again"), std::string::npos) << key;
  EXPECT_EQ(errorOf([&] { plannedCameraOf(manifestFile(out), "trot_side", where); }),
            file + ": shots: expected a shot named trot_side (the scene's and camera's names)");
  fs::remove_all(out);
}

TEST(FarmShots, AnUnknownCameraIsTheScenesOwnError) {
  const fs::path scene = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "trot.json";
  EXPECT_NE(errorOf([&] { planRender(request("/shared/trot", 4), scene, "nosuch", "", {}); }).find("nosuch"),
            std::string::npos);
}

TEST(FarmShots, MovieShotsListTheFramesAndContactSheetFilesEachChunkWrites) {
  MovieOptions o;
  o.frames_limit = 5;
  o.contact_count = 2;
  const std::vector<MovieJob> jobs = {{"trot_side", fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "trot.json", "side", "", "", {}}};
  const FarmPlan plan = planMovies(request("/shared/review", 3), jobs, o, {"--preset", "draft"}, true);
  ASSERT_EQ(plan.shots.size(), 1u);
  const FarmShot& shot = plan.shots[0];
  EXPECT_EQ(shot.frames_dir, "frames/trot_side");
  EXPECT_EQ(shot.outputs, (std::vector<std::string>{"trot_side.mp4", "trot_side_sheet.png"}));
  ASSERT_EQ(shot.chunks.size(), 2u);
  EXPECT_EQ(shot.chunks[0].frames, (std::vector<int>{1, 2, 3}));
  // Two contact-sheet frames among five: the first and the last, each with its EXR beside the PNG.
  EXPECT_EQ(shot.chunks[0].files,
            (std::vector<std::string>{"frames/trot_side/trot_side.0001.png", "frames/trot_side/trot_side.0001.sheet.exr",
                                      "frames/trot_side/trot_side.0002.png", "frames/trot_side/trot_side.0003.png"}));
  EXPECT_EQ(shot.chunks[1].files.back(), "frames/trot_side/trot_side.0005.sheet.exr");
  EXPECT_EQ(plan.finish_command, (std::vector<std::string>{"/opt/stirrup/bin/stirrup", "movies", "--out", "/shared/review",
                                                           "--finish", "--preset", "draft", "--only", "trot_side"}));
}

TEST(FarmShots, TheOutputFolderMustBeWritableAndShared) {
  EXPECT_EQ(errorOf([] { checkSharedOutput("/proc/stirrup_farm_out", 1); }).rfind("--out: /proc/stirrup_farm_out: cannot make the folder", 0), 0u);
  EXPECT_EQ(errorOf([] { checkSharedOutput("/etc/hostname", 1); }), "--out: /etc/hostname: not a folder");
  if (fs::is_directory("/dev/shm")) {
    const fs::path shm = "/dev/shm/stirrup_farm_test_" + std::to_string(::getpid());
    EXPECT_EQ(errorOf([&] { checkSharedOutput(shm, 1); }),
              "--out: " + shm.string() +
                  ": on tmpfs, in this machine's memory, which the cluster's nodes do not share; use a folder on a shared "
                  "filesystem (NFS, Lustre, CephFS)");
    fs::remove_all(shm);
  }
  // A folder on this machine's own disk serves a one-node cluster, not a cluster of several.
  const fs::path local = fs::path(STIRRUP_BINARY_DIR) / ("farm_out_" + std::to_string(::getpid()));
  EXPECT_EQ(errorOf([&] { checkSharedOutput(local, 1); }), "(no error)");
  EXPECT_EQ(errorOf([&] { checkSharedOutput(local, 4); }),
            "--out: " + local.string() +
                ": on a local disk, not shared by the cluster's 4 nodes; use a folder on a shared filesystem (NFS, Lustre, CephFS)");
  fs::remove_all(local);
}

}  // namespace
}  // namespace stirrup::render
