#include "render/farm/farm_shots.h"

#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "tests/input_error.h"

namespace stirrup::render::farm {
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

TEST(FarmShots, AnUnknownCameraIsTheScenesOwnError) {
  const fs::path scene = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "trot.json";
  EXPECT_NE(errorOf([&] { planRender(request("/shared/trot", 4), scene, "nosuch", "", {}); }).find("nosuch"),
            std::string::npos);
}

TEST(FarmShots, MovieShotsListTheFramesAndContactSheetFilesEachChunkWrites) {
  MovieOptions o;
  o.frames_limit = 5;
  o.contact_count = 2;
  const std::vector<MovieJob> jobs = {{"trot_side", fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "trot.json", "side", "", ""}};
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
                                                           "--finish", "--only", "trot_side", "--preset", "draft"}));
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
}  // namespace stirrup::render::farm
