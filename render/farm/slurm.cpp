#include "render/farm/slurm.h"

#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <sstream>

#include "rig/error.h"

extern char** environ;

namespace stirrup::render {
namespace {

std::string firstLine(const std::string& text) {
  std::string s = text.substr(0, text.find('\n'));
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

// Runs a Slurm command; a missing command or a non-zero exit is one InputError line.
ProgramResult slurmCommand(const std::vector<std::string>& argv) {
  ProgramResult r = runProgram(argv, kSlurmCommandTimeoutSeconds);
  if (r.timed_out)
    throw rig::InputError("farm: " + argv[0] + " did not answer within " + std::to_string(int(kSlurmCommandTimeoutSeconds)) +
                     " s (is the Slurm controller up?)");
  if (!r.started)
    throw rig::InputError("farm: " + argv[0] + " not found on PATH (install slurm-wlm, load the site's Slurm module, "
                     "or start a local cluster with scripts/slurm-local up)");
  if (r.exit_code != 0) {
    const std::string why = firstLine(r.err.empty() ? r.out : r.err);
    throw rig::InputError("farm: " + argv[0] + " failed (exit " + std::to_string(r.exit_code) + ")" +
                     (why.empty() ? "" : ": " + why));
  }
  return r;
}

}  // namespace

ProgramResult runProgram(const std::vector<std::string>& argv, double timeout_seconds) {
  ProgramResult r;
  std::array<int, 2> out_pipe{}, err_pipe{};
  if (pipe(out_pipe.data()) != 0) return r;
  if (pipe(err_pipe.data()) != 0) {
    close(out_pipe[0]), close(out_pipe[1]);
    return r;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, out_pipe[0]);
  posix_spawn_file_actions_addclose(&actions, err_pipe[0]);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out_pipe[1]);
  close(err_pipe[1]);
  if (spawned == 0) {
    // Both pipes are drained together, so a command that fills one while we wait on the other cannot hang.
    std::array<pollfd, 2> fds = {pollfd{out_pipe[0], POLLIN, 0}, pollfd{err_pipe[0], POLLIN, 0}};
    std::array<std::string*, 2> sinks = {&r.out, &r.err};
    int open_fds = 2;
    std::array<char, 4096> buf{};
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
    while (open_fds > 0) {
      int wait_ms = -1;
      if (timeout_seconds > 0) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) {
          kill(pid, SIGKILL);
          r.timed_out = true;
          break;
        }
        wait_ms = static_cast<int>(left.count());
      }
      const int ready = poll(fds.data(), fds.size(), wait_ms);
      if (ready < 0) {
        if (errno == EINTR) continue;
        break;
      }
      if (ready == 0) continue;
      for (std::size_t i = 0; i < fds.size(); ++i) {
        if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        const ssize_t n = read(fds[i].fd, buf.data(), buf.size());
        if (n > 0) {
          sinks[i]->append(buf.data(), static_cast<std::size_t>(n));
        } else if (n == 0 || errno != EINTR) {
          fds[i].fd = -1;
          --open_fds;
        }
      }
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    // glibc's posix_spawnp reports a program it cannot execute as its own error, before this point.
    r.started = true;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  close(out_pipe[0]);
  close(err_pipe[0]);
  return r;
}

void requireSlurm() {
  for (const char* program : {"sbatch", "squeue", "sinfo", "scancel"}) {
    const ProgramResult r = runProgram({program, "--version"});
    if (!r.started)
      throw rig::InputError(std::string("farm: Slurm is not reachable: ") + program +
                       " is not on PATH (install slurm-wlm, load the site's Slurm module, or start a local "
                       "cluster with scripts/slurm-local up)");
  }
  const ProgramResult ping = runProgram({"sinfo", "-h", "-o", "%P"}, kSlurmCommandTimeoutSeconds);
  if (ping.exit_code != 0 || lines(ping.out).empty()) {
    // Slurm's clients print a line a retry; the last says why they gave up.
    const std::vector<std::string> said = lines(ping.err.empty() ? ping.out : ping.err);
    const std::string why = ping.timed_out ? "no answer within " + std::to_string(int(kSlurmCommandTimeoutSeconds)) + " s"
                                           : (said.empty() ? "" : said.back());
    throw rig::InputError("farm: Slurm is not reachable: no controller answers sinfo" + (why.empty() ? "" : " (" + why + ")") +
                     "; start one with scripts/slurm-local up, or check SLURM_CONF");
  }
}

std::vector<std::string> slurmPartitions() {
  std::vector<std::string> names;
  for (std::string line : lines(slurmCommand({"sinfo", "-h", "-o", "%P"}).out)) {
    const bool is_default = !line.empty() && line.back() == '*';
    if (is_default) line.pop_back();
    if (std::find(names.begin(), names.end(), line) != names.end()) continue;
    if (is_default) names.insert(names.begin(), line);
    else names.push_back(line);
  }
  return names;
}

int slurmNodeCount() {
  std::vector<std::string> nodes = lines(slurmCommand({"sinfo", "-h", "-N", "-o", "%N"}).out);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return static_cast<int>(nodes.size());
}

std::string sbatch(const std::filesystem::path& script, const std::vector<std::string>& options) {
  std::vector<std::string> argv = {"sbatch", "--parsable"};
  argv.insert(argv.end(), options.begin(), options.end());
  argv.push_back(script.string());
  const std::string out = firstLine(slurmCommand(argv).out);
  // --parsable prints "JOBID" or "JOBID;CLUSTER".
  std::string id = out.substr(0, out.find(';'));
  if (id.empty() || !std::all_of(id.begin(), id.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw rig::InputError("farm: sbatch " + script.string() + ": expected a job id, got \"" + out + "\"");
  return id;
}

std::map<std::string, std::string> slurmJobStates(const std::vector<std::string>& job_ids) {
  std::map<std::string, std::string> states;
  if (job_ids.empty()) return states;
  auto wanted = [&](const std::string& id) {
    const std::string job = id.substr(0, id.find('_'));
    return std::find(job_ids.begin(), job_ids.end(), job) != job_ids.end();
  };
  // Finished jobs first, where the cluster keeps accounting (without it sacct fails; that is not an error).
  std::string list;
  for (const std::string& id : job_ids) list += (list.empty() ? "" : ",") + id;
  const ProgramResult acct = runProgram({"sacct", "-n", "-X", "-P", "-j", list, "-o", "JobID,State"});
  if (acct.started && acct.exit_code == 0)
    for (const std::string& line : lines(acct.out)) {
      const std::size_t bar = line.find('|');
      if (bar == std::string::npos) continue;
      const std::string id = line.substr(0, bar);
      std::string state = line.substr(bar + 1);
      state = state.substr(0, state.find(' '));  // "CANCELLED by 0" -> "CANCELLED"
      if (wanted(id)) states[id] = state;
    }
  // Then what the controller has now (-r: one line per array task; -t all: also jobs that ended within
  // its MinJobAge, so a cancelled or failed task is named even without accounting).
  for (const std::string& line : lines(slurmCommand({"squeue", "-h", "-r", "-t", "all", "-o", "%i %T"}).out)) {
    const std::size_t space = line.find(' ');
    if (space == std::string::npos) continue;
    const std::string id = line.substr(0, space);
    if (wanted(id)) states[id] = line.substr(space + 1);
  }
  return states;
}

void scancel(const std::vector<std::string>& ids) {
  if (ids.empty()) return;
  std::vector<std::string> argv = {"scancel"};
  argv.insert(argv.end(), ids.begin(), ids.end());
  const ProgramResult r = runProgram(argv);
  if (!r.started) throw rig::InputError("farm: scancel not found on PATH");
  // scancel exits non-zero for a job that has already ended; only other complaints are errors.
  if (r.exit_code != 0 && r.err.find("already completed") == std::string::npos &&
      r.err.find("Invalid job id") == std::string::npos)
    throw rig::InputError("farm: scancel failed: " + firstLine(r.err));
}

}  // namespace stirrup::render
