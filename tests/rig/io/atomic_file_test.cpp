#include "rig/io/atomic_file.h"

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(AtomicFile, TheTemporaryIsBesideTheFileKeepingItsExtensionWhenAsked) {
  EXPECT_EQ(temporaryFor("out/a.0001.png"), fs::path("out/a.0001.png.tmp"));
  EXPECT_EQ(temporaryFor("out/m.mp4", TempName::KeepExtension), fs::path("out/m.mp4.tmp.mp4"));
}

TEST(AtomicFile, BytesReplaceTheFileWholeAndMakeItsFolder) {
  const fs::path dir = test::freshTestDir("test_atomic_file", "bytes");
  const fs::path f = dir / "new" / "folder" / "x.txt";
  writeFileAtomically(f, std::string_view("first"));
  EXPECT_EQ(contents(f), "first");
  writeFileAtomically(f, std::vector<unsigned char>{'2', 'n', 'd'});
  EXPECT_EQ(contents(f), "2nd");
  EXPECT_FALSE(fs::exists(temporaryFor(f)));
}

TEST(AtomicFile, ExecuteBitsAreAdded) {
  const fs::path f = test::freshTestDir("test_atomic_file", "perms") / "run.sh";
  writeFileAtomically(f, "#!/bin/sh\n", fs::perms::owner_exec);
  EXPECT_NE(fs::status(f).permissions() & fs::perms::owner_exec, fs::perms::none);
}

TEST(AtomicFile, AWriterThatThrowsLeavesTheOldFileAndNoTemporary) {
  const fs::path f = test::freshTestDir("test_atomic_file", "throws") / "keep.txt";
  writeFileAtomically(f, std::string_view("old"));
  EXPECT_THROW(replaceFileAtomically(f,
                                     [](const fs::path& tmp) {
                                       std::ofstream(tmp) << "half";
                                       throw std::runtime_error("disk full");
                                     }),
               std::runtime_error);
  EXPECT_EQ(contents(f), "old");
  EXPECT_FALSE(fs::exists(temporaryFor(f)));
}

TEST(AtomicFile, AFolderInTheWayIsAOneLineErrorAndNoTemporaryRemains) {
  const fs::path target = test::freshTestDir("test_atomic_file", "folder") / "taken";
  fs::create_directories(target / "inside");  // a non-empty folder where the file should go
  const std::string error = test::errorOf([&] { writeFileAtomically(target, std::string_view("x")); });
  EXPECT_EQ(error.rfind(target.string() + ": cannot write (", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_FALSE(fs::exists(temporaryFor(target)));
}

TEST(AtomicFile, AnUnwritableFolderIsAnErrorNamingTheFile) {
  const fs::path f = "/proc/stirrup-cannot-write-here/x.txt";
  EXPECT_EQ(test::errorOf([&] { writeFileAtomically(f, std::string_view("x")); }), f.string() + ": cannot write");
}

}  // namespace
}  // namespace stirrup::rig
