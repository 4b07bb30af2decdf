// The Slurm commands stirrup farm uses (sbatch, squeue, sacct, scancel, sinfo), run as programs: the
// same commands a user types, so a site's wrappers and its SLURM_CONF apply unchanged. Every failure is a
// one-line rig::InputError saying which command failed and what it said.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace stirrup::render {

// A program run without a shell: its exit code and what it printed. `started` is false when it could
// not be run at all (not on PATH); `timed_out` when it was killed after `timeout_seconds` (0: no limit).
struct ProgramResult {
  bool started = false;
  bool timed_out = false;
  int exit_code = -1;
  std::string out;
  std::string err;
};
ProgramResult runProgram(const std::vector<std::string>& argv, double timeout_seconds = 0);

// How long a Slurm command may take before stirrup gives up on the controller (Slurm's own clients retry
// an unreachable controller for up to a minute).
inline constexpr double kSlurmCommandTimeoutSeconds = 30;

// InputError unless the Slurm commands are on PATH and a controller answers.
void requireSlurm();

// The cluster's partitions (sinfo), the default one first.
std::vector<std::string> slurmPartitions();
// How many nodes the cluster has (sinfo).
int slurmNodeCount();

// sbatch `options...` `script`, with --parsable; returns the job id. InputError with sbatch's message.
std::string sbatch(const std::filesystem::path& script, const std::vector<std::string>& options);

// The state of every job and array task still known to the controller, by id ("12" or "12_3"):
// PENDING, RUNNING, COMPLETING, ... (squeue), and, where the cluster keeps accounting, finished ones
// too (sacct: COMPLETED, FAILED, CANCELLED, TIMEOUT, ...). Without accounting a finished job simply
// leaves the queue; stirrup farm then judges its chunk by the files it wrote.
std::map<std::string, std::string> slurmJobStates(const std::vector<std::string>& job_ids);

// scancel each id (a job or "JOB_TASK"); ids that have already ended are not an error.
void scancel(const std::vector<std::string>& ids);

}  // namespace stirrup::render
