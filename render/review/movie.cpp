#include "render/review/movie.h"
#include "rig/io/atomic_file.h"

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

// The container a movie's extension asks for ("mp4" or "mov"), checked against the codec.
std::string containerOf(const fs::path& output, MovieCodec codec) {
  const std::string ext = output.extension().string();
  if (ext != ".mp4" && ext != ".mov")
    throw std::runtime_error("movie " + output.string() + ": expected a file name ending in .mp4 or .mov");
  if (codec == MovieCodec::ProRes && ext != ".mov")
    throw std::runtime_error("movie " + output.string() + ": ProRes needs a .mov file");
  return ext.substr(1);
}

// What ffmpeg does with the frames, whichever way they come: even dimensions (yuv420p needs them; the
// scale filter also tags the BT.709 matrix), the codec, the colour tags, the rate and the container,
// written to `tmp`.
std::vector<std::string> outputArguments(MovieCodec codec, int crf, double fps, const std::string& container,
                                         const fs::path& tmp) {
  std::ostringstream rate;
  rate.precision(10);
  rate << fps;
  std::vector<std::string> args = {"-vf", "scale=trunc(iw/2)*2:trunc(ih/2)*2:out_color_matrix=bt709"};
  if (codec == MovieCodec::ProRes)
    args.insert(args.end(), {"-c:v", "prores_ks", "-profile:v", "3", "-vendor", "apl0", "-pix_fmt", "yuv422p10le"});
  else
    args.insert(args.end(), {"-c:v", "libx264", "-preset", "medium", "-crf", std::to_string(crf), "-pix_fmt", "yuv420p"});
  args.insert(args.end(), {"-color_range", "tv", "-colorspace", "bt709", "-color_primaries", "bt709", "-color_trc",
                           "iec61966-2-1", "-r", rate.str(), "-movflags", "+faststart", "-f", container, tmp.string()});
  return args;
}

// The last line of ffmpeg's log that says something.
std::string lastLine(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

void encodeMovie(const MovieRequest& r) {
  if (r.frames.empty()) throw std::runtime_error("movie " + r.output.string() + ": no frames to encode");
  const std::string container = containerOf(r.output, r.codec);
  if (!r.output.parent_path().empty()) fs::create_directories(r.output.parent_path());
  // The concat demuxer takes any list of frames (stepped farm ranges too), each shown for 1/fps.
  const fs::path list = r.output.string() + ".frames.txt";
  {
    std::ofstream out(list);
    out << "ffconcat version 1.0\n";
    for (const fs::path& f : r.frames)
      out << "file " << shellQuote(fs::absolute(f).string()) << "\nduration " << 1.0 / r.fps << "\n";
    // The concat demuxer ignores the last duration unless the last file is listed again.
    out << "file " << shellQuote(fs::absolute(r.frames.back()).string()) << "\n";
    if (!out) throw std::runtime_error("movie " + r.output.string() + ": cannot write " + list.string());
  }
  // ffmpeg writes the temporary; it replaces the movie only when ffmpeg succeeded.
  rig::replaceFileAtomically(
      r.output,
      [&](const fs::path& tmp) {
        std::ostringstream cmd;
        cmd << "ffmpeg -nostdin -hide_banner -loglevel error -y -f concat -safe 0 -i " << shellQuote(list.string())
            << " -frames:v " << r.frames.size();
        for (const std::string& a : outputArguments(r.codec, r.crf, r.fps, container, tmp)) cmd << " " << shellQuote(a);
        cmd << " 2>&1";
        FILE* pipe = popen(cmd.str().c_str(), "r");
        if (!pipe) throw std::runtime_error("movie " + r.output.string() + ": cannot start ffmpeg");
        std::string last, line;
        std::array<char, 512> buf{};
        while (fgets(buf.data(), static_cast<int>(buf.size()), pipe)) {
          line = buf.data();
          while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
          if (!line.empty()) last = line;
        }
        const int status = pclose(pipe);
        std::error_code ignored;
        fs::remove(list, ignored);
        if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
          if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
            throw std::runtime_error("movie " + r.output.string() + ": ffmpeg not found (run scripts/setup)");
          throw std::runtime_error("movie " + r.output.string() + ": ffmpeg failed: " + last);
        }
      },
      rig::TempName::KeepExtension);
}

MovieEncoder::MovieEncoder(const Spec& spec, int width, int height) : spec_(spec) {
  const std::string container = containerOf(spec.output, spec.codec);
  if (width < 1 || height < 1)
    throw std::runtime_error("movie " + spec.output.string() + ": expected frames of 1 x 1 pixels or more");
  if (!spec.output.parent_path().empty()) fs::create_directories(spec.output.parent_path());
  frame_bytes_ = std::size_t(width) * std::size_t(height) * 3;
  tmp_ = rig::temporaryFor(spec.output, rig::TempName::KeepExtension);
  log_ = spec.output.string() + ".ffmpeg.log";
  std::ostringstream rate;
  rate.precision(10);
  rate << spec.fps;
  std::vector<std::string> args = {"ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y", "-f", "rawvideo",
                                   "-pix_fmt", "rgb24", "-s", std::to_string(width) + "x" + std::to_string(height),
                                   "-framerate", rate.str(), "-i", "pipe:0"};
  for (std::string& a : outputArguments(spec.codec, spec.crf, spec.fps, container, tmp_)) args.push_back(std::move(a));
  // A socket rather than a pipe: a write to an ffmpeg that stopped fails with EPIPE (MSG_NOSIGNAL)
  // instead of raising SIGPIPE in the whole program. Neither end leaks into other children.
  int ends[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw std::runtime_error("movie " + spec.output.string() + ": cannot open a pipe to ffmpeg");
  shutdown(ends[0], SHUT_WR);  // ffmpeg's end only reads
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_adddup2(&files, ends[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&files, STDERR_FILENO, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = posix_spawnp(&pid, "ffmpeg", &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  close(ends[0]);
  if (spawned != 0) {
    close(ends[1]);
    std::error_code ignored;
    fs::remove(log_, ignored);
    throw std::runtime_error("movie " + spec.output.string() + ": ffmpeg not found (run scripts/setup)");
  }
  pid_ = pid;
  input_ = ends[1];
}

MovieEncoder::~MovieEncoder() {
  if (input_ >= 0) close(input_);
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    reap();
  }
  std::error_code ignored;
  fs::remove(tmp_, ignored);
  fs::remove(log_, ignored);
}

int MovieEncoder::reap() {
  int status = 0;
  rusage usage{};
  while (wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  cpu_s_ = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  return status;
}

void MovieEncoder::fail(const std::string& what) {
  if (input_ >= 0) close(input_), input_ = -1;
  if (pid_ > 0) reap();
  const std::string last = lastLine(log_);
  std::error_code ignored;
  fs::remove(tmp_, ignored);
  fs::remove(log_, ignored);
  throw std::runtime_error("movie " + spec_.output.string() + ": " + what + (last.empty() ? "" : ": " + last));
}

void MovieEncoder::addFrame(std::span<const uint8_t> rgb) {
  if (rgb.size() != frame_bytes_)
    throw std::invalid_argument("MovieEncoder::addFrame: expected " + std::to_string(frame_bytes_) + " bytes, got " +
                                std::to_string(rgb.size()));
  if (input_ < 0) throw std::logic_error("MovieEncoder::addFrame: the movie is finished");
  for (std::size_t sent = 0; sent < rgb.size();) {
    const ssize_t n = send(input_, rgb.data() + sent, rgb.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("ffmpeg stopped reading frames");
    sent += std::size_t(n);
  }
  ++frames_;
}

void MovieEncoder::finish() {
  if (input_ < 0) throw std::logic_error("MovieEncoder::finish: the movie is finished");
  close(input_);
  input_ = -1;
  const int status = reap();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) fail("ffmpeg failed");
  if (frames_ == 0) fail("no frames to encode");
  std::error_code error;
  fs::rename(tmp_, spec_.output, error);
  if (error) fail("cannot write (" + error.message() + ")");
  fs::remove(log_, error);
}

}  // namespace stirrup::render
