#include "render/review/movie.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

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

TEST(Movie, ShellQuoteSurvivesQuotes) {
  EXPECT_EQ(shellQuote("a'b"), "'a'\\''b'");
  EXPECT_EQ(run("printf %s " + shellQuote("it's $HOME")), "it's $HOME");
}

}  // namespace
}  // namespace stirrup::render
