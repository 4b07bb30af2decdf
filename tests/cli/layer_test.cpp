// `stirrup layer` end to end: sequences in, composited sequences out, frame mapping, frame lists,
// errors that leave nothing behind, and a scene whose reference footage is absent.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "render/tracer/image.h"
#include "render/review/layer.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::path(STIRRUP_BINARY_DIR) / "layer_cli_test" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

render::Image grey(int w, int h, float v) {
  render::Image img(w, h);
  for (glm::vec4& p : img.rgba) p = {v, v, v, 1.0f};
  return img;
}

std::string frameName(const std::string& stem, int f) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s.%04d.png", stem.c_str(), f);
  return buf;
}

// The 8-bit sRGB code of a written pixel's green channel.
int code(const fs::path& file, int x = 0, int y = 0) {
  return render::linearToSrgb8(render::readLinearImage(file).at(x, y).y);
}

int fileCount(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(LayerCli, HelpNamesTheOptions) {
  const CommandResult r = runStirrup("layer --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--mode", "--opacity", "--offset", "--rate", "--crop", "--scale", "--position", "--frames",
                          "--grid", "--scene", "side-by-side"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(LayerCli, OffsetAndRatePickBsFramesFrameByFrame) {
  const fs::path dir = freshDir("mapping");
  fs::create_directories(dir / "out");
  // A: 4 black frames. B: 8 frames, frame k a grey whose sRGB code is 20 k (linear from the code).
  for (int f = 1; f <= 4; ++f) render::writePng(grey(4, 2, 0.0f), dir / frameName("a", f));
  for (int k = 1; k <= 8; ++k) {
    const float srgb = 20.0f * float(k) / 255.0f;
    const float linear = srgb <= 0.04045f ? srgb / 12.92f : std::pow((srgb + 0.055f) / 1.055f, 2.4f);
    render::writePng(grey(4, 2, linear), dir / frameName("b", k));
  }
  // Over at opacity 0 over the whole frame shows B exactly; rate 2, offset 1: A's frame f shows B's
  // frame 2 + 2 (f - 1) = 2, 4, 6, 8.
  const CommandResult r = runStirrup("layer " + quote((dir / "a.####.png").string()) + " " + quote((dir / "b.####.png").string()) +
                                     " -o " + quote((dir / "out/o.####.png").string()) +
                                     " --mode over --opacity 0 --coverage full --offset 1 --rate 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  for (int f = 1; f <= 4; ++f) EXPECT_EQ(code(dir / "out" / frameName("o", f)), 20 * (2 + 2 * (f - 1))) << f;
  EXPECT_EQ(fileCount(dir / "out"), 4);
}

TEST(LayerCli, FrameListAndDifference) {
  const fs::path dir = freshDir("difference");
  fs::create_directories(dir / "out");
  // A 0.5 linear (code 188), B black: the difference at gain 1 is A.
  for (int f = 1; f <= 5; ++f) {
    render::writePng(grey(3, 3, 0.5f), dir / frameName("a", f));
    render::writePng(grey(3, 3, 0.0f), dir / frameName("b", f));
  }
  const CommandResult r = runStirrup("layer " + quote((dir / "a.####.png").string()) + " " + quote((dir / "b.####.png").string()) +
                                     " -o " + quote((dir / "out/d.####.png").string()) +
                                     " --mode difference --gain 1 --frames 1-5x2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(fileCount(dir / "out"), 3);
  for (int f : {1, 3, 5}) EXPECT_EQ(code(dir / "out" / frameName("d", f), 2, 2), 188) << f;
  EXPECT_FALSE(fs::exists(dir / "out" / frameName("d", 2)));
}

// A printf pattern names a sequence as #s do (docs/frame-sequences.md): -o OUT.%04d.png writes a file a
// frame (it once wrote every frame over one file named OUT.%04d.png), and B.%04d.png reads B's frames.
TEST(LayerCli, PrintfPatternsAreSequencesToo) {
  const fs::path dir = freshDir("printf");
  fs::create_directories(dir / "out");
  for (int f = 1; f <= 3; ++f) {
    render::writePng(grey(3, 3, 0.5f), dir / frameName("a", f));
    render::writePng(grey(3, 3, 0.0f), dir / frameName("b", f));
  }
  const CommandResult r = runStirrup("layer " + quote((dir / "a.%04d.png").string()) + " " + quote((dir / "b.%04d.png").string()) +
                                     " -o " + quote((dir / "out/d.%04d.png").string()) + " --mode difference --gain 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(fileCount(dir / "out"), 3);
  for (int f = 1; f <= 3; ++f) EXPECT_EQ(code(dir / "out" / frameName("d", f), 1, 1), 188) << f;
  EXPECT_FALSE(fs::exists(dir / "out" / "d.%04d.png"));
}

TEST(LayerCli, SideBySideIsBothAtAsHeight) {
  const fs::path dir = freshDir("side");
  render::writePng(grey(8, 6, 1.0f), dir / "a.png");
  render::writePng(grey(6, 3, 0.0f), dir / "b.png");
  const CommandResult r = runStirrup("layer " + quote((dir / "a.png").string()) + " " + quote((dir / "b.png").string()) + " -o " +
                                     quote((dir / "s.png").string()) + " --mode side-by-side --no-labels");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const render::Image s = render::readLinearImage(dir / "s.png");
  EXPECT_EQ(s.height, 6);
  EXPECT_EQ(s.width, 8 + 4 + 12);  // A, the 4-pixel gap, B doubled to height 6
  EXPECT_EQ(render::linearToSrgb8(s.at(7, 5).x), 255);
  EXPECT_EQ(render::linearToSrgb8(s.at(23, 5).x), 0);
}

TEST(LayerCli, BadInputIsOneLineAndWritesNothing) {
  const fs::path dir = freshDir("errors");
  fs::create_directories(dir / "out");
  for (int f = 1; f <= 2; ++f) render::writePng(grey(4, 4, 0.2f), dir / frameName("a", f));
  render::writePng(grey(4, 4, 0.2f), dir / "b.png");
  const std::string a = quote((dir / "a.####.png").string()), out = " -o " + quote((dir / "out/o.####.png").string());
  struct Case {
    std::string args, expect;
  };
  const Case cases[] = {
      {a + " " + quote((dir / "missing.png").string()) + out, "missing.png: no such image file"},
      {a + " " + quote((dir / "b.png").string()) + out + " --crop 2,2,4,4", "crop: rectangle 2,2,4,4"},
      {a + " " + quote((dir / "b.png").string()) + out + " --crop 1,1", "--crop: expected x,y,width,height"},
      {a + " " + quote((dir / "b.png").string()) + out + " --mode blend", "--mode: expected side-by-side"},
      {a + " " + quote((dir / "b.png").string()) + out + " --frames 1-3", "frame 3 is not in the sequence"},
      {a + " " + quote((dir / "b.png").string()) + out + " --position 1", "--position: expected x,y"},
      {a + " " + quote((dir / "b.png").string()) + " -o " + quote((dir / "out/one.png").string()),
       "-o: expected a sequence pattern"},
      {a + " " + quote((dir / "b.png").string()) + out + " --grid 2", "--grid: expected ROWSxCOLUMNS"},
      {a + " " + quote((dir / "b.png").string()) + out + " --grid 1x2 --cell-crop 0,0,3,3", "grid.cell_crop"},
  };
  for (const Case& c : cases) {
    const CommandResult r = runStirrup("layer " + c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(fileCount(dir / "out"), 0) << c.args;
  }
}

TEST(LayerCli, PlateGridCutsFrames) {
  const fs::path dir = freshDir("plate");
  // A 2x3 plate of 4x4 cells, cell k (reading order) grey code 40 k.
  render::Image plate(12, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 12; ++x) {
      const int k = 1 + (y / 4) * 3 + x / 4;
      const float srgb = 40.0f * float(k) / 255.0f;
      const float linear = std::pow((srgb + 0.055f) / 1.055f, 2.4f);
      plate.at(x, y) = {linear, linear, linear, 1.0f};
    }
  render::writePng(plate, dir / "plate.png");
  for (int f = 1; f <= 6; ++f) render::writePng(grey(4, 4, 0.0f), dir / frameName("a", f));
  const CommandResult r = runStirrup("layer " + quote((dir / "a.####.png").string()) + " " + quote((dir / "plate.png").string()) +
                                     " --grid 2x3 --mode over --opacity 0 --coverage full --offset 2 --edge loop -o " +
                                     quote((dir / "o.####.png").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // offset 2: A's frame f shows cell 3 + (f - 1), looping after cell 6.
  const int want[] = {3, 4, 5, 6, 1, 2};
  for (int f = 1; f <= 6; ++f) EXPECT_EQ(code(dir / frameName("o", f), 2, 2), 40 * want[f - 1]) << f;
}

TEST(LayerCli, SceneWithAbsentReferenceIsSkipped) {
  const fs::path dir = freshDir("scene");
  render::writePng(grey(4, 4, 0.2f), dir / "a.0001.png");
  {
    std::FILE* f = std::fopen((dir / "s.json").c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(R"({"reference": {"file": "no/such/plate.jpg", "grid": {"rows": 2, "columns": 6}}})", f);
    std::fclose(f);
  }
  const CommandResult r = runStirrup("layer " + quote((dir / "a.####.png").string()) + " --scene " + quote((dir / "s.json").string()) +
                                     " -o " + quote((dir / "o.####.png").string()));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("skipped"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("plate.jpg"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "o.0001.png"));
}

TEST(LayerCli, MuybridgePlateAgainstAFrame) {
  const fs::path plate = fs::path(STIRRUP_SHARED_DIR) / "reference/muybridge/horse-and-rider-gallop-plate.jpg";
  if (!fs::exists(plate)) GTEST_SKIP() << plate << " is absent (../shared/reference)";
  const fs::path dir = freshDir("muybridge");
  for (int f = 1; f <= 2; ++f) render::writePng(grey(640, 360, 0.5f), dir / frameName("a", f));
  const CommandResult r = runStirrup("layer " + quote((dir / "a.####.png").string()) + " --scene " +
                                     quote(std::string(STIRRUP_SOURCE_DIR) + "/scenes/gallop_layered.json") + " -o " +
                                     quote((dir / "o.####.png").string()) + " --mode side-by-side");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const render::Image o = render::readLinearImage(dir / frameName("o", 2));
  EXPECT_EQ(o.height, 360);
  EXPECT_GT(o.width, 640 + 4 + 300);
}

}  // namespace
}  // namespace stirrup::test
