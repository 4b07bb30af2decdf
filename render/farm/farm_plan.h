// A render farm plan: which shots, cut into which chunks of frames, run by which commands, with which
// scheduler settings, and (once submitted) which Slurm jobs. It is written beside the frames as
// OUT/farm.json, the manifest `stirrup farm status` and `resume` read back, and as one sbatch script a
// shot (OUT/farm/NAME.sbatch, a job array: task i renders chunk i) plus OUT/farm/finish.sbatch.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace stirrup::render {

// sbatch options, as the site names them; empty means the site's default.
struct SbatchSettings {
  std::string partition;
  std::string account;
  std::string time;  // Slurm's time format, e.g. "30:00" or "1-00:00:00"
  std::string mem;   // e.g. "2G"
  int cpus_per_task = 1;
};

struct FarmChunk {
  int task = 0;                    // its array task id, from 1
  std::vector<int> frames;         // in playing order
  std::vector<std::string> files;  // what it writes, relative to the output folder
};

// A `render` shot's view camera as framed once when the plan was made (scene/view.h): every
// chunk's task reads it (stirrup render --camera-plan) instead of framing the view again, about a
// second a chunk. `key` names what the framing read (render/farm/farm_shots.h framingKey): a task
// whose scene, size or profile differs refuses the camera.
struct PlannedCamera {
  std::string name;  // the scene's camera
  std::string key;
  std::array<double, 3> position{}, target{}, up{}, seat_from_pivot_cm{};
  double ortho_height_cm = 0.0, fov_deg = 0.0;
};

struct FarmShot {
  std::string name;
  // The task's command line; the script adds --threads (the task's CPUs) and --frames (its chunk).
  std::vector<std::string> command;
  std::vector<FarmChunk> chunks;
  std::vector<std::string> outputs;     // relative; the shot is finished when all of them exist
  std::string frames_dir;               // relative; where its chunks write
  std::vector<std::string> array_jobs;  // the job arrays that ran its chunks: submit's, then each resume's
  std::optional<PlannedCamera> camera;  // a render shot's framed view camera (none: no view, or a movie)
};

struct FarmPlan {
  std::filesystem::path out;  // absolute; every node must see it at this path
  std::string kind;           // "render" (one shot) or "movies" (the movie set)
  std::string submitted;      // UTC, "2026-11-25 06:00:00"
  SbatchSettings sbatch;
  std::vector<FarmShot> shots;
  std::vector<std::string> finish_command;  // encodes, makes sheets, plots and the index, once
  std::vector<std::string> finish_jobs;     // the finishing jobs: submit's, then each resume's
};

// `frames` cut into consecutive chunks of `chunk` frames (the last may be shorter).
std::vector<std::vector<int>> chunkFrames(const std::vector<int>& frames, int chunk);

// Where the plan's files go.
std::filesystem::path manifestFile(const std::filesystem::path& out);           // OUT/farm.json
std::filesystem::path scriptFile(const FarmPlan& plan, const std::string& shot);  // OUT/farm/SHOT.sbatch
std::filesystem::path finishScriptFile(const FarmPlan& plan);                    // OUT/farm/finish.sbatch
std::filesystem::path logDir(const FarmPlan& plan);                              // OUT/farm/logs

// The batch scripts' text. A task script maps SLURM_ARRAY_TASK_ID to its chunk's frames, so a resume
// submits the same script for a few task ids only.
std::string taskScript(const FarmPlan& plan, const FarmShot& shot);
std::string finishScript(const FarmPlan& plan);
// Writes every script (and makes the log folder), each atomically.
void writeScripts(const FarmPlan& plan);

// The manifest, written atomically; read back with one-line InputErrors naming the file and the field.
void writeManifest(const FarmPlan& plan);
FarmPlan readManifest(const std::filesystem::path& out);
// The manifest file itself (OUT/farm.json, or a copy of it under another name).
FarmPlan readManifestFile(const std::filesystem::path& file);

}  // namespace stirrup::render
