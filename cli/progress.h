// A progress bar for long work, drawn on stderr only when it is a terminal (quiet in CI logs), or
// always with --progress. Shows frames done, frames per second and time left.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include <unistd.h>

namespace stirrup::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, int total, bool force)
      : label_(std::move(label)), total_(total), enabled_(force || isatty(STDERR_FILENO)),
        start_(std::chrono::steady_clock::now()) {}

  void step(int done) {
    if (!enabled_) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double fps = s > 0 ? done / s : 0.0;
    const double left = fps > 0 ? (total_ - done) / fps : 0.0;
    constexpr int kWidth = 30;
    const int filled = total_ > 0 ? kWidth * done / total_ : kWidth;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r%s [%s] %d/%d  %.1f fps  %.0fs left ", label_.c_str(), bar.c_str(), done,
                 total_, fps, left);
    if (done >= total_) std::fputc('\n', stderr);
    std::fflush(stderr);
  }

 private:
  std::string label_;
  int total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace stirrup::cli
