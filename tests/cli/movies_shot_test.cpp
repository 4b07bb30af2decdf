// stirrup movies SHOT.glb: the review movie set of a glTF shot (render/review/movie_set.h shotMovieSet),
// run on a real `stirrup bake`. The oracle for "as render does" is `stirrup render SHOT.glb` of the same
// view, frame, preset and size: its objectId pass says where the horse and the rider are, and the movie's
// frame must show them there, as render's frame does.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "tests/cli/run_command.h"
#include "tests/test_files.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 320, kHeight = 180;
// The burn-in bands at 180 rows (render/review/burn_in.cpp: text size max(9, h/24) = 9, band 9 + 4 + 2).
constexpr int kBand = 15;

std::string probe(const fs::path& movie) {
  return runCommand("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                    "stream=codec_name,pix_fmt,width,height,r_frame_rate,nb_read_frames -of csv=p=0 " + quote(movie.string()))
      .out;
}

// The image's channels [first, first + count) as floats, row by row (empty when it cannot be read).
std::vector<float> readChannels(const fs::path& file, int first, int count, int* width = nullptr) {
  auto in = OIIO::ImageInput::open(file.string());
  EXPECT_TRUE(in) << file << ": " << OIIO::geterror();
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  if (width) *width = spec.width;
  std::vector<float> pixels(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(count));
  EXPECT_TRUE(in->read_image(0, 0, first, first + count, OIIO::TypeDesc::FLOAT, pixels.data())) << file;
  return pixels;
}

std::vector<float> objectIds(const fs::path& exr) {
  auto in = OIIO::ImageInput::open(exr.string());
  EXPECT_TRUE(in) << exr;
  if (!in) return {};
  const int channel = in->spec().channelindex("objectId");
  EXPECT_GE(channel, 0) << exr;
  in->close();
  return channel < 0 ? std::vector<float>{} : readChannels(exr, channel, 1);
}

std::string bake(const fs::path& dir, const std::string& frames) {
  const fs::path shot = dir / "trot.glb";
  const CommandResult b = runStirrup("bake " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json") + " -o " + quote(shot.string()) +
                                     " --frames " + frames);
  EXPECT_EQ(b.exit_code, 0) << b.err;
  return shot.string();
}

// A real bake of the trot's first six frames: its side, persp and close movies are playable H.264 (a
// one-second slate and the six frames, at the size asked), and each movie's frame 3, decoded from the .mp4,
// shows the horse and the rider where `stirrup render SHOT.glb` draws them; the frame the movie was encoded
// from is render's frame to the byte between the burn-in bands.
TEST(MoviesShot, ABakeMakesPlayableMoviesOfThePair) {
  const fs::path dir = freshTestDir("movies_shot_test", "bake");
  const std::string shot = bake(dir, "1-6");
  const fs::path out = dir / "movies";
  const std::string size = std::to_string(kWidth) + "x" + std::to_string(kHeight);
  const CommandResult m = runStirrup("movies " + quote(shot) + " --only side,trot_persp,close --preset draft --resolution " + size +
                                     " --date 2026-01-01 --keep-frames --out " + quote(out.string()));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(m.out, (out / "index.html").string() + "\n");
  EXPECT_EQ(m.err, "");
  EXPECT_FALSE(fs::exists(out / "trot_plot.png"));  // a shot's rider is posed as keyed: no channel plot
  EXPECT_FALSE(fs::exists(out / "trot_turntable.mp4"));  // not asked for
  for (const std::string view : {"side", "persp", "close"}) {
    const std::string name = "trot_" + view;
    EXPECT_EQ(probe(out / (name + ".mp4")), "h264,320,180,yuv420p,24/1,30\n") << name;  // 24 slate frames and 6
    EXPECT_TRUE(fs::is_regular_file(out / (name + "_sheet.png"))) << name;
    EXPECT_NE(readText(out / "index.html").find(name + ".mp4"), std::string::npos) << name;

    const fs::path rendered = dir / "render";
    const CommandResult r = runStirrup("render " + quote(shot) + " --camera " + view + " --frames 3 --preset draft --resolution " + size +
                                       " --format both --out " + quote(rendered.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<float> ids = objectIds(rendered / (name + ".0003.exr"));
    const std::vector<float> want = readChannels(rendered / (name + ".0003.png"), 0, 3);
    const std::vector<float> kept = readChannels(out / "frames" / name / (name + ".0003.png"), 0, 3);
    const fs::path decoded = dir / (name + ".decoded.png");  // the movie's 27th frame: the slate's 24, then 1, 2, 3
    const CommandResult d = runCommand("ffmpeg -v error -y -i " + quote((out / (name + ".mp4")).string()) +
                                       " -vf 'select=eq(n\\,26)' -vframes 1 " + quote(decoded.string()));
    ASSERT_EQ(d.exit_code, 0) << d.err;
    const std::vector<float> movie = readChannels(decoded, 0, 3);
    ASSERT_EQ(ids.size(), std::size_t(kWidth * kHeight));
    ASSERT_EQ(want.size(), ids.size() * 3);
    ASSERT_EQ(kept.size(), want.size());
    ASSERT_EQ(movie.size(), want.size());
    // Between the burn-in bands: the pair's pixels (objectId 1 the horse, 2 the rider) and the mean colour
    // of the rest, the background the movie would show there without the pair.
    int horse = 0, rider = 0, unequal = 0, background = 0;
    double pair_error = 0.0, sky_ground[3] = {0.0, 0.0, 0.0};
    for (int y = kBand; y < kHeight - kBand; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const std::size_t p = std::size_t(y) * kWidth + std::size_t(x);
        for (int c = 0; c < 3; ++c) unequal += kept[3 * p + std::size_t(c)] != want[3 * p + std::size_t(c)];
        const long id = std::lround(ids[p]);
        if (id != 1 && id != 2) {
          ++background;
          for (int c = 0; c < 3; ++c) sky_ground[c] += want[3 * p + std::size_t(c)];
          continue;
        }
        (id == 1 ? horse : rider) += 1;
        for (int c = 0; c < 3; ++c) pair_error += std::abs(movie[3 * p + std::size_t(c)] - want[3 * p + std::size_t(c)]);
      }
    EXPECT_EQ(unequal, 0) << name << ": the movie's frame is not render's";
    // The pair is in the frame (measured at 320x180: 4200 to 7600 horse and 940 to 4700 rider pixels).
    EXPECT_GT(horse, 1000) << name;
    EXPECT_GT(rider, 300) << name;
    // The movie over the pair's pixels against render's, and the background's mean colour against render's
    // there: H.264 at CRF 18 in yuv420p (and the draft's one sample a pixel, which it smooths) keeps the
    // first small, a movie without the pair there would be off by the second.
    double control = 0.0;
    for (int y = kBand; y < kHeight - kBand; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const std::size_t p = std::size_t(y) * kWidth + std::size_t(x);
        const long id = std::lround(ids[p]);
        if (id == 1 || id == 2)
          for (int c = 0; c < 3; ++c) control += std::abs(sky_ground[c] / background - want[3 * p + std::size_t(c)]);
      }
    const double mean = pair_error / (3.0 * (horse + rider)), off = control / (3.0 * (horse + rider));
    EXPECT_LT(mean, 0.04) << name << ": the movie does not show the pair where render draws it";
    EXPECT_LT(mean, off / 4.0) << name << ": the movie is as far from render's pair as the background is";
    std::printf("%s: horse %d px, rider %d px; over them the movie against render: mean %.4f, the background: %.4f\n", name.c_str(),
                horse, rider, mean, off);
  }
}

// With a look (issue 60: `movies SHOT.glb --scene LOOK.json`, as `render SHOT.glb --scene` takes it): the
// movies are the look's cameras, made with its size, quality, sun and ground. Cross_country's bake (its
// hills under it) with cross_country as the look: its four cameras listed; the top movie's kept frame is
// render's of the same camera, look, frame, preset and size, to the byte between the burn-in bands.
TEST(MoviesShot, WithALookTheMoviesAreTheLooksCameras) {
  const fs::path dir = freshTestDir("movies_shot_test", "look");
  const fs::path shot = dir / "cc.glb";
  const std::string look = quote(STIRRUP_SOURCE_DIR "/scenes/cross_country.json");
  ASSERT_EQ(runStirrup("bake " + look + " --frames 1-3 -o " + quote(shot.string())).exit_code, 0);
  const CommandResult l = runStirrup("movies " + quote(shot.string()) + " --scene " + look + " --list");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  std::string want;
  for (const char* camera : {"persp", "side", "close", "top"}) want += std::string("cc_") + camera + "\t" + shot.string() + "\t" + camera + "\n";
  EXPECT_EQ(l.out, want);
  const fs::path out = dir / "movies";
  const CommandResult m = runStirrup("movies " + quote(shot.string()) + " --scene " + look + " --only top --preset draft --resolution 160x90 " +
                                     "--date 2026-01-01 --keep-frames --out " + quote(out.string()));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(probe(out / "cc_top.mp4"), "h264,160,90,yuv420p,24/1,27\n");  // 24 slate frames and 3
  const fs::path rendered = dir / "render";
  const CommandResult r = runStirrup("render " + quote(shot.string()) + " --scene " + look + " --camera top --frames 2 --preset draft " +
                                     "--resolution 160x90 --out " + quote(rendered.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<float> want_px = readChannels(rendered / "cross_country_top.0002.png", 0, 3);
  const std::vector<float> kept = readChannels(out / "frames" / "cc_top" / "cc_top.0002.png", 0, 3);
  ASSERT_EQ(want_px.size(), std::size_t(160 * 90 * 3));
  ASSERT_EQ(kept.size(), want_px.size());
  const int band = kBand;  // the burn-in bands: 15 rows at any height up to 360 (9-point text at least)
  int unequal = 0;
  for (std::size_t i = std::size_t(band) * 160 * 3; i < std::size_t(90 - band) * 160 * 3; ++i) unequal += kept[i] != want_px[i];
  EXPECT_EQ(unequal, 0) << "the movie's frame is not render's";
}

// --list names the shot's set: its five views over the shot.
TEST(MoviesShot, ListsTheShotsViews) {
  const fs::path dir = freshTestDir("movies_shot_test", "list");
  const std::string shot = bake(dir, "1-2");
  const CommandResult l = runStirrup("movies " + quote(shot) + " --list");
  ASSERT_EQ(l.exit_code, 0) << l.err;
  std::string want;
  for (const char* view : {"side", "persp", "close", "turntable", "top"}) want += std::string("trot_") + view + "\t" + shot + "\t" + view + "\n";
  EXPECT_EQ(l.out, want);
  // --only before the shot takes one value an occurrence (names by commas, or the option again): the
  // path after it is the shot, not a second name.
  const CommandResult only = runStirrup("movies --only side --only top,close " + quote(shot) + " --list");
  ASSERT_EQ(only.exit_code, 0) << only.err;
  EXPECT_EQ(only.out, "trot_side\t" + shot + "\tside\ntrot_close\t" + shot + "\tclose\ntrot_top\t" + shot + "\ttop\n");
}

// Bad input: a .glb that is not a shot (not glTF at all; a horse clip), a view a shot cannot make asked for
// by name, a scene file where the shot goes, --scenes with a shot: each one line naming the file or the
// view, exit 1, and no output folder, so no movie, half-written or whole.
TEST(MoviesShot, BadInputIsAOneLineErrorAndNoMovie) {
  const fs::path dir = freshTestDir("movies_shot_test", "bad");
  const fs::path out = dir / "movies";
  const fs::path junk = dir / "notgltf.glb";
  std::ofstream(junk) << "nothing";
  const fs::path clip = dir / "trot_clip.glb";
  ASSERT_EQ(runStirrup("clip make trot -o " + quote(clip.string())).exit_code, 0);
  const std::string shot = bake(dir, "1-2");
  struct Case {
    std::string args, says;
  };
  const std::vector<Case> cases = {
      {quote(junk.string()), junk.string() + ": "},
      {quote(clip.string()), clip.string() + ": not a shot (expected a stirrup bake"},
      {quote(shot) + " --only layered", "--only: layered: the layered view cannot be made from a glTF shot"},
      {quote(shot) + " --only side,trot_layered", "--only: trot_layered: the layered view cannot be made from a glTF shot"},
      {quote(shot) + " --only follow", "--only: follow: the follow view cannot be made from a glTF shot"},
      {quote(shot) + " --only sideways", "--only: no movie named \"sideways\" for the glTF shot " + shot},
      {quote(STIRRUP_SOURCE_DIR "/scenes/trot.json"), STIRRUP_SOURCE_DIR "/scenes/trot.json: expected a glTF shot"},
      {quote(shot) + " --scenes " + quote(STIRRUP_SOURCE_DIR "/scenes"), "--scenes: chooses the scene set's scenes, not a glTF shot's"},
      {"--scene " + quote(STIRRUP_SOURCE_DIR "/scenes/trot.json"), "--scene: the look of a glTF shot's movies"},
      {quote(shot) + " --scene " + quote((dir / "nope.json").string()), (dir / "nope.json").string() + ": cannot open the file"},
  };
  for (const Case& c : cases) {
    const CommandResult r = runStirrup("movies " + c.args + " --preset draft --resolution 96x54 --out " + quote(out.string()));
    EXPECT_EQ(r.exit_code, 1) << c.args << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args << ": wrote " << out;
  }
}

}  // namespace
}  // namespace stirrup::test
