// stirrup render --format exr|both, --exr, --preset, --resolution and --set, end to end: the EXR a compositor gets has the
// passes and the camera, frame and scene in its header.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "tests/cli/run_command.h"
#include "tests/scene_folder.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// A small, quick copy of the default trot (the profile from the repository's scenes folder).
fs::path writeSmallScene(const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path file = dir / "small.json";
  std::ofstream(file) << R"({
    "name": "small",
    "profile": ")" << thesisProfile().string() << R"(",
    "resolution": [96, 54],
    "quality": {"preset": "draft", "samples": 2},
    "cameras": [{"name": "cam", "type": "perspective", "fov": 35,
                 "position": [20, 150, 700], "target": [20, 100, 0], "follow": true}]
  })";
  return file;
}

TEST(RenderExr, WritesPassesAndCameraMetadata) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "passes";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  const CommandResult ok =
      runStirrup("render " + quote(scene.string()) + " --frames 3 --format exr --out " + quote(dir.string()));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_FALSE(fs::exists(dir / "small_cam.0003.png"));
  const fs::path exr = dir / "small_cam.0003.exr";
  ASSERT_TRUE(fs::exists(exr));
  auto in = OIIO::ImageInput::open(exr.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec spec = in->spec();
  EXPECT_EQ(spec.width, 96);
  EXPECT_EQ(spec.height, 54);
  const std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
  EXPECT_EQ(names, (std::vector<std::string>{"R", "G", "B", "A", "Z", "matte", "objectId", "N.x", "N.y", "N.z"}));
  EXPECT_EQ(spec.channelformat(0), OIIO::TypeDesc::HALF);
  EXPECT_EQ(spec.get_string_attribute("stirrup:scene"), "small");
  EXPECT_EQ(spec.get_int_attribute("stirrup:frame"), 3);
  EXPECT_NEAR(spec.get_float_attribute("stirrup:time"), 2.0f / 24.0f, 1e-6f);
  EXPECT_EQ(spec.get_string_attribute("stirrup:camera"), "cam");
  EXPECT_EQ(spec.get_string_attribute("stirrup:camera:projection"), "perspective");
  EXPECT_EQ(spec.get_float_attribute("stirrup:camera:fov"), 35.0f);
  EXPECT_TRUE(spec.find_attribute("stirrup:camera:position"));
  EXPECT_TRUE(spec.find_attribute("stirrup:camera:target"));
  EXPECT_TRUE(spec.find_attribute("worldToCamera"));

  std::vector<float> px(size_t(96 * 54) * names.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, int(names.size()), OIIO::TypeDesc::FLOAT, px.data()));
  in->close();
  // The object ids are exactly sky, ground, horse and rider, and all but sky appear; the matte is
  // the characters only: 0 wherever the id is ground.
  int seen[3] = {0, 0, 0};
  for (size_t i = 0; i < size_t(96 * 54); ++i) {
    const float* p = &px[i * names.size()];
    const float id = p[6], matte = p[5];
    ASSERT_TRUE(id == -1.0f || id == 0.0f || id == 1.0f || id == 2.0f) << id;
    if (id >= 0.0f) ++seen[int(id)];
    if (id == 0.0f) {
      EXPECT_LE(matte, 0.5f);  // ground won the pixel's vote: at most half its samples saw a character
    }
    if (id == 1.0f || id == 2.0f) {
      EXPECT_GT(matte, 0.0f);
      const float len2 = p[7] * p[7] + p[8] * p[8] + p[9] * p[9];
      EXPECT_NEAR(len2, 1.0f, 0.01f);
      EXPECT_GT(p[4], 0.0f);  // depth in front of the camera
    }
  }
  EXPECT_GT(seen[0], 0);
  EXPECT_GT(seen[1], 0);
  EXPECT_GT(seen[2], 0);
}

TEST(RenderExr, ExrFlagWritesBothAndResumeNeedsBoth) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "both";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  const std::string args = "render " + quote(scene.string()) + " --frames 1-2 --exr --out " + quote(dir.string());
  ASSERT_EQ(runStirrup(args).exit_code, 0);
  for (const char* f : {"small_cam.0001.png", "small_cam.0001.exr", "small_cam.0002.png", "small_cam.0002.exr"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  // A frame missing its EXR is not complete: --resume renders it again.
  fs::remove(dir / "small_cam.0002.exr");
  const auto png_time = fs::last_write_time(dir / "small_cam.0001.png");
  ASSERT_EQ(runStirrup(args + " --resume").exit_code, 0);
  EXPECT_TRUE(fs::exists(dir / "small_cam.0002.exr"));
  EXPECT_EQ(fs::last_write_time(dir / "small_cam.0001.png"), png_time);
}

TEST(RenderExr, AnUnknownPresetIsAOneLineErrorBeforeAnyOutput) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "preset";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  const fs::path out = dir / "out";
  const CommandResult r =
      runStirrup("render " + quote(scene.string()) + " --preset fast --out " + quote(out.string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "stirrup: --preset: expected draft, review or final, got fast\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(RenderOverrides, ResolutionSetsTheFrameSize) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "resolution";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  const CommandResult r =
      runStirrup("render " + quote(scene.string()) + " --frames 2 --resolution 64x40 --out " + quote(dir.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto in = OIIO::ImageInput::open((dir / "small_cam.0002.png").string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 64);
  EXPECT_EQ(in->spec().height, 40);
}

TEST(RenderOverrides, ABadResolutionIsAOneLineErrorBeforeAnyOutput) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "bad_resolution";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  const fs::path out = dir / "out";
  for (const char* bad : {"320", "320x", "0x180", "320x180x2", "wide"}) {
    const CommandResult r = runStirrup("render " + quote(scene.string()) + " --resolution " + bad + " --out " + quote(out.string()));
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_EQ(r.err, std::string("stirrup: --resolution: expected WIDTHxHEIGHT (16-8192 each), got \"") + bad + "\"\n");
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
}

TEST(RenderOverrides, SetChangesTheRiderAndBadKeysAreOneLineErrors) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "set";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  for (const char* run : {"plain", "lifted"}) {
    const std::string set = std::string(run) == "lifted" ? " --set eq7.w2_scale=0.05" : "";
    const CommandResult r = runStirrup("render " + quote(scene.string()) + " --frames 5" + set + " --out " +
                                       quote((dir / run).string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_NE(readText(dir / "plain/small_cam.0005.png"), readText(dir / "lifted/small_cam.0005.png"));
  const fs::path out = dir / "bad";
  const CommandResult unknown = runStirrup("render " + quote(scene.string()) + " --set eq7.nope=1 --out " + quote(out.string()));
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_EQ(lineCount(unknown.err), 1u) << unknown.err;
  EXPECT_NE(unknown.err.find("--set: eq7.nope: unknown rig profile parameter"), std::string::npos) << unknown.err;
  const CommandResult text = runStirrup("render " + quote(scene.string()) + " --set eq7.w2_scale=high --out " + quote(out.string()));
  EXPECT_EQ(text.exit_code, 1);
  EXPECT_EQ(text.err, "stirrup: --set: eq7.w2_scale: expected a number, got \"high\"\n");
  EXPECT_FALSE(fs::exists(out));
}

// A crowd's pairs resolve their own profiles (each pair names one): --set reaches them too (it once
// changed only the scene's own profile, which no pair of a crowd rides with), and a bad key still names
// --set. Two riders, one thesis, one english, lifted alike.
TEST(RenderOverrides, SetReachesEveryPairOfACrowd) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "crowd_set";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene = dir / "two.json";
  std::ofstream(scene) << R"({"name": "two", "frames": "1-6", "resolution": [96, 54],
    "riders": [
      {"points": [[0, -200], [2000, -200]], "speed": [[0, 300]], "profile": "thesis", "seed": 1},
      {"points": [[0, 200], [2000, 200]], "speed": [[0, 300]], "profile": "english", "seed": 2}],
    "cameras": [{"name": "side", "view": "side", "follow_pair": 0}, {"name": "other", "view": "side", "follow_pair": 1}]})";
  for (const char* camera : {"side", "other"}) {
    SCOPED_TRACE(camera);
    for (const char* run : {"plain", "lifted"}) {
      const std::string set = std::string(run) == "lifted" ? " --set eq7.w2_scale=0.05" : "";
      const CommandResult r = runStirrup("render " + quote(scene.string()) + " --camera " + camera + " --frames 5 --preset draft" +
                                         set + " --out " + quote((dir / run).string()));
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const std::string frame = std::string("two_") + camera + ".0005.png";
    EXPECT_NE(readText(dir / "plain" / frame), readText(dir / "lifted" / frame));
  }
  const CommandResult unknown = runStirrup("render " + quote(scene.string()) + " --set eq7.nope=1 --out " + quote((dir / "bad").string()));
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_EQ(lineCount(unknown.err), 1u) << unknown.err;
  EXPECT_NE(unknown.err.find("--set: eq7.nope: unknown rig profile parameter"), std::string::npos) << unknown.err;
}

TEST(RenderExr, APresetChangesTheSamples) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "presets";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  for (const char* preset : {"draft", "review"}) {
    const CommandResult r = runStirrup("render " + quote(scene.string()) + " --frames 2 --preset " + preset +
                                       " --out " + quote((dir / preset).string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_NE(readText(dir / "draft/small_cam.0002.png"), readText(dir / "review/small_cam.0002.png"));
}

TEST(RenderEncodeOnly, EncodesTheFramesThereAndNamesAMissingOne) {
  // A farm's last step: render nothing, encode what the tasks wrote.
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "render_exr_test" / "encode_only";
  fs::remove_all(dir);
  const fs::path scene = writeSmallScene(dir);
  const std::string base = "render " + quote(scene.string()) + " --out " + quote(dir.string());
  ASSERT_EQ(runStirrup(base + " --frames 1-2").exit_code, 0);
  const fs::path movie = dir / "small.mp4";
  CommandResult r = runStirrup(base + " --frames 1-3 --encode-only --movie " + quote(movie.string()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "stirrup: --encode-only: frame 3 is missing (" + (dir / "small_cam.0003.png").string() + ")\n");
  EXPECT_FALSE(fs::exists(movie));
  EXPECT_FALSE(fs::exists(dir / "small_cam.0003.png"));  // nothing rendered
  r = runStirrup(base + " --frames 1-2 --encode-only --movie " + quote(movie.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(runCommand("ffprobe -v error -count_frames -show_entries stream=nb_read_frames -of csv=p=0 " +
                       quote(movie.string())).out, "2\n");
  r = runStirrup(base + " --encode-only");
  EXPECT_EQ(r.err, "stirrup: --encode-only: expected --movie FILE.mp4 to encode\n");
}

}  // namespace
}  // namespace stirrup::test
