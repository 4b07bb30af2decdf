// What the program does before any subcommand: STIRRUP_SIMD pins the integrator's SIMD target; and
// what it loads to start (OpenImageIO only when a command reads or writes an image file or draws text).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

TEST(Main, AnUnknownSimdTargetIsAOneLineError) {
  const CommandResult r = runCommand("STIRRUP_SIMD=NEON " + quote(STIRRUP_EXE) + " bench --help");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.find("stirrup: error: STIRRUP_SIMD: SIMD target \"NEON\": expected one of "), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
}

// The same frame rendered on the oldest x86 target the kernels have and on the CPU's best is the same
// image, through the whole program.
TEST(Main, APinnedSimdTargetRendersTheSameFrame) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "main_simd";
  fs::remove_all(dir);
  const std::string scene = quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes/trot.json").string());
  const std::string args = " render " + scene + " --camera persp --frames 28 --resolution 160x90 --preset review --out ";
  const CommandResult best = runCommand(quote(STIRRUP_EXE) + args + quote((dir / "best").string()));
  ASSERT_EQ(best.exit_code, 0) << best.err;
  const CommandResult sse4 = runCommand("STIRRUP_SIMD=SSE4 " + quote(STIRRUP_EXE) + args + quote((dir / "sse4").string()));
  ASSERT_EQ(sse4.exit_code, 0) << sse4.err;
  const CommandResult same = runStirrup("diff " + quote((dir / "best/trot_persp.0028.png").string()) + " " +
                                        quote((dir / "sse4/trot_persp.0028.png").string()) +
                                        " --fail 0 --failpercent 0 --warn 0 --warnpercent 0");
  EXPECT_EQ(same.exit_code, 0) << same.out << same.err;
}

// The dynamic loader's record of the files a run loaded (LD_DEBUG=files, on stderr).
std::string loadedFiles(const std::string& args) {
  const CommandResult r = runCommand("LD_DEBUG=files " + quote(STIRRUP_EXE) + " " + args);
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err.substr(r.err.size() > 2000 ? r.err.size() - 2000 : 0);
  return r.err;
}

// OpenImageIO and its some 250 libraries cost 0.4 s of CPU at every start (docs/performance-history.md,
// "Process start"): a run that touches no image file loads none of them; one that does loads the
// module, found beside the program, and OpenImageIO through it.
TEST(Main, OpenImageIOIsLoadedOnlyByARunThatReadsOrWritesAnImageFile) {
  const fs::path dir = fs::path(STIRRUP_BINARY_DIR) / "main_loads";
  fs::remove_all(dir);
  const std::string scene = quote((fs::path(STIRRUP_SOURCE_DIR) / "scenes/trot.json").string());
  const std::string help = loadedFiles("--help");
  EXPECT_NE(help.find("file=libembree3.so"), std::string::npos) << "LD_DEBUG gave no record";
  EXPECT_EQ(help.find("OpenImageIO"), std::string::npos);
  EXPECT_EQ(help.find("libstirrup_openimageio.so"), std::string::npos);
  const std::string render =
      loadedFiles("render " + scene + " --frames 5 --resolution 64x36 --preset draft --out " + quote((dir / "a").string()));
  EXPECT_EQ(render.find("OpenImageIO"), std::string::npos);
  ASSERT_TRUE(fs::is_regular_file(dir / "a/trot_side.0005.png"));
  const std::string diff = loadedFiles("diff " + quote((dir / "a/trot_side.0005.png").string()) + " " +
                                       quote((dir / "a/trot_side.0005.png").string()));
  EXPECT_NE(diff.find("libstirrup_openimageio.so [0];  dynamically loaded by"), std::string::npos);
  EXPECT_NE(diff.find("file=libOpenImageIO.so"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stirrup::test
