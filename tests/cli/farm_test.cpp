// stirrup farm end to end on a real Slurm cluster: the local one-node cluster of scripts/slurm-local,
// started by CTest's fixture (tests/CMakeLists.txt: Farm.SlurmUp before, Farm.SlurmDown after). Every
// Farm.* test is reported skipped, never passed, where no cluster answers; FarmWithoutACluster.* needs
// none and always runs. Small shots (a few frames, 96x54)
// keep it quick; the fault test renders frames large enough that a task can be cancelled mid-chunk.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <unistd.h>

#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

bool clusterAnswers() { return runCommand("sinfo -h -o %P").exit_code == 0; }

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / ("test_farm_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

std::string bytes(const fs::path& file) { return readText(file); }

// Every regular file under `dir`, relative, with its bytes.
std::map<std::string, std::string> filesUnder(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = bytes(e.path());
  return files;
}

std::string probeFrames(const fs::path& movie) {
  return runCommand("ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames -of csv=p=0 " +
                    quote(movie.string()))
      .out;
}

int queuedJobs() {
  const CommandResult r = runCommand("squeue -h -o %i");
  return static_cast<int>(lineCount(r.out));
}

// The same small movie set, locally and on the farm: frames kept so they can be compared.
const std::string kSmallSet =
    "--frames-limit 4 --preset draft --resolution 96x54 --date 2026-01-01 --keep-frames";

TEST(Farm, TwoShotsRenderByteIdenticalToALocalRenderAndTheFinishingJobMakesTheMovies) {
  if (!clusterAnswers()) GTEST_SKIP() << "no Slurm cluster answers (scripts/slurm-local up needs root)";
  const fs::path local = scratch("local"), farm = scratch("farm");
  const CommandResult l = runStirrup("movies --only trot_side,jump_side " + kSmallSet + " --out " + quote(local.string()));
  ASSERT_EQ(l.exit_code, 0) << l.err;

  const CommandResult s =
      runStirrup("farm submit --movies --only trot_side,jump_side " + kSmallSet + " --chunk 3 --out " + quote(farm.string()));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  // The job ids, one array a shot (4 frames in chunks of 3: 2 tasks) and the finishing job, then the manifest.
  EXPECT_TRUE(std::regex_search(s.out, std::regex("trot_side +job [0-9]+ \\(2 tasks\\)\n"))) << s.out;
  EXPECT_TRUE(std::regex_search(s.out, std::regex("jump_side +job [0-9]+ \\(2 tasks\\)\n"))) << s.out;
  EXPECT_TRUE(std::regex_search(s.out, std::regex("finish +job [0-9]+ \\(after all of them\\)\n"))) << s.out;
  EXPECT_NE(s.out.find((farm / "farm.json").string()), std::string::npos);

  const CommandResult st = runStirrup("farm status --wait " + quote(farm.string()));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  EXPECT_NE(st.out.find("  trot_side  finished\n"), std::string::npos) << st.out;
  EXPECT_NE(st.out.find("  jump_side  finished\n"), std::string::npos) << st.out;
  EXPECT_NE(st.out.find("\ncomplete\n"), std::string::npos) << st.out;

  // Every frame, contact sheet and plot, byte for byte; and the movies, frame for frame.
  const auto local_frames = filesUnder(local / "frames"), farm_frames = filesUnder(farm / "frames");
  ASSERT_EQ(local_frames.size(), 2u * 5u);  // 4 frames and a slate each
  ASSERT_EQ(farm_frames.size(), local_frames.size());
  for (const auto& [name, content] : local_frames) {
    ASSERT_TRUE(farm_frames.count(name)) << name;
    EXPECT_TRUE(farm_frames.at(name) == content) << name << " differs";
  }
  for (const char* file : {"trot_side_sheet.png", "jump_side_sheet.png", "trot_plot.png", "jump_plot.png"})
    EXPECT_TRUE(bytes(local / file) == bytes(farm / file)) << file << " differs";
  for (const char* movie : {"trot_side.mp4", "jump_side.mp4"}) {
    EXPECT_EQ(probeFrames(farm / movie), "28\n") << movie;  // a 24-frame slate and 4 frames
    EXPECT_EQ(probeFrames(farm / movie), probeFrames(local / movie)) << movie;
  }
  EXPECT_TRUE(fs::is_regular_file(farm / "index.html"));
  fs::remove_all(local);
  fs::remove_all(farm);
}

// A glTF shot's movies (issue 60), with a scene's look: the trot's first 4 frames baked, its side movie
// made by `stirrup movies SHOT.glb --scene trot.json` and by the farm, frame for frame the same.
TEST(Farm, AShotsMoviesRenderOnTheFarmAsLocally) {
  if (!clusterAnswers()) GTEST_SKIP() << "no Slurm cluster answers (scripts/slurm-local up needs root)";
  const fs::path local = scratch("shot_local"), farm = scratch("shot_farm"), baked = scratch("shot_bake") / "trot_shot.glb";
  const std::string scene = quote(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  ASSERT_EQ(runStirrup("bake " + scene + " --frames 1-4 -o " + quote(baked.string())).exit_code, 0);
  const std::string shot = quote(baked.string()) + " --scene " + scene + " --only side " + kSmallSet;
  const CommandResult l = runStirrup("movies " + shot + " --out " + quote(local.string()));
  ASSERT_EQ(l.exit_code, 0) << l.err;
  const CommandResult s = runStirrup("farm submit " + shot + " --movies --chunk 3 --out " + quote(farm.string()));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_TRUE(std::regex_search(s.out, std::regex("trot_shot_side +job [0-9]+ \\(2 tasks\\)\n"))) << s.out;
  const CommandResult st = runStirrup("farm status --wait " + quote(farm.string()));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  EXPECT_NE(st.out.find("\ncomplete\n"), std::string::npos) << st.out;
  // The tasks ran the shot with its look (absolute paths), as the local command did.
  EXPECT_NE(readText(farm / "farm.json").find("--scene"), std::string::npos);
  const auto local_frames = filesUnder(local / "frames"), farm_frames = filesUnder(farm / "frames");
  ASSERT_EQ(local_frames.size(), 5u);  // 4 frames and a slate
  ASSERT_EQ(farm_frames.size(), local_frames.size());
  for (const auto& [name, content] : local_frames) {
    ASSERT_TRUE(farm_frames.count(name)) << name;
    EXPECT_TRUE(farm_frames.at(name) == content) << name << " differs";
  }
  EXPECT_TRUE(bytes(local / "trot_shot_side_sheet.png") == bytes(farm / "trot_shot_side_sheet.png"));
  EXPECT_EQ(probeFrames(farm / "trot_shot_side.mp4"), "28\n");
  EXPECT_EQ(probeFrames(farm / "trot_shot_side.mp4"), probeFrames(local / "trot_shot_side.mp4"));
  // A scene's movies with --movies and a glTF look are refused before anything is submitted.
  const CommandResult bad = runStirrup("farm submit " + scene + " --movies --out " + quote(scratch("shot_bad").string()));
  EXPECT_NE(bad.exit_code, 0);
  fs::remove_all(local);
  fs::remove_all(farm);
}

TEST(Farm, ASingleSceneRendersThroughItsCameraAndEncodes) {
  if (!clusterAnswers()) GTEST_SKIP() << "no Slurm cluster answers (scripts/slurm-local up needs root)";
  const fs::path local = scratch("render_local"), farm = scratch("render_farm");
  const std::string scene = quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "trot.json").string());
  const std::string shot = scene + " --camera side --frames 1-5 --preset draft --resolution 96x54";
  ASSERT_EQ(runStirrup("render " + shot + " --out " + quote(local.string())).exit_code, 0);
  const CommandResult s = runStirrup("farm submit " + shot + " --chunk 2 --out " + quote(farm.string()));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_TRUE(std::regex_search(s.out, std::regex("trot_side +job [0-9]+ \\(3 tasks\\)\n"))) << s.out;
  const CommandResult st = runStirrup("farm status --wait " + quote(farm.string()));
  EXPECT_NE(st.out.find("\ncomplete\n"), std::string::npos) << st.out << st.err;
  for (int f = 1; f <= 5; ++f) {
    const std::string name = "trot_side.000" + std::to_string(f) + ".png";
    EXPECT_TRUE(bytes(local / name) == bytes(farm / name)) << name << " differs";
  }
  EXPECT_EQ(probeFrames(farm / "trot_side.mp4"), "5\n");
  fs::remove_all(local);
  fs::remove_all(farm);
}

// A scene beyond a horse's limits (a walk at 900 cm/s) is refused by farm submit before anything is
// submitted; with --allow-impossible it renders on the farm, every task given the flag.
TEST(Farm, AnImpossibleSceneIsSubmittedOnlyWithAllowImpossible) {
  if (!clusterAnswers()) GTEST_SKIP() << "no Slurm cluster answers (scripts/slurm-local up needs root)";
  const fs::path farm = scratch("impossible"), scenes = scratch("impossible_scene");
  fs::create_directories(scenes);
  const fs::path scene = scenes / "walk900.json";
  std::ofstream(scene) << R"({"frames": "1-2", "clip": {"generator": "walk", "speed_cm_s": 900}})";
  const std::string shot = quote(scene.string()) + " --camera side --preset draft --resolution 96x54 --chunk 2 --out " + quote(farm.string());
  const CommandResult refused = runStirrup("farm submit " + shot);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find(": clip.speed_cm_s: 900 cm/s is faster than a horse walks (at most 250 cm/s: "), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(farm / "farm.json"));
  const CommandResult s = runStirrup("farm submit " + shot + " --allow-impossible");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_NE(bytes(farm / "farm.json").find("--allow-impossible"), std::string::npos);
  const CommandResult st = runStirrup("farm status --wait " + quote(farm.string()));
  EXPECT_NE(st.out.find("\ncomplete\n"), std::string::npos) << st.out << st.err;
  EXPECT_TRUE(fs::exists(farm / "walk900_side.0002.png"));
  fs::remove_all(farm);
  fs::remove_all(scenes);
}

// The state squeue gives a job or array task ("12_2"), or "" once it has left the queue.
std::string taskState(const std::string& id) {
  const CommandResult r = runCommand("squeue -h -r -t all -o '%i %T'");
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(id + " ", 0) == 0) return line.substr(id.size() + 1);
  return "";
}

TEST(Farm, ACancelledTaskIsFoundByStatusAndRedoneByResume) {
  if (!clusterAnswers()) GTEST_SKIP() << "no Slurm cluster answers (scripts/slurm-local up needs root)";
  // Frames big enough (final quality, 320x180, 8 a chunk: about 5 s a task) that a task can be caught running.
  const std::string set = "--only trot_side --frames-limit 16 --preset final --resolution 320x180 --date 2026-01-01 --keep-frames";
  const fs::path local = scratch("fault_local"), farm = scratch("fault_farm");
  const CommandResult s = runStirrup("farm submit --movies " + set + " --chunk 8 --out " + quote(farm.string()));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(s.out, m, std::regex("trot_side +job ([0-9]+)"))) << s.out;
  const std::string task = m[1].str() + "_2";

  // Cancel task 2 while it runs, before its chunk is done.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (taskState(task) != "RUNNING" && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(taskState(task), "RUNNING");
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // a frame or so in: some files, not all
  ASSERT_EQ(runCommand("scancel " + task).exit_code, 0);

  const CommandResult st = runStirrup("farm status --wait " + quote(farm.string()));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  // Chunk 2 is frames 9-16; the status names it, what Slurm said of it, and what to do.
  EXPECT_TRUE(std::regex_search(st.out, std::regex("    chunk 2 \\(frames 9-16\\): missing, [0-9]+ files not written; "
                                                   "Slurm task " + task + " CANCELLED\n")))
      << st.out;
  EXPECT_NE(st.out.find("  trot_side  1/2 chunks done, 1 missing"), std::string::npos) << st.out;
  EXPECT_NE(st.out.find("incomplete: stirrup farm resume " + farm.string()), std::string::npos) << st.out;
  EXPECT_FALSE(fs::exists(farm / "trot_side.mp4"));  // the finishing job never ran

  const CommandResult r = runStirrup("farm resume " + quote(farm.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("resubmitted trot_side chunk 2 (frames 9-16)\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("chunk 1"), std::string::npos) << r.out;  // only what is missing
  const CommandResult done = runStirrup("farm status --wait " + quote(farm.string()));
  EXPECT_NE(done.out.find("\ncomplete\n"), std::string::npos) << done.out << done.err;

  // Byte-identical to a local render, and nothing partial anywhere.
  ASSERT_EQ(runStirrup("movies " + set + " --out " + quote(local.string())).exit_code, 0);
  const auto local_frames = filesUnder(local / "frames"), farm_frames = filesUnder(farm / "frames");
  ASSERT_EQ(farm_frames.size(), local_frames.size());
  for (const auto& [name, content] : local_frames) EXPECT_TRUE(farm_frames.count(name) && farm_frames.at(name) == content) << name;
  EXPECT_TRUE(bytes(local / "trot_side_sheet.png") == bytes(farm / "trot_side_sheet.png"));
  for (const auto& e : fs::recursive_directory_iterator(farm))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  fs::remove_all(local);
  fs::remove_all(farm);
}

TEST(Farm, BadInputIsAOneLineErrorAndSubmitsNothing) {
  if (!clusterAnswers()) GTEST_SKIP() << "no Slurm cluster answers (scripts/slurm-local up needs root)";
  const fs::path out = scratch("bad");
  const std::string submit = "farm submit --movies --only trot_side --frames-limit 2 --preset draft --out ";
  const int before = queuedJobs();
  auto expectError = [&](const CommandResult& r, const std::string& starts) {
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_EQ(r.err.rfind("stirrup: " + starts, 0), 0u) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.out, "");
  };
  expectError(runStirrup(submit + quote(out.string()) + " --chunk 0"),
              "--chunk: expected a positive number of frames a task, got 0");
  expectError(runStirrup(submit + quote(out.string()) + " --chunk -3"),
              "--chunk: expected a positive number of frames a task, got -3");
  expectError(runStirrup(submit + quote(out.string()) + " --partition nosuch"),
              "--partition: no partition \"nosuch\" on this cluster (expected one of ");
  expectError(runStirrup(submit + "/dev/shm/stirrup_farm_bad"), "--out: /dev/shm/stirrup_farm_bad: on tmpfs");
  expectError(runStirrup(submit + "/proc/stirrup_farm_bad"), "--out: /proc/stirrup_farm_bad: cannot make the folder");
  const fs::path dead = scratch("dead.conf");
  std::ofstream(dead) << "ClusterName=dead\nSlurmctldHost=localhost\nSlurmctldPort=6899\n"
                         "NodeName=localhost CPUs=1 State=UNKNOWN\nPartitionName=main Nodes=localhost Default=YES\n";
  expectError(runCommand("SLURM_CONF=" + quote(dead.string()) + " " + quote(STIRRUP_EXE) + " " + submit + quote(out.string())),
              "farm: Slurm is not reachable: no controller answers sinfo");
  expectError(runCommand("PATH=/nonexistent " + quote(STIRRUP_EXE) + " " + submit + quote(out.string())),
              "farm: Slurm is not reachable: sbatch is not on PATH");
  EXPECT_EQ(queuedJobs(), before);
  EXPECT_FALSE(fs::exists(out / "farm.json"));
  EXPECT_FALSE(fs::exists(out / "farm"));
  fs::remove_all(out);
  fs::remove_all("/dev/shm/stirrup_farm_bad");
  fs::remove(dead);
}

TEST(Farm, TheInstalledProgramRendersOnTheFarmFromAnyFolder) {
  // A studio submits with the installed stirrup (docs/install.md), from a folder of its own: the scripts
  // must run that program, which finds its scenes beside itself, not in the source tree.
  if (!clusterAnswers()) GTEST_SKIP() << "no Slurm cluster answers (scripts/slurm-local up needs root)";
  const fs::path root = fs::temp_directory_path() / ("stirrup_farm_install_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const fs::path prefix = root / "prefix", work = root / "work", farm = scratch("installed");
  fs::create_directories(work);
  const CommandResult install = runCommand(quote(STIRRUP_CMAKE) + " --install " + quote(STIRRUP_BINARY_DIR) + " --prefix " +
                                           quote(prefix.string()));
  ASSERT_EQ(install.exit_code, 0) << install.err << install.out;
  const std::string installed = (prefix / "bin/stirrup").string();
  const CommandResult s = runCommand("cd " + quote(work.string()) + " && " + quote(installed) +
                                     " farm submit scenes/walk.json --camera persp --frames 1-4 --preset draft "
                                     "--resolution 96x54 --chunk 2 --out " + quote(farm.string()));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_NE(readText(farm / "farm/walk_persp.sbatch").find("exec '" + installed + "' 'render' '" +
                                                           (prefix / "share/stirrup/scenes/walk.json").string() + "'"),
            std::string::npos)
      << readText(farm / "farm/walk_persp.sbatch");
  const CommandResult st = runStirrup("farm status --wait " + quote(farm.string()));
  EXPECT_NE(st.out.find("\ncomplete\n"), std::string::npos) << st.out << st.err;
  // The same frames as the build tree's program renders.
  const fs::path local = scratch("installed_local");
  ASSERT_EQ(runStirrup("render " + quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes/walk.json").string()) +
                       " --camera persp --frames 1-4 --preset draft --resolution 96x54 --out " + quote(local.string()))
                .exit_code,
            0);
  for (int f = 1; f <= 4; ++f) {
    const std::string name = "walk_persp.000" + std::to_string(f) + ".png";
    EXPECT_TRUE(fs::exists(farm / name) && bytes(local / name) == bytes(farm / name)) << name;
  }
  EXPECT_EQ(probeFrames(farm / "walk_persp.mp4"), "4\n");
  fs::remove_all(root);
  fs::remove_all(farm);
  fs::remove_all(local);
}

// Needs no cluster, and is registered apart from the cluster's tests (tests/CMakeLists.txt): the
// manifest is read before Slurm is asked anything.
TEST(FarmWithoutACluster, StatusOfAFolderWithoutAFarmIsAOneLineError) {
  const fs::path out = scratch("none");
  fs::create_directories(out);
  const CommandResult r = runStirrup("farm status " + quote(out.string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "stirrup: " + (out / "farm.json").string() +
                       ": no farm manifest here (expected the output folder of stirrup farm submit)\n");
  fs::remove_all(out);
}

}  // namespace
}  // namespace stirrup::test
