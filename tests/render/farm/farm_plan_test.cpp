#include "render/farm/farm_plan.h"

#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "tests/input_error.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

FarmPlan twoChunkPlan(const fs::path& out) {
  FarmPlan plan;
  plan.out = out;
  plan.kind = "movies";
  plan.submitted = "2026-11-25 06:00:00";
  plan.sbatch.partition = "main";
  plan.sbatch.time = "30:00";
  plan.sbatch.cpus_per_task = 2;
  FarmShot shot;
  shot.name = "trot_side";
  shot.command = {"/opt/stirrup/bin/stirrup", "movies", "--out", out.string(), "--only", "trot_side", "--date", "it's"};
  shot.frames_dir = "frames/trot_side";
  shot.outputs = {"trot_side.mp4", "trot_side_sheet.png"};
  shot.chunks = {{1, {1, 3, 5}, {"frames/trot_side/trot_side.0001.png"}}, {2, {7, 9}, {"frames/trot_side/trot_side.0007.png"}}};
  shot.array_jobs = {"41"};
  plan.shots = {shot};
  plan.finish_command = {"/opt/stirrup/bin/stirrup", "movies", "--out", out.string(), "--finish"};
  plan.finish_jobs = {"42"};
  return plan;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("stirrup_farm_plan_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(FarmPlan, ChunksCutAFrameListInPlayingOrder) {
  EXPECT_EQ(chunkFrames({1, 2, 3, 4, 5}, 2), (std::vector<std::vector<int>>{{1, 2}, {3, 4}, {5}}));
  EXPECT_EQ(chunkFrames({1, 3, 5}, 8), (std::vector<std::vector<int>>{{1, 3, 5}}));
  EXPECT_EQ(chunkFrames({}, 3), (std::vector<std::vector<int>>{}));
  EXPECT_EQ(errorOf([] { chunkFrames({1}, 0); }), "--chunk: expected a positive number of frames, got 0");
}

TEST(FarmPlan, TaskScriptMapsEachArrayTaskToItsChunk) {
  const FarmPlan plan = twoChunkPlan("/shared/out");
  const std::string script = taskScript(plan, plan.shots[0]);
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(script.find("#SBATCH --job-name=stirrup:trot_side\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --output=/shared/out/farm/logs/trot_side.%A_%a.log\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --partition=main\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --time=30:00\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --cpus-per-task=2\n"), std::string::npos);
  EXPECT_EQ(script.find("--account"), std::string::npos);  // not given: the site's default
  EXPECT_NE(script.find("  1) frames=1-5x2 ;;\n  2) frames=7,9 ;;\n"), std::string::npos);
  // Quoted for the shell, the quote inside a word included.
  EXPECT_NE(script.find("exec '/opt/stirrup/bin/stirrup' 'movies' '--out' '/shared/out' '--only' 'trot_side' '--date' "
                        "'it'\\''s' --threads \"${SLURM_CPUS_PER_TASK:-1}\" --frames \"$frames\"\n"),
            std::string::npos)
      << script;
}

TEST(FarmPlan, TaskScriptRunsEachChunkThroughBash) {
  // The script itself, run by bash as Slurm would with a task id, must start the command with its chunk.
  const fs::path dir = scratch("bash");
  FarmPlan plan = twoChunkPlan(dir);
  plan.shots[0].command = {"/bin/echo", "stirrup"};
  writeScripts(plan);
  const fs::path script = scriptFile(plan, "trot_side");
  auto run = [&](const std::string& task) {
    const std::string cmd = "SLURM_ARRAY_TASK_ID=" + task + " SLURM_CPUS_PER_TASK=3 bash " + script.string() + " 2>&1";
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    char buf[512];
    while (fgets(buf, sizeof buf, p)) out += buf;
    pclose(p);
    return out;
  };
  EXPECT_EQ(run("2"), "stirrup --threads 3 --frames 7,9\n");
  EXPECT_EQ(run("1"), "stirrup --threads 3 --frames 1-5x2\n");
  EXPECT_EQ(run("3"), "stirrup farm: trot_side has no chunk 3\n");
  EXPECT_TRUE(fs::is_directory(logDir(plan)));
  EXPECT_TRUE(fs::is_regular_file(finishScriptFile(plan)));
  fs::remove_all(dir);
}

TEST(FarmPlan, ManifestReadsBackAsWritten) {
  const fs::path dir = scratch("manifest");
  const FarmPlan plan = twoChunkPlan(dir);
  writeManifest(plan);
  const FarmPlan back = readManifest(dir);
  EXPECT_EQ(back.out, plan.out);
  EXPECT_EQ(back.kind, "movies");
  EXPECT_EQ(back.submitted, plan.submitted);
  EXPECT_EQ(back.sbatch.partition, "main");
  EXPECT_EQ(back.sbatch.cpus_per_task, 2);
  ASSERT_EQ(back.shots.size(), 1u);
  EXPECT_EQ(back.shots[0].command, plan.shots[0].command);
  EXPECT_EQ(back.shots[0].outputs, plan.shots[0].outputs);
  EXPECT_EQ(back.shots[0].array_jobs, std::vector<std::string>{"41"});
  ASSERT_EQ(back.shots[0].chunks.size(), 2u);
  EXPECT_EQ(back.shots[0].chunks[0].frames, (std::vector<int>{1, 3, 5}));
  EXPECT_EQ(back.shots[0].chunks[1].files, plan.shots[0].chunks[1].files);
  EXPECT_EQ(back.finish_command, plan.finish_command);
  EXPECT_EQ(back.finish_jobs, std::vector<std::string>{"42"});
  fs::remove_all(dir);
}

// A render shot's framed camera reads back to the bit (17 significant digits), and a bad one is a
// one-line error naming the file and the camera's field.
TEST(FarmPlan, APlannedCameraReadsBackToTheBitAndABadOneNamesItsField) {
  const fs::path dir = scratch("camera");
  FarmPlan plan = twoChunkPlan(dir);
  PlannedCamera c;
  c.name = "side";
  c.key = "0123456789abcdef";
  c.position = {0.1, -1.0 / 3.0, 1234.5678901234567};
  c.target = {2.0 / 3.0, 100.0, -0.0};
  c.up = {0.0, 1.0, 0.0};
  c.seat_from_pivot_cm = {35.25, 61.0, 1e-300};
  c.ortho_height_cm = 317.77777777777777;
  c.fov_deg = 26.991466561840441;
  plan.shots[0].camera = c;
  writeManifest(plan);
  const FarmPlan back = readManifestFile(manifestFile(dir));
  ASSERT_TRUE(back.shots[0].camera.has_value());
  const PlannedCamera& b = *back.shots[0].camera;
  EXPECT_EQ(b.name, c.name);
  EXPECT_EQ(b.key, c.key);
  EXPECT_EQ(b.position, c.position);
  EXPECT_EQ(b.target, c.target);
  EXPECT_EQ(b.up, c.up);
  EXPECT_EQ(b.seat_from_pivot_cm, c.seat_from_pivot_cm);
  EXPECT_EQ(b.ortho_height_cm, c.ortho_height_cm);
  EXPECT_EQ(b.fov_deg, c.fov_deg);

  const std::string file = manifestFile(dir).string();
  const auto broken = [&](const std::function<void(PlannedCamera&)>& change) {
    FarmPlan p = plan;
    change(*p.shots[0].camera);
    writeManifest(p);
    return errorOf([&] { readManifest(dir); });
  };
  EXPECT_EQ(broken([](PlannedCamera& k) { k.fov_deg = 180.0; }),
            file + ": shots[0].camera.fov_deg: expected a number between 0 and 180");
  EXPECT_EQ(broken([](PlannedCamera& k) { k.ortho_height_cm = -2.0; }),
            file + ": shots[0].camera.ortho_height_cm: expected a number above 0");
  EXPECT_EQ(broken([](PlannedCamera& k) { k.target = k.position; }),
            file + ": shots[0].camera.target: expected a point other than the camera's position");
  EXPECT_EQ(broken([](PlannedCamera& k) { k.up = {0.0, 0.0, 0.0}; }), file + ": shots[0].camera.up: expected a direction, not 0 0 0");
  // Hand-edited: a missing field, a word for a number.
  std::string text;
  writeManifest(plan);
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto rewrite = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    ASSERT_NE(t.find(from), std::string::npos) << from;
    t.replace(t.find(from), from.size(), to);
    std::ofstream(file) << t;
  };
  rewrite("\"key\": \"0123456789abcdef\",", "");
  EXPECT_EQ(errorOf([&] { readManifest(dir); }), file + ": shots[0].camera.key: expected a string (missing)");
  const std::size_t fov = text.find("\"fov_deg\": ");
  ASSERT_NE(fov, std::string::npos);
  rewrite(text.substr(fov, text.find_first_of(",\n}", fov) - fov), "\"fov_deg\": \"wide\"");
  const std::string wide = errorOf([&] { readManifest(dir); });
  EXPECT_EQ(wide.rfind(file + ": shots[0].camera.fov_deg: ", 0), 0u) << wide;
  EXPECT_EQ(wide.find('\n'), std::string::npos);
  fs::remove_all(dir);
}

TEST(FarmPlan, ABrokenManifestIsAOneLineErrorNamingTheField) {
  const fs::path dir = scratch("broken");
  const std::string file = manifestFile(dir).string();
  EXPECT_EQ(errorOf([&] { readManifest(dir); }),
            file + ": no farm manifest here (expected the output folder of stirrup farm submit)");
  writeManifest(twoChunkPlan(dir));
  std::string text;
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto rewrite = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    std::ofstream(file) << t;
  };
  rewrite("\"frames\": \"7,9\"", "\"frames\": \"7-\"");
  EXPECT_EQ(errorOf([&] { readManifest(dir); }),
            file + ": shots[0].chunks[1].frames: \"7-\": expected a range FIRST-LAST[xSTEP] of whole numbers");
  rewrite("\"kind\": \"movies\"", "\"kind\": \"films\"");
  EXPECT_NE(errorOf([&] { readManifest(dir); }).find("kind"), std::string::npos);
  EXPECT_EQ(errorOf([&] { readManifest(dir); }).find('\n'), std::string::npos);
  rewrite("\"array_jobs\": [\n        \"41\"\n      ]", "\"array_jobs\": 41");
  EXPECT_NE(errorOf([&] { readManifest(dir); }).find("shots[0].array_jobs"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stirrup::render
