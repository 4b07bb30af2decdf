#include "render/review/movie.h"
#include "rig/io/atomic_file.h"

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>

namespace stirrup::render {

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

void encodeMovie(const MovieRequest& r) {
  namespace fs = std::filesystem;
  if (r.frames.empty()) throw std::runtime_error("movie " + r.output.string() + ": no frames to encode");
  const std::string ext = r.output.extension().string();
  if (ext != ".mp4" && ext != ".mov")
    throw std::runtime_error("movie " + r.output.string() + ": expected a file name ending in .mp4 or .mov");
  if (r.codec == MovieCodec::ProRes && ext != ".mov")
    throw std::runtime_error("movie " + r.output.string() + ": ProRes needs a .mov file");
  if (!r.output.parent_path().empty()) fs::create_directories(r.output.parent_path());
  std::ostringstream fps;
  fps.precision(10);
  fps << r.fps;
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
  // Even dimensions are required by yuv420p; the scale filter also tags the BT.709 matrix.
  std::ostringstream cmd;
  cmd << "ffmpeg -nostdin -hide_banner -loglevel error -y"
      << " -f concat -safe 0 -i " << shellQuote(list.string())
      << " -frames:v " << r.frames.size()
      << " -vf " << shellQuote("scale=trunc(iw/2)*2:trunc(ih/2)*2:out_color_matrix=bt709")
      << (r.codec == MovieCodec::ProRes
              ? std::string(" -c:v prores_ks -profile:v 3 -vendor apl0 -pix_fmt yuv422p10le")
              : " -c:v libx264 -preset medium -crf " + std::to_string(r.crf) + " -pix_fmt yuv420p")
      << " -color_range tv -colorspace bt709 -color_primaries bt709 -color_trc iec61966-2-1"
      << " -r " << fps.str() << " -movflags +faststart -f " << (ext == ".mov" ? "mov" : "mp4") << " ";
  // ffmpeg writes the temporary; it replaces the movie only when ffmpeg succeeded.
  rig::replaceFileAtomically(
      r.output,
      [&](const fs::path& tmp) {
        cmd << shellQuote(tmp.string()) << " 2>&1";
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

}  // namespace stirrup::render
