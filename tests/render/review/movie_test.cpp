#include "render/review/movie.h"

#include <array>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

std::string run(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  std::array<char, 256> buf{};
  while (fgets(buf.data(), buf.size(), p)) out += buf.data();
  pclose(p);
  return out;
}

void writeFrame(const fs::path& file, int value) {
  const int w = 64, h = 36;
  std::vector<unsigned char> px(w * h * 3, static_cast<unsigned char>(value));
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
  out->close();
}

TEST(Movie, EncodesH264Yuv420pWithTheFrameCountAndRate) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_movie";
  fs::remove_all(dir);
  fs::create_directories(dir);
  MovieRequest r;
  for (int i = 1; i <= 9; i += 2) {  // a stepped list: frames 1, 3, 5, 7, 9
    const fs::path f = dir / ("m." + std::to_string(i) + ".png");
    writeFrame(f, 20 * i);
    r.frames.push_back(f);
  }
  r.fps = 24;
  r.output = dir / "m.mp4";
  encodeMovie(r);
  ASSERT_TRUE(fs::exists(r.output));
  EXPECT_FALSE(fs::exists(dir / "m.mp4.tmp.mp4"));
  const std::string probe = run("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                                "stream=codec_name,pix_fmt,nb_read_frames,r_frame_rate -of csv=p=0 " +
                                shellQuote(r.output.string()));
  EXPECT_EQ(probe, "h264,yuv420p,24/1,5\n");
}

TEST(Movie, EncodesQuickTimeProResAndH264) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_movie_mov";
  fs::remove_all(dir);
  fs::create_directories(dir);
  MovieRequest r;
  for (int i = 1; i <= 6; ++i) {
    const fs::path f = dir / ("m." + std::to_string(i) + ".png");
    writeFrame(f, 30 * i);
    r.frames.push_back(f);
  }
  r.fps = 25;
  r.output = dir / "prores.mov";
  r.codec = MovieCodec::ProRes;
  encodeMovie(r);
  const std::string probe = "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                            "stream=codec_name,profile,pix_fmt,nb_read_frames,r_frame_rate -of csv=p=0 ";
  EXPECT_EQ(run(probe + shellQuote(r.output.string())), "prores,HQ,yuv422p10le,25/1,6\n");
  EXPECT_NE(run("ffprobe -v error -show_entries format=format_name -of csv=p=0 " + shellQuote(r.output.string()))
                .find("mov"),
            std::string::npos);
  r.output = dir / "h264.mov";
  r.codec = MovieCodec::H264;
  encodeMovie(r);
  EXPECT_EQ(run(probe + shellQuote(r.output.string())), "h264,High,yuv420p,25/1,6\n");
}

TEST(Movie, RejectsProResInMp4AndOtherExtensions) {
  MovieRequest r;
  r.frames = {"x.png"};
  r.output = "x.mp4";
  r.codec = MovieCodec::ProRes;
  EXPECT_THROW(encodeMovie(r), std::runtime_error);
  r.output = "x.avi";
  r.codec = MovieCodec::H264;
  EXPECT_THROW(encodeMovie(r), std::runtime_error);
}

TEST(Movie, FailedEncodeLeavesNoMovie) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_movie_fail";
  fs::remove_all(dir);
  fs::create_directories(dir);
  MovieRequest r;
  r.frames = {dir / "missing.0001.png"};
  r.output = dir / "bad.mp4";
  EXPECT_THROW(encodeMovie(r), std::runtime_error);
  EXPECT_FALSE(fs::exists(r.output));
  EXPECT_FALSE(fs::exists(dir / "bad.mp4.tmp.mp4"));
}

// Every decoded frame's checksum (ffmpeg's framemd5, without its header): the pixels a viewer sees.
std::string decodedFrames(const fs::path& movie) {
  std::string out;
  std::istringstream lines(run("ffmpeg -v error -i " + shellQuote(movie.string()) + " -f framemd5 -"));
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] != '#') out += line + "\n";
  return out;
}

// Frames of a gradient and a moving bar, as distinct as review frames are from one another.
std::vector<uint8_t> testFrame(int w, int h, int k) {
  std::vector<uint8_t> rgb(std::size_t(w) * std::size_t(h) * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = &rgb[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3];
      p[0] = uint8_t(4 * x + k), p[1] = uint8_t(7 * y), p[2] = (x / 6 == k) ? 255 : uint8_t(x ^ y);
    }
  return rgb;
}

// The movie from memory is the movie from PNGs: the same frames, the same encoder settings, the same
// decoded pixels (here even the same bytes), in H.264 and ProRes; and it reports ffmpeg's CPU time.
TEST(MovieEncoder, MakesTheMovieTheFramesOnDiskMake) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_movie_encoder";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const int w = 66, h = 38;  // even: the scale filter keeps the size
  for (const auto& [codec, ext] : {std::pair{MovieCodec::H264, ".mp4"}, std::pair{MovieCodec::ProRes, ".mov"}}) {
    MovieRequest files;
    files.fps = 24;
    files.codec = codec;
    files.output = dir / (std::string("files") + ext);
    MovieEncoder memory({dir / (std::string("memory") + ext), 24, 18, codec}, w, h);
    for (int k = 0; k < 7; ++k) {
      const std::vector<uint8_t> rgb = testFrame(w, h, k);
      const fs::path png = dir / ("f." + std::to_string(k) + ".png");
      auto out = OIIO::ImageOutput::create(png.string());
      ASSERT_TRUE(out && out->open(png.string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8)));
      ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgb.data()));
      out->close();
      files.frames.push_back(png);
      memory.addFrame(rgb);
    }
    EXPECT_FALSE(fs::exists(dir / (std::string("memory") + ext)));  // not before it is finished
    memory.finish();
    encodeMovie(files);
    EXPECT_EQ(memory.frames(), 7);
    EXPECT_GT(memory.cpuSeconds(), 0.0);
    const std::string from_memory = decodedFrames(dir / (std::string("memory") + ext));
    EXPECT_EQ(std::count(from_memory.begin(), from_memory.end(), '\n'), 7);
    EXPECT_EQ(from_memory, decodedFrames(files.output)) << ext;
    EXPECT_FALSE(fs::exists(dir / (std::string("memory") + ext + ".tmp" + ext)));
  }
  fs::remove_all(dir);
}

// An encoder dropped before finish() (the render failed) leaves no movie and no temporary; a frame of
// the wrong size and a bad file name are refused.
TEST(MovieEncoder, UnfinishedOrRefusedLeavesNoMovie) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "test_movie_encoder_fail";
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    MovieEncoder e({dir / "dropped.mp4"}, 32, 16);
    e.addFrame(testFrame(32, 16, 1));
    EXPECT_THROW(e.addFrame(testFrame(16, 16, 1)), std::invalid_argument);
  }
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_THROW(MovieEncoder({dir / "x.avi"}, 32, 16), std::runtime_error);
  EXPECT_THROW(MovieEncoder({dir / "x.mp4", 24, 18, MovieCodec::ProRes}, 32, 16), std::runtime_error);
  EXPECT_THROW(MovieEncoder({dir / "x.mp4"}, 0, 16), std::runtime_error);
  // No frames: an error, and no movie.
  MovieEncoder empty({dir / "empty.mp4"}, 32, 16);
  EXPECT_THROW(empty.finish(), std::runtime_error);
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(Movie, ShellQuoteSurvivesQuotes) {
  EXPECT_EQ(shellQuote("a'b"), "'a'\\''b'");
  EXPECT_EQ(run("printf %s " + shellQuote("it's $HOME")), "it's $HOME");
}

}  // namespace
}  // namespace stirrup::render
