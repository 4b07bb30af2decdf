#include "render/farm/slurm.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "tests/input_error.h"

namespace stirrup::render {
namespace {

using test::errorOf;

TEST(Slurm, RunProgramCapturesBothStreamsAndTheExitCode) {
  const ProgramResult r = runProgram({"sh", "-c", "echo out; echo err >&2; exit 3"});
  EXPECT_TRUE(r.started);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.out, "out\n");
  EXPECT_EQ(r.err, "err\n");
}

TEST(Slurm, RunProgramDrainsLargeOutputOnBothStreams) {
  // 1 MB on each stream, more than a pipe holds: reading one while the other fills must not hang.
  const ProgramResult r = runProgram({"sh", "-c", "head -c 1000000 /dev/zero; head -c 1000000 /dev/zero >&2"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out.size(), 1000000u);
  EXPECT_EQ(r.err.size(), 1000000u);
}

TEST(Slurm, RunProgramSaysWhenAProgramIsMissing) {
  const ProgramResult r = runProgram({"stirrup-no-such-program"});
  EXPECT_FALSE(r.started);
}

// PATH is this process's: the Slurm commands are looked up in it, so an empty one hides them.
class NoSlurmOnPath : public ::testing::Test {
 protected:
  void SetUp() override {
    saved_ = std::getenv("PATH");
    setenv("PATH", "/nonexistent", 1);
  }
  void TearDown() override { setenv("PATH", saved_.c_str(), 1); }
  std::string saved_;
};

TEST_F(NoSlurmOnPath, RequireSlurmIsAOneLineError) {
  EXPECT_EQ(errorOf([] { requireSlurm(); }),
            "farm: Slurm is not reachable: sbatch is not on PATH (install slurm-wlm, load the site's Slurm module, "
            "or start a local cluster with scripts/slurm-local up)");
  EXPECT_EQ(errorOf([] { sbatch("job.sbatch", {}); }),
            "farm: sbatch not found on PATH (install slurm-wlm, load the site's Slurm module, or start a local cluster "
            "with scripts/slurm-local up)");
}

TEST(Slurm, RunProgramStopsAProgramPastItsTimeLimit) {
  const auto start = std::chrono::steady_clock::now();
  const ProgramResult r = runProgram({"sleep", "30"}, 0.3);
  EXPECT_TRUE(r.timed_out);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

TEST(Slurm, NoControllerIsAOneLineError) {
  // The commands are there but no controller answers: a slurm.conf naming one on a port nothing listens on.
  if (!runProgram({"sinfo", "--version"}).started) GTEST_SKIP() << "Slurm's commands are not installed";
  const std::filesystem::path conf =
      std::filesystem::temp_directory_path() / ("stirrup_dead_slurm_" + std::to_string(::getpid()) + ".conf");
  std::ofstream(conf) << "ClusterName=dead\nSlurmctldHost=localhost\nSlurmctldPort=6899\n"
                         "NodeName=localhost CPUs=1 State=UNKNOWN\nPartitionName=main Nodes=localhost Default=YES\n";
  const char* saved = std::getenv("SLURM_CONF");
  const std::string saved_conf = saved ? saved : "";
  setenv("SLURM_CONF", conf.c_str(), 1);
  const std::string error = errorOf([] { requireSlurm(); });
  if (saved) setenv("SLURM_CONF", saved_conf.c_str(), 1);
  else unsetenv("SLURM_CONF");
  std::filesystem::remove(conf);
  EXPECT_EQ(error.rfind("farm: Slurm is not reachable: no controller answers sinfo", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

}  // namespace
}  // namespace stirrup::render
