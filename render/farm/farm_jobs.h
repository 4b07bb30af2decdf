// Submitting a farm plan to Slurm, asking what became of it, and redoing what is missing. The files on
// the shared output folder are the truth about what is done (every frame is written to a temporary name
// and renamed, so a file that exists is whole); Slurm says what is still pending or running, and, where
// the cluster keeps accounting, how a finished task ended.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/farm/farm_plan.h"

namespace stirrup::render {

// Submits one job array a shot and the finishing job after them all (afterok); records the job ids in
// the plan and writes the manifest and scripts. When any sbatch fails, the jobs already submitted are
// cancelled and the error is thrown: nothing is left half submitted.
void submitPlan(FarmPlan& plan);

enum class ChunkState { Done, Pending, Running, Missing };

struct ChunkStatus {
  int task = 0;
  std::string frames;       // as the script writes them, "9-12"
  ChunkState state = ChunkState::Missing;
  std::string slurm_state;  // what Slurm last said about its task ("CANCELLED", "RUNNING", ...), or ""
  std::string job;          // the task's id, "12_3", when Slurm knows it
  int missing_files = 0;
};

struct ShotStatus {
  std::string name;
  bool finished = false;  // its movie (or outputs) exist
  std::vector<ChunkStatus> chunks;
  int partial_files = 0;  // temporary files a killed task left in its frames folder
};

struct FarmStatus {
  std::vector<ShotStatus> shots;
  std::string finish_job;    // the latest finishing job
  std::string finish_state;  // its Slurm state, or "" once it has left the queue
  bool active = false;       // some job of the plan is still pending or running
  bool complete = false;     // every shot finished
};

FarmStatus farmStatus(const FarmPlan& plan);
// One line a shot and one a chunk that is not done, for people.
std::string describeStatus(const FarmPlan& plan, const FarmStatus& status);

// What a resume did.
struct ResumeResult {
  std::vector<std::string> resubmitted;  // "trot_side chunk 3 (frames 9-12)"
  std::string array_jobs;                // the new job ids, space-separated
  std::string finish_job;                // the new finishing job, or ""
  int partial_files_removed = 0;
};

// Resubmits only the chunks whose frames are missing and that no task is working on (the same scripts,
// with --array naming those tasks), and a new finishing job when the old one can no longer run; removes
// the temporary files killed tasks left. Records the new jobs in the plan and rewrites the manifest.
ResumeResult resumePlan(FarmPlan& plan);

// Blocks until no job of the plan is pending or running (polling squeue).
void waitForPlan(const FarmPlan& plan, double poll_seconds = 1.0);

}  // namespace stirrup::render
