// Review movies: an image sequence (NAME.####.png) encoded by ffmpeg as H.264 (yuv420p, CRF 18, BT.709
// tags, faststart) in .mp4 or .mov, or as ProRes 422 HQ in .mov, the settings the ASWF encoding
// guidelines give for review (render-notes.md §3).
#pragma once

#include <filesystem>
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

// Quotes a string for /bin/sh.
std::string shellQuote(const std::string& s);

}  // namespace stirrup::render
