#include "render/farm/farm_jobs.h"

#include <chrono>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>

#include "render/farm/slurm.h"
#include "rig/error.h"
#include "scene/frame_range.h"

namespace stirrup::render {
namespace fs = std::filesystem;

namespace {

std::string join(const std::vector<std::string>& words, const std::string& separator) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : separator) + w;
  return out;
}

// Slurm's job states (squeue(1) "JOB STATE CODES") grouped by what they mean for a chunk. A job held
// after its reservation was deleted (RESV_DEL_HOLD) still waits in the queue: resubmitting its chunk
// would render it twice once it is released.
bool waiting(const std::string& s) {
  return s == "PENDING" || s == "CONFIGURING" || s == "REQUEUED" || s == "REQUEUE_HOLD" || s == "REQUEUE_FED" ||
         s == "RESV_DEL_HOLD" || s == "RESIZING" || s == "SUSPENDED" || s == "STOPPED";
}
bool running(const std::string& s) {
  return s == "RUNNING" || s == "COMPLETING" || s == "STAGE_OUT" || s == "SIGNALING";
}
bool active(const std::string& s) { return waiting(s) || running(s); }

std::vector<std::string> allJobs(const FarmPlan& plan) {
  std::vector<std::string> ids;
  for (const FarmShot& shot : plan.shots) ids.insert(ids.end(), shot.array_jobs.begin(), shot.array_jobs.end());
  ids.insert(ids.end(), plan.finish_jobs.begin(), plan.finish_jobs.end());
  return ids;
}

// Temporary files (NAME.tmp) a task killed mid-write leaves beside its frames.
std::vector<fs::path> partialFiles(const FarmPlan& plan, const FarmShot& shot) {
  std::vector<fs::path> found;
  std::error_code ec;
  const fs::path dir = plan.out / shot.frames_dir;
  if (!fs::is_directory(dir, ec)) return found;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".tmp") found.push_back(entry.path());
  return found;
}

std::string finishDependency(const std::vector<std::string>& must_succeed, const std::vector<std::string>& must_end) {
  std::vector<std::string> parts;
  if (!must_succeed.empty()) parts.push_back("afterok:" + join(must_succeed, ":"));
  if (!must_end.empty()) parts.push_back("afterany:" + join(must_end, ":"));
  return join(parts, ",");
}

// The finishing job's sbatch options: after `dependency`, and removed by Slurm (rather than left pending
// for ever) when a task it waits on fails; `stirrup farm resume` then submits a new one.
std::vector<std::string> finishOptions(const std::string& dependency) {
  if (dependency.empty()) return {};
  return {"--dependency=" + dependency, "--kill-on-invalid-dep=yes"};
}

}  // namespace

void submitPlan(FarmPlan& plan) {
  writeScripts(plan);
  std::vector<std::string> submitted;
  try {
    for (FarmShot& shot : plan.shots) {
      const std::string id = sbatch(scriptFile(plan, shot.name), {"--array=1-" + std::to_string(shot.chunks.size())});
      shot.array_jobs = {id};
      submitted.push_back(id);
    }
    const std::string finish = sbatch(finishScriptFile(plan), finishOptions(finishDependency(submitted, {})));
    plan.finish_jobs = {finish};
    submitted.push_back(finish);
    writeManifest(plan);
  } catch (...) {
    try {
      scancel(submitted);
    } catch (const rig::InputError&) {
      // The first error is the one to report.
    }
    throw;
  }
}

FarmStatus farmStatus(const FarmPlan& plan) {
  const std::map<std::string, std::string> states = slurmJobStates(allJobs(plan));
  FarmStatus status;
  status.complete = true;
  for (const FarmShot& shot : plan.shots) {
    ShotStatus s;
    s.name = shot.name;
    s.finished = !shot.outputs.empty();
    for (const std::string& o : shot.outputs) s.finished = s.finished && fs::is_regular_file(plan.out / o);
    s.partial_files = static_cast<int>(partialFiles(plan, shot).size());
    for (const FarmChunk& chunk : shot.chunks) {
      ChunkStatus c;
      c.task = chunk.task;
      c.frames = scene::formatFrameList(chunk.frames);
      for (const std::string& f : chunk.files) c.missing_files += fs::is_regular_file(plan.out / f) ? 0 : 1;
      // The newest array that ran this chunk has the say.
      for (auto job = shot.array_jobs.rbegin(); job != shot.array_jobs.rend(); ++job) {
        const auto it = states.find(*job + "_" + std::to_string(chunk.task));
        if (it == states.end()) continue;
        c.job = it->first;
        c.slurm_state = it->second;
        break;
      }
      if (s.finished || c.missing_files == 0) c.state = ChunkState::Done;
      else if (running(c.slurm_state)) c.state = ChunkState::Running;
      else if (waiting(c.slurm_state)) c.state = ChunkState::Pending;
      else c.state = ChunkState::Missing;
      status.active = status.active || c.state == ChunkState::Running || c.state == ChunkState::Pending;
      s.chunks.push_back(std::move(c));
    }
    status.complete = status.complete && s.finished;
    status.shots.push_back(std::move(s));
  }
  if (!plan.finish_jobs.empty()) {
    status.finish_job = plan.finish_jobs.back();
    const auto it = states.find(status.finish_job);
    if (it != states.end()) status.finish_state = it->second;
    status.active = status.active || active(status.finish_state);
  }
  return status;
}

std::string describeStatus(const FarmPlan& plan, const FarmStatus& status) {
  std::ostringstream s;
  s << plan.out.string() << ": " << plan.kind << ", " << plan.shots.size() << (plan.shots.size() == 1 ? " shot" : " shots")
    << ", submitted " << plan.submitted << " UTC\n";
  std::size_t width = 6;
  for (const ShotStatus& shot : status.shots) width = std::max(width, shot.name.size());
  for (const ShotStatus& shot : status.shots) {
    int counts[4] = {0, 0, 0, 0};
    for (const ChunkStatus& c : shot.chunks) ++counts[static_cast<int>(c.state)];
    s << "  " << shot.name << std::string(width - shot.name.size() + 2, ' ');
    if (shot.finished) {
      s << "finished\n";
      continue;
    }
    s << counts[0] << "/" << shot.chunks.size() << " chunks done";
    if (counts[2]) s << ", " << counts[2] << " running";
    if (counts[1]) s << ", " << counts[1] << " pending";
    if (counts[3]) s << ", " << counts[3] << " missing";
    if (shot.partial_files) s << ", " << shot.partial_files << " partial files (resume removes them)";
    s << "\n";
    for (const ChunkStatus& c : shot.chunks) {
      if (c.state == ChunkState::Done) continue;
      static const char* names[] = {"done", "pending", "running", "missing"};
      s << "    chunk " << c.task << " (frames " << c.frames << "): " << names[static_cast<int>(c.state)];
      if (c.state == ChunkState::Missing) s << ", " << c.missing_files << " files not written";
      if (!c.job.empty()) s << "; Slurm task " << c.job << " " << c.slurm_state;
      s << "\n";
    }
  }
  s << "  finish" << std::string(width - 6 + 2, ' ');
  if (status.finish_job.empty()) s << "not submitted (--dry-run)\n";
  else s << "job " << status.finish_job << ": " << (status.finish_state.empty() ? "no longer queued" : status.finish_state) << "\n";
  if (status.complete) s << "complete\n";
  else if (status.active) s << "in progress\n";
  else s << "incomplete: stirrup farm resume " << plan.out.string() << " redoes what is missing\n";
  return s.str();
}

ResumeResult resumePlan(FarmPlan& plan) {
  const FarmStatus status = farmStatus(plan);
  ResumeResult result;
  if (status.complete) return result;
  std::vector<std::string> new_jobs, still_active;
  for (std::size_t i = 0; i < plan.shots.size(); ++i) {
    FarmShot& shot = plan.shots[i];
    const ShotStatus& s = status.shots[i];
    if (s.finished) continue;
    std::vector<std::string> tasks;
    std::set<std::string> active_arrays;
    for (const ChunkStatus& c : s.chunks) {
      if (c.state == ChunkState::Missing) {
        tasks.push_back(std::to_string(c.task));
        result.resubmitted.push_back(shot.name + " chunk " + std::to_string(c.task) + " (frames " + c.frames + ")");
      }
      if (c.state == ChunkState::Running || c.state == ChunkState::Pending) active_arrays.insert(c.job.substr(0, c.job.find('_')));
    }
    // A temporary file is only left over when no task of the shot could still be writing it.
    if (active_arrays.empty())
      for (const fs::path& partial : partialFiles(plan, shot)) {
        std::error_code ec;
        if (fs::remove(partial, ec)) ++result.partial_files_removed;
      }
    still_active.insert(still_active.end(), active_arrays.begin(), active_arrays.end());
    if (tasks.empty()) continue;
    // Slurm's --array takes a comma list (its step is ":", not the frame lists' "x").
    const std::string id = sbatch(scriptFile(plan, shot.name), {"--array=" + join(tasks, ",")});
    shot.array_jobs.push_back(id);
    new_jobs.push_back(id);
    writeManifest(plan);  // recorded at once: a later failure must not lose a submitted job
  }
  const bool finish_queued = active(status.finish_state);
  if (!new_jobs.empty() || !finish_queued) {
    if (finish_queued) scancel({status.finish_job});
    result.finish_job = sbatch(finishScriptFile(plan), finishOptions(finishDependency(new_jobs, still_active)));
    plan.finish_jobs.push_back(result.finish_job);
    writeManifest(plan);
  }
  result.array_jobs = join(new_jobs, " ");
  return result;
}

void waitForPlan(const FarmPlan& plan, double poll_seconds) {
  const std::vector<std::string> ids = allJobs(plan);
  while (true) {
    bool any = false;
    for (const auto& [id, state] : slurmJobStates(ids)) any = any || active(state);
    if (!any) return;
    std::this_thread::sleep_for(std::chrono::duration<double>(poll_seconds));
  }
}

}  // namespace stirrup::render
