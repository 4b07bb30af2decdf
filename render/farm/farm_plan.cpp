#include "render/farm/farm_plan.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "render/review/movie.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "rig/io/json_fields.h"
#include "scene/frame_range.h"

namespace stirrup::render {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Written to a temporary name and renamed, like every frame: a reader never sees half a manifest.
void writeTextAtomically(const fs::path& file, const std::string& text, fs::perms perms = fs::perms::none) {
  rig::writeFileAtomically(file, text, perms);
}

std::string commandLine(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& a : argv) line += (line.empty() ? "" : " ") + shellQuote(a);
  return line;
}

// The #SBATCH lines every script shares.
std::string sbatchHeader(const FarmPlan& plan, const std::string& job_name, const std::string& log) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by stirrup farm submit (docs/farm.md). Submitted with sbatch; safe to resubmit by hand.\n"
    << "#SBATCH --job-name=" << job_name << "\n"
    << "#SBATCH --output=" << (logDir(plan) / log).string() << "\n"
    << "#SBATCH --cpus-per-task=" << plan.sbatch.cpus_per_task << "\n";
  if (!plan.sbatch.partition.empty()) s << "#SBATCH --partition=" << plan.sbatch.partition << "\n";
  if (!plan.sbatch.account.empty()) s << "#SBATCH --account=" << plan.sbatch.account << "\n";
  if (!plan.sbatch.time.empty()) s << "#SBATCH --time=" << plan.sbatch.time << "\n";
  if (!plan.sbatch.mem.empty()) s << "#SBATCH --mem=" << plan.sbatch.mem << "\n";
  s << "set -euo pipefail\n"
    << "cd " << shellQuote(plan.out.string()) << "\n";
  return s.str();
}

std::vector<std::string> stringArray(const rig::JsonObjectReader& r, const std::string& key, const json& v) {
  if (!v.is_array()) r.fail(key, "expected an array of strings, got " + rig::describeJson(v));
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_string()) r.fail(key + "[" + std::to_string(i) + "]", "expected a string, got " + rig::describeJson(v[i]));
    out.push_back(v[i].get<std::string>());
  }
  return out;
}

std::vector<std::string> requiredStrings(rig::JsonObjectReader& r, const std::string& key) {
  const json* v = r.value(key);
  if (!v) r.fail(key, "expected an array of strings (missing)");
  return stringArray(r, key, *v);
}

std::string requiredString(rig::JsonObjectReader& r, const std::string& key) {
  if (!r.has(key)) r.fail(key, "expected a string (missing)");
  return r.string(key, "");
}

json cameraJson(const PlannedCamera& c) {
  // Numbers are written with 17 significant digits (nlohmann's), so they read back to the bit.
  return {{"name", c.name},
          {"key", c.key},
          {"position", c.position},
          {"target", c.target},
          {"up", c.up},
          {"seat_from_pivot_cm", c.seat_from_pivot_cm},
          {"ortho_height_cm", c.ortho_height_cm},
          {"fov_deg", c.fov_deg}};
}

PlannedCamera readCamera(rig::JsonObjectReader& r) {
  PlannedCamera c;
  c.name = requiredString(r, "name");
  c.key = requiredString(r, "key");
  const auto finite3 = [&](const std::string& key) {
    if (!r.has(key)) r.fail(key, "expected an array of 3 numbers (missing)");
    const std::array<double, 3> v = r.numbers<3>(key, {});
    for (std::size_t i = 0; i < 3; ++i)
      if (!std::isfinite(v[i])) r.fail(key + "[" + std::to_string(i) + "]", "expected a finite number");
    return v;
  };
  c.position = finite3("position");
  c.target = finite3("target");
  if (c.target == c.position) r.fail("target", "expected a point other than the camera's position");
  c.up = finite3("up");
  if (c.up == std::array<double, 3>{0.0, 0.0, 0.0}) r.fail("up", "expected a direction, not 0 0 0");
  c.seat_from_pivot_cm = finite3("seat_from_pivot_cm");
  if (!r.has("ortho_height_cm")) r.fail("ortho_height_cm", "expected a number above 0 (missing)");
  c.ortho_height_cm = r.number("ortho_height_cm", 0.0);
  if (!(c.ortho_height_cm > 0.0 && std::isfinite(c.ortho_height_cm))) r.fail("ortho_height_cm", "expected a number above 0");
  if (!r.has("fov_deg")) r.fail("fov_deg", "expected a number between 0 and 180 (missing)");
  c.fov_deg = r.number("fov_deg", 0.0);
  if (!(c.fov_deg > 0.0 && c.fov_deg < 180.0)) r.fail("fov_deg", "expected a number between 0 and 180");
  r.finish();
  return c;
}

}  // namespace

std::vector<std::vector<int>> chunkFrames(const std::vector<int>& frames, int chunk) {
  if (chunk <= 0) throw rig::InputError("--chunk: expected a positive number of frames, got " + std::to_string(chunk));
  std::vector<std::vector<int>> chunks;
  for (std::size_t i = 0; i < frames.size(); i += static_cast<std::size_t>(chunk))
    chunks.emplace_back(frames.begin() + static_cast<long>(i),
                        frames.begin() + static_cast<long>(std::min(frames.size(), i + static_cast<std::size_t>(chunk))));
  return chunks;
}

fs::path manifestFile(const fs::path& out) { return out / "farm.json"; }
fs::path scriptFile(const FarmPlan& plan, const std::string& shot) { return plan.out / "farm" / (shot + ".sbatch"); }
fs::path finishScriptFile(const FarmPlan& plan) { return plan.out / "farm" / "finish.sbatch"; }
fs::path logDir(const FarmPlan& plan) { return plan.out / "farm" / "logs"; }

std::string taskScript(const FarmPlan& plan, const FarmShot& shot) {
  std::ostringstream s;
  s << sbatchHeader(plan, "stirrup:" + shot.name, shot.name + ".%A_%a.log");
  s << "# One chunk of frames a task: sbatch --array=1-" << shot.chunks.size() << " runs them all, --array=3 redoes chunk 3.\n"
    << "case \"${SLURM_ARRAY_TASK_ID:?run this script as a Slurm job array}\" in\n";
  for (const FarmChunk& c : shot.chunks) s << "  " << c.task << ") frames=" << scene::formatFrameList(c.frames) << " ;;\n";
  s << "  *) echo \"stirrup farm: " << shot.name << " has no chunk $SLURM_ARRAY_TASK_ID\" >&2; exit 2 ;;\n"
    << "esac\n"
    << "exec " << commandLine(shot.command) << " --threads \"${SLURM_CPUS_PER_TASK:-1}\" --frames \"$frames\"\n";
  return s.str();
}

std::string finishScript(const FarmPlan& plan) {
  std::ostringstream s;
  s << sbatchHeader(plan, "stirrup:finish", "finish.%j.log");
  s << "# Runs after every chunk has rendered (--dependency=afterok): movies, contact sheets, plots, index.\n"
    << "exec " << commandLine(plan.finish_command) << " --threads \"${SLURM_CPUS_PER_TASK:-1}\"\n";
  return s.str();
}

void writeScripts(const FarmPlan& plan) {
  fs::create_directories(logDir(plan));
  const fs::perms exec = fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec;
  for (const FarmShot& shot : plan.shots) writeTextAtomically(scriptFile(plan, shot.name), taskScript(plan, shot), exec);
  writeTextAtomically(finishScriptFile(plan), finishScript(plan), exec);
}

void writeManifest(const FarmPlan& plan) {
  json j;
  j["format"] = "stirrup farm manifest 1";
  j["out"] = plan.out.string();
  j["kind"] = plan.kind;
  j["submitted"] = plan.submitted;
  j["sbatch"] = {{"partition", plan.sbatch.partition},
                 {"account", plan.sbatch.account},
                 {"time", plan.sbatch.time},
                 {"mem", plan.sbatch.mem},
                 {"cpus_per_task", plan.sbatch.cpus_per_task}};
  j["shots"] = json::array();
  for (const FarmShot& shot : plan.shots) {
    json chunks = json::array();
    for (const FarmChunk& c : shot.chunks)
      chunks.push_back({{"task", c.task}, {"frames", scene::formatFrameList(c.frames)}, {"files", c.files}});
    j["shots"].push_back({{"name", shot.name},
                          {"command", shot.command},
                          {"frames_dir", shot.frames_dir},
                          {"outputs", shot.outputs},
                          {"array_jobs", shot.array_jobs},
                          {"chunks", chunks}});
    if (shot.camera) j["shots"].back()["camera"] = cameraJson(*shot.camera);
  }
  j["finish_command"] = plan.finish_command;
  j["finish_jobs"] = plan.finish_jobs;
  fs::create_directories(plan.out);
  writeTextAtomically(manifestFile(plan.out), j.dump(2) + "\n");
}

FarmPlan readManifest(const fs::path& out) {
  const fs::path file = manifestFile(out);
  if (!fs::is_regular_file(file))
    throw rig::InputError(file.string() + ": no farm manifest here (expected the output folder of stirrup farm submit)");
  return readManifestFile(file);
}

FarmPlan readManifestFile(const fs::path& file) {
  if (!fs::is_regular_file(file)) throw rig::InputError(file.string() + ": no such farm manifest");
  const json j = rig::readJsonFile(file);
  if (!j.is_object()) throw rig::InputError(file.string() + ": expected a JSON object");
  rig::JsonObjectReader r(file.string(), "", j);
  if (r.string("format", "") != "stirrup farm manifest 1")
    r.fail("format", "expected \"stirrup farm manifest 1\"");
  FarmPlan plan;
  plan.out = requiredString(r, "out");
  plan.kind = requiredString(r, "kind");
  if (plan.kind != "render" && plan.kind != "movies") r.fail("kind", "expected \"render\" or \"movies\"");
  plan.submitted = r.string("submitted", "");
  {
    rig::JsonObjectReader s = r.object("sbatch");
    plan.sbatch.partition = s.string("partition", "");
    plan.sbatch.account = s.string("account", "");
    plan.sbatch.time = s.string("time", "");
    plan.sbatch.mem = s.string("mem", "");
    plan.sbatch.cpus_per_task = s.integer("cpus_per_task", 1);
    s.finish();
  }
  const json* shots = r.value("shots");
  if (!shots || !shots->is_array() || shots->empty()) r.fail("shots", "expected a non-empty array of shots");
  for (std::size_t i = 0; i < shots->size(); ++i) {
    const std::string path = "shots[" + std::to_string(i) + "]";
    if (!(*shots)[i].is_object()) r.fail(path, "expected an object");
    rig::JsonObjectReader sr(file.string(), path, (*shots)[i]);
    FarmShot shot;
    shot.name = requiredString(sr, "name");
    shot.command = requiredStrings(sr, "command");
    shot.frames_dir = requiredString(sr, "frames_dir");
    shot.outputs = requiredStrings(sr, "outputs");
    shot.array_jobs = requiredStrings(sr, "array_jobs");
    const json* chunks = sr.value("chunks");
    if (!chunks || !chunks->is_array() || chunks->empty()) sr.fail("chunks", "expected a non-empty array of chunks");
    for (std::size_t k = 0; k < chunks->size(); ++k) {
      const std::string cpath = path + ".chunks[" + std::to_string(k) + "]";
      if (!(*chunks)[k].is_object()) r.fail(cpath, "expected an object");
      rig::JsonObjectReader cr(file.string(), cpath, (*chunks)[k]);
      FarmChunk c;
      c.task = cr.integer("task", 0);
      if (c.task != static_cast<int>(k) + 1) cr.fail("task", "expected " + std::to_string(k + 1));
      c.frames = scene::parseFrameList(requiredString(cr, "frames"), file.string() + ": " + cpath + ".frames");
      c.files = requiredStrings(cr, "files");
      cr.finish();
      shot.chunks.push_back(std::move(c));
    }
    if (sr.has("camera")) {
      rig::JsonObjectReader cr = sr.object("camera");
      shot.camera = readCamera(cr);
    }
    sr.finish();
    plan.shots.push_back(std::move(shot));
  }
  plan.finish_command = requiredStrings(r, "finish_command");
  plan.finish_jobs = requiredStrings(r, "finish_jobs");
  r.finish();
  return plan;
}

}  // namespace stirrup::render
