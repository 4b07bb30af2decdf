// The farm job lifecycle (render/farm/farm_jobs.cpp) against fake Slurm commands: sbatch, squeue,
// sacct and scancel are small shell scripts put first on PATH, which log what stirrup asked (sbatch and
// scancel, with their arguments) and answer from files the test writes (the next job id, which sbatch
// call fails, what squeue and sacct print). So submission and its rollback, every state Slurm reports
// and what resume resubmits are checked on every test run, without root or a cluster; the real cluster
// runs the same code end to end in tests/cli/farm_test.cpp.
#include "render/farm/farm_jobs.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "render/farm/farm_plan.h"
#include "tests/input_error.h"

namespace stirrup::render {

// Test output names the state (found by ADL, so outside the anonymous namespace).
void PrintTo(ChunkState s, std::ostream* os);
void PrintTo(ChunkState s, std::ostream* os) {
  static const char* const kNames[] = {"done", "pending", "running", "missing"};
  *os << kNames[static_cast<int>(s)];
}

namespace {

namespace fs = std::filesystem;
using test::errorOf;

std::string readFile(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t nl = text.find('\n', start);
    lines.push_back(text.substr(start, nl - start));
    if (nl == std::string::npos) break;
    start = nl + 1;
  }
  return lines;
}

// A scratch folder with the fake commands in bin/ (first on PATH while a test runs), their state in
// state/ and the farm's output folder in out/.
class FakeSlurm : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    root_ = fs::temp_directory_path() / ("stirrup_fake_slurm_" + test + "_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "bin");
    fs::create_directories(state());
    fs::create_directories(out());
    const std::string s = state().string();
    // sbatch: logs its arguments, counts its calls, fails the call named in sbatch_fails_at, otherwise
    // prints the next job id (--parsable's form).
    writeScript("sbatch", "echo \"sbatch $*\" >> '" + s + "/calls'\n"
                     "n=$(( $(cat '" + s + "/sbatch_count' 2>/dev/null || echo 0) + 1 ))\n"
                     "echo $n > '" + s + "/sbatch_count'\n"
                     "if [ \"$(cat '" + s + "/sbatch_fails_at' 2>/dev/null)\" = \"$n\" ]; then\n"
                     "  echo 'sbatch: error: Batch job submission failed: Invalid partition name specified' >&2\n"
                     "  exit 1\n"
                     "fi\n"
                     "id=$(cat '" + s + "/next_id')\n"
                     "echo $((id + 1)) > '" + s + "/next_id'\n"
                     "echo $id\n");
    // squeue: what the controller knows ("%i %T" lines), from the file squeue.
    writeScript("squeue", "cat '" + s + "/squeue' 2>/dev/null\nexit 0\n");
    // sacct: accounting, from the file sacct ("JobID|State" lines); without it, as on a cluster that
    // keeps no accounting, an error.
    writeScript("sacct", "if [ -f '" + s + "/sacct' ]; then cat '" + s + "/sacct'; exit 0; fi\n"
                    "echo 'sacct: error: Slurm accounting storage is disabled' >&2\nexit 1\n");
    // scancel: logs its arguments; refuses when scancel_fails exists.
    writeScript("scancel", "echo \"scancel $*\" >> '" + s + "/calls'\n"
                      "if [ -f '" + s + "/scancel_fails' ]; then\n"
                      "  echo \"scancel: error: Kill job error on job id $1: Access/permission denied\" >&2\n"
                      "  exit 1\n"
                      "fi\n");
    write("next_id", "101\n");
    const char* path = std::getenv("PATH");
    saved_path_ = path ? path : "";
    setenv("PATH", ((root_ / "bin").string() + ":" + saved_path_).c_str(), 1);
  }
  void TearDown() override {
    setenv("PATH", saved_path_.c_str(), 1);
    fs::remove_all(root_);
  }

  fs::path state() const { return root_ / "state"; }
  fs::path out() const { return root_ / "out"; }
  void write(const std::string& name, const std::string& text) const { std::ofstream(state() / name) << text; }
  // What sbatch and scancel were asked, one line a call.
  std::vector<std::string> calls() const { return linesOf(readFile(state() / "calls")); }
  // A shot of `chunks` chunks of two frames each (chunk i: frames 2i-1, 2i, one file a frame).
  FarmShot shot(const std::string& name, int chunks) const {
    FarmShot s;
    s.name = name;
    s.command = {"/bin/true"};
    s.frames_dir = "frames/" + name;
    s.outputs = {name + ".mp4"};
    for (int i = 1; i <= chunks; ++i) {
      FarmChunk c;
      c.task = i;
      c.frames = {2 * i - 1, 2 * i};
      for (int f : c.frames) c.files.push_back(s.frames_dir + "/" + name + "." + std::to_string(f) + ".png");
      s.chunks.push_back(c);
    }
    return s;
  }
  FarmPlan plan(std::vector<FarmShot> shots) const {
    FarmPlan p;
    p.out = out();
    p.kind = "movies";
    p.submitted = "2026-11-25 06:00:00";
    p.shots = std::move(shots);
    p.finish_command = {"/bin/true"};
    return p;
  }
  // Writes the files of a chunk, as a task that finished it would.
  void finishChunk(const FarmShot& s, int task) const {
    fs::create_directories(out() / s.frames_dir);
    for (const std::string& f : s.chunks[static_cast<std::size_t>(task - 1)].files) std::ofstream(out() / f) << "png";
  }
  std::string script(const FarmPlan& p, const std::string& shot) const { return scriptFile(p, shot).string(); }

 private:
  void writeScript(const std::string& name, const std::string& body) const {
    const fs::path file = root_ / "bin" / name;
    std::ofstream(file) << "#!/bin/sh\n" << body;
    ::chmod(file.c_str(), 0755);
  }
  fs::path root_;
  std::string saved_path_;
};

// One job array a shot (--array=1-N), then the finishing job after all of them (afterok), removed by
// Slurm if one fails; the ids are recorded in the plan and in the manifest.
TEST_F(FakeSlurm, SubmitSendsAnArrayAShotThenTheFinishingJobAfterThem) {
  FarmPlan p = plan({shot("trot_side", 2), shot("jump_side", 3)});
  submitPlan(p);
  EXPECT_EQ(calls(), (std::vector<std::string>{
                         "sbatch --parsable --array=1-2 " + script(p, "trot_side"),
                         "sbatch --parsable --array=1-3 " + script(p, "jump_side"),
                         "sbatch --parsable --dependency=afterok:101:102 --kill-on-invalid-dep=yes " + finishScriptFile(p).string(),
                     }));
  EXPECT_EQ(p.shots[0].array_jobs, std::vector<std::string>{"101"});
  EXPECT_EQ(p.shots[1].array_jobs, std::vector<std::string>{"102"});
  EXPECT_EQ(p.finish_jobs, std::vector<std::string>{"103"});
  const FarmPlan back = readManifest(out());
  EXPECT_EQ(back.shots[1].array_jobs, std::vector<std::string>{"102"});
  EXPECT_EQ(back.finish_jobs, std::vector<std::string>{"103"});
}

// When a later sbatch fails, the jobs already submitted are cancelled and sbatch's error is the one
// reported: nothing is left half submitted, and no manifest claims jobs.
TEST_F(FakeSlurm, AFailedSbatchCancelsWhatWasSubmittedBeforeIt) {
  const std::string refused =
      "farm: sbatch failed (exit 1): sbatch: error: Batch job submission failed: Invalid partition name specified";
  {
    FarmPlan p = plan({shot("trot_side", 2), shot("jump_side", 3)});
    write("sbatch_fails_at", "2\n");  // the second shot's array
    EXPECT_EQ(errorOf([&] { submitPlan(p); }), refused);
    EXPECT_EQ(calls(), (std::vector<std::string>{"sbatch --parsable --array=1-2 " + script(p, "trot_side"),
                                                 "sbatch --parsable --array=1-3 " + script(p, "jump_side"),
                                                 "scancel 101"}));
    EXPECT_FALSE(fs::exists(manifestFile(out())));
  }
  fs::remove(state() / "calls");
  fs::remove(state() / "sbatch_count");
  {
    FarmPlan p = plan({shot("trot_side", 2), shot("jump_side", 3)});
    write("sbatch_fails_at", "3\n");  // the finishing job
    write("scancel_fails", "");       // and the rollback refused too: the first error is still sbatch's
    EXPECT_EQ(errorOf([&] { submitPlan(p); }), refused);
    ASSERT_EQ(calls().size(), 4u);
    EXPECT_EQ(calls()[3], "scancel 102 103");  // ids go on from the first attempt's
    EXPECT_FALSE(fs::exists(manifestFile(out())));
  }
  fs::remove(state() / "calls");
  fs::remove(state() / "sbatch_count");
  fs::remove(state() / "scancel_fails");
  {
    FarmPlan p = plan({shot("trot_side", 2)});
    write("sbatch_fails_at", "1\n");  // nothing submitted: nothing to cancel
    EXPECT_EQ(errorOf([&] { submitPlan(p); }), refused);
    EXPECT_EQ(calls(), std::vector<std::string>{"sbatch --parsable --array=1-2 " + script(p, "trot_side")});
  }
}

// Every job state squeue(1) lists ("JOB STATE CODES"), for a task whose frames are not all written:
// still to run (pending), running, or ended without its frames (missing: resume redoes it). Grouped by
// hand from the man page's descriptions: held and requeued jobs wait in the queue, and so does a job
// held after its reservation was deleted (RESV_DEL_HOLD); a job with an allocation that is stopping,
// staging out or being signalled still runs; the rest have ended.
TEST_F(FakeSlurm, StatusMapsEverySlurmStateOfATask) {
  const std::vector<std::pair<std::string, ChunkState>> kStates = {
      {"PENDING", ChunkState::Pending},      {"CONFIGURING", ChunkState::Pending},
      {"REQUEUED", ChunkState::Pending},     {"REQUEUE_HOLD", ChunkState::Pending},
      {"REQUEUE_FED", ChunkState::Pending},  {"RESV_DEL_HOLD", ChunkState::Pending},
      {"RESIZING", ChunkState::Pending},     {"SUSPENDED", ChunkState::Pending},
      {"STOPPED", ChunkState::Pending},      {"RUNNING", ChunkState::Running},
      {"COMPLETING", ChunkState::Running},   {"STAGE_OUT", ChunkState::Running},
      {"SIGNALING", ChunkState::Running},    {"COMPLETED", ChunkState::Missing},
      {"FAILED", ChunkState::Missing},       {"CANCELLED", ChunkState::Missing},
      {"TIMEOUT", ChunkState::Missing},      {"NODE_FAIL", ChunkState::Missing},
      {"PREEMPTED", ChunkState::Missing},    {"BOOT_FAIL", ChunkState::Missing},
      {"DEADLINE", ChunkState::Missing},     {"OUT_OF_MEMORY", ChunkState::Missing},
      {"REVOKED", ChunkState::Missing},      {"SPECIAL_EXIT", ChunkState::Missing},
  };
  const int n = static_cast<int>(kStates.size());
  FarmPlan p = plan({shot("trot_side", n + 1)});
  p.shots[0].array_jobs = {"500"};
  p.finish_jobs = {"501"};
  std::string squeue = "999_1 RUNNING\n";  // another user's job: not ours
  for (int i = 0; i < n; ++i) squeue += "500_" + std::to_string(i + 1) + " " + kStates[static_cast<std::size_t>(i)].first + "\n";
  write("squeue", squeue + "501 PENDING\n");
  const FarmStatus st = farmStatus(p);
  ASSERT_EQ(st.shots.size(), 1u);
  ASSERT_EQ(st.shots[0].chunks.size(), static_cast<std::size_t>(n + 1));
  for (int i = 0; i < n; ++i) {
    const ChunkStatus& c = st.shots[0].chunks[static_cast<std::size_t>(i)];
    EXPECT_EQ(c.state, kStates[static_cast<std::size_t>(i)].second) << kStates[static_cast<std::size_t>(i)].first;
    EXPECT_EQ(c.slurm_state, kStates[static_cast<std::size_t>(i)].first);
    EXPECT_EQ(c.job, "500_" + std::to_string(i + 1));
    EXPECT_EQ(c.missing_files, 2);
  }
  // A task Slurm no longer knows, its frames not written: missing, with no Slurm state to name.
  const ChunkStatus& gone = st.shots[0].chunks.back();
  EXPECT_EQ(gone.state, ChunkState::Missing);
  EXPECT_EQ(gone.slurm_state, "");
  EXPECT_EQ(gone.job, "");
  EXPECT_EQ(st.finish_state, "PENDING");
  EXPECT_TRUE(st.active);
  EXPECT_FALSE(st.complete);
}

// The files are the truth about what is done; accounting (sacct) names how a task that has left the
// queue ended; the newest array that ran a chunk has the say; the shot is finished when its outputs
// exist.
TEST_F(FakeSlurm, StatusReadsTheFilesAccountingAndTheNewestArray) {
  FarmPlan p = plan({shot("trot_side", 3)});
  p.shots[0].array_jobs = {"500", "600"};  // submit's, then a resume's
  p.finish_jobs = {"501", "601"};
  finishChunk(p.shots[0], 1);
  write("sacct", "500_1|COMPLETED\n500_2|CANCELLED by 0\n");
  write("squeue", "500_1 FAILED\n600_2 RUNNING\n");  // the controller's word over accounting's
  FarmStatus st = farmStatus(p);
  const auto& c = st.shots[0].chunks;
  EXPECT_EQ(c[0].state, ChunkState::Done);  // its frames are there, whatever Slurm says
  EXPECT_EQ(c[0].slurm_state, "FAILED");
  EXPECT_EQ(c[1].state, ChunkState::Running);  // 600_2 is newer than 500_2's CANCELLED
  EXPECT_EQ(c[1].job, "600_2");
  EXPECT_EQ(c[2].state, ChunkState::Missing);
  EXPECT_EQ(st.finish_state, "");  // 601 has left the queue and accounting does not know it
  EXPECT_TRUE(st.active);
  const std::string text = describeStatus(p, st);
  EXPECT_NE(text.find("  trot_side  1/3 chunks done, 1 running, 1 missing\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    chunk 2 (frames 3-4): running; Slurm task 600_2 RUNNING\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    chunk 3 (frames 5-6): missing, 2 files not written\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  finish     job 601: no longer queued\nin progress\n"), std::string::npos) << text;
  // Once 600_2 has left the queue unaccounted, the older array's word stands: accounting's
  // "CANCELLED by 0" is CANCELLED, and the chunk is missing.
  write("squeue", "");
  st = farmStatus(p);
  EXPECT_EQ(st.shots[0].chunks[1].slurm_state, "CANCELLED");
  EXPECT_EQ(st.shots[0].chunks[1].job, "500_2");
  EXPECT_EQ(st.shots[0].chunks[1].state, ChunkState::Missing);
  EXPECT_FALSE(st.active);
  EXPECT_NE(describeStatus(p, st).find("incomplete: stirrup farm resume " + out().string() + " redoes what is missing\n"),
            std::string::npos);
  // The outputs there: finished, every chunk done, complete.
  std::ofstream(out() / "trot_side.mp4") << "mp4";
  st = farmStatus(p);
  EXPECT_TRUE(st.shots[0].finished);
  EXPECT_EQ(st.shots[0].chunks[2].state, ChunkState::Done);
  EXPECT_TRUE(st.complete);
}

// Resume resubmits only the chunks that are missing and that no task is working on, the same script
// with --array naming those tasks; a new finishing job goes after the new arrays (afterok) and the
// arrays still running (afterany); temporary files are removed only where no task could still be
// writing them; the new jobs are recorded.
TEST_F(FakeSlurm, ResumeRedoesOnlyWhatIsMissingAndNothingRunning) {
  FarmPlan p = plan({shot("trot_side", 3), shot("jump_side", 2)});
  p.shots[0].array_jobs = {"200"};
  p.shots[1].array_jobs = {"201"};
  p.finish_jobs = {"202"};
  writeManifest(p);
  finishChunk(p.shots[0], 1);  // trot_side: chunk 1 done, 2 cancelled, 3 never ran
  std::ofstream(out() / "frames/trot_side/trot_side.3.png.tmp") << "half";
  fs::create_directories(out() / "frames/jump_side");  // jump_side: chunk 1 running, 2 failed
  std::ofstream(out() / "frames/jump_side/jump_side.1.png.tmp") << "being written";
  write("squeue", "200_2 CANCELLED\n201_1 RUNNING\n201_2 FAILED\n");  // 202 was removed (invalid dependency)
  const ResumeResult r = resumePlan(p);
  EXPECT_EQ(calls(), (std::vector<std::string>{
                         "sbatch --parsable --array=2,3 " + script(p, "trot_side"),
                         "sbatch --parsable --array=2 " + script(p, "jump_side"),
                         "sbatch --parsable --dependency=afterok:101:102,afterany:201 --kill-on-invalid-dep=yes " +
                             finishScriptFile(p).string(),
                     }));
  EXPECT_EQ(r.resubmitted, (std::vector<std::string>{"trot_side chunk 2 (frames 3-4)", "trot_side chunk 3 (frames 5-6)",
                                                     "jump_side chunk 2 (frames 3-4)"}));
  EXPECT_EQ(r.array_jobs, "101 102");
  EXPECT_EQ(r.finish_job, "103");
  EXPECT_EQ(r.partial_files_removed, 1);
  EXPECT_FALSE(fs::exists(out() / "frames/trot_side/trot_side.3.png.tmp"));
  EXPECT_TRUE(fs::exists(out() / "frames/jump_side/jump_side.1.png.tmp"));  // 201_1 may be writing it
  const FarmPlan back = readManifest(out());
  EXPECT_EQ(back.shots[0].array_jobs, (std::vector<std::string>{"200", "101"}));
  EXPECT_EQ(back.shots[1].array_jobs, (std::vector<std::string>{"201", "102"}));
  EXPECT_EQ(back.finish_jobs, (std::vector<std::string>{"202", "103"}));
}

// A finishing job still waiting is replaced when new chunks are resubmitted (scancel, then a new one
// after them), and left alone when nothing is missing; a finished plan resumes nothing.
TEST_F(FakeSlurm, ResumeReplacesAWaitingFinishingJobOnlyWhenItSubmitsChunks) {
  FarmPlan p = plan({shot("trot_side", 2)});
  p.shots[0].array_jobs = {"200"};
  p.finish_jobs = {"202"};
  finishChunk(p.shots[0], 1);
  write("squeue", "200_2 RUNNING\n202 PENDING\n");
  ResumeResult r = resumePlan(p);  // nothing missing, the finishing job waits on the running task
  EXPECT_TRUE(r.resubmitted.empty());
  EXPECT_EQ(r.finish_job, "");
  EXPECT_FALSE(fs::exists(state() / "calls"));  // neither sbatch nor scancel
  write("squeue", "200_2 TIMEOUT\n202 PENDING\n");
  r = resumePlan(p);
  EXPECT_EQ(calls(), (std::vector<std::string>{"sbatch --parsable --array=2 " + script(p, "trot_side"), "scancel 202",
                                               "sbatch --parsable --dependency=afterok:101 --kill-on-invalid-dep=yes " +
                                                   finishScriptFile(p).string()}));
  EXPECT_EQ(r.finish_job, "102");
  fs::remove(state() / "calls");
  // Every chunk done but the finishing job gone (it failed): only a new finishing job, after nothing.
  finishChunk(p.shots[0], 2);
  write("squeue", "");
  r = resumePlan(p);
  EXPECT_EQ(calls(), std::vector<std::string>{"sbatch --parsable " + finishScriptFile(p).string()});
  EXPECT_TRUE(r.resubmitted.empty());
  fs::remove(state() / "calls");
  // Finished: nothing at all.
  std::ofstream(out() / "trot_side.mp4") << "mp4";
  r = resumePlan(p);
  EXPECT_FALSE(fs::exists(state() / "calls"));
  EXPECT_TRUE(r.resubmitted.empty());
  EXPECT_EQ(r.finish_job, "");
}

}  // namespace
}  // namespace stirrup::render
