// What the program does before any subcommand: STIRRUP_SIMD pins the integrator's SIMD target.
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

}  // namespace
}  // namespace stirrup::test
