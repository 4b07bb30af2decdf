// Review movies: frames encoded by ffmpeg as H.264 (yuv420p, CRF 18, BT.709 tags, faststart) in .mp4
// or .mov, or as ProRes 422 HQ in .mov, the settings the ASWF encoding guidelines give for review
// (render-notes.md §3). The frames come from an image sequence on disk (NAME.####.png: encodeMovie, a
// farm's last step) or straight from memory (MovieEncoder: raw 8-bit sRGB frames over a pipe, no PNG
// written or read back); both give ffmpeg the same bytes, so both give the same movie.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace stirrup::render {

enum class MovieCodec {
  H264,    // libx264, yuv420p, CRF (in .mp4 or .mov)
  ProRes,  // ProRes 422 HQ: prores_ks profile 3, yuv422p10le, vendor apl0 (in .mov)
};

struct MovieRequest {
  std::vector<std::filesystem::path> frames;  // in playing order; any frame list, stepped or not
  double fps = 24.0;                          // each frame is shown for 1/fps seconds
  std::filesystem::path output;         // .mp4 or .mov
  int crf = 18;                         // "visually lossless"
  MovieCodec codec = MovieCodec::H264;  // ProRes needs a .mov
};

// Runs ffmpeg; writes OUTPUT.tmp.mp4 and renames it when ffmpeg succeeds, so a failed encode never
// leaves a movie that looks complete. Throws std::runtime_error with ffmpeg's last line on failure.
void encodeMovie(const MovieRequest& request);

// The encoder of a movie fed from memory: ffmpeg runs beside the caller, reading raw frames (rgb24, 8-bit
// sRGB, rows top to bottom: encodeSrgb8's bytes) on its standard input, and encodes them exactly as
// encodeMovie encodes the same frames read from PNGs. Frames are shown for 1/fps each, in the order
// added. The movie goes to OUTPUT.tmp.EXT and is renamed by finish() when ffmpeg succeeds; an encoder
// destroyed unfinished (an error while rendering) kills ffmpeg and leaves no movie. addFrame blocks
// while ffmpeg is behind (the pipe is full), so a slow encoder holds the renderer back rather than
// frames piling up in memory.
class MovieEncoder {
 public:
  struct Spec {
    std::filesystem::path output;  // .mp4 or .mov
    double fps = 24.0;
    int crf = 18;
    MovieCodec codec = MovieCodec::H264;
  };
  // Starts ffmpeg. Throws std::runtime_error for a bad extension, ProRes outside .mov, a size below
  // 1 x 1, or ffmpeg not starting.
  MovieEncoder(const Spec& spec, int width, int height);
  ~MovieEncoder();
  MovieEncoder(const MovieEncoder&) = delete;
  MovieEncoder& operator=(const MovieEncoder&) = delete;

  // One frame: width * height * 3 bytes. Throws std::runtime_error (with ffmpeg's last line) when
  // ffmpeg has stopped.
  void addFrame(std::span<const uint8_t> rgb);
  // Ends the input, waits for ffmpeg and renames the movie into place. Throws std::runtime_error with
  // ffmpeg's last line on failure (no movie is left then).
  void finish();
  int frames() const { return frames_; }
  // ffmpeg's CPU time (user + system seconds) once finished: the encoder's share of the machine.
  double cpuSeconds() const { return cpu_s_; }

 private:
  // Waits for ffmpeg; returns its exit status as waitpid gives it and keeps its CPU time.
  int reap();
  [[noreturn]] void fail(const std::string& what);

  Spec spec_;
  std::filesystem::path tmp_, log_;
  std::size_t frame_bytes_ = 0;
  int pid_ = -1;   // ffmpeg, until reaped
  int input_ = -1; // the write end of its standard input
  int frames_ = 0;
  double cpu_s_ = 0.0;
};

// Quotes a string for /bin/sh.
std::string shellQuote(const std::string& s);

}  // namespace stirrup::render
