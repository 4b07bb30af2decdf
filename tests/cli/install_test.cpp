// The installed program (docs/install.md): `cmake --install BUILD --prefix P` into a temporary prefix,
// then P/bin/stirrup renders, evaluates the rig and makes a review movie from a folder outside the source
// tree with none of stirrup's variables set, finding its data in P/share/stirrup. The binary has no
// source or build path compiled in. And `cpack -G DEB` makes a package that depends on what it runs.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

// Every stirrup variable unset, so nothing points the program at the source tree.
const std::string kCleanEnv = "env -u STIRRUP_DATA -u STIRRUP_PROFILES -u STIRRUP_SHARED_DIR -u STIRRUP_FONT ";

class Installed : public ::testing::Test {
 protected:
  static fs::path root_, prefix_, work_;
  static std::string install_error_;

  // One install for the suite, in the system's temporary folder (outside the source and build trees).
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("stirrup_install_test_" + std::to_string(::getpid()));
    prefix_ = root_ / "prefix";
    work_ = root_ / "work";
    fs::remove_all(root_);
    fs::create_directories(work_);
    const CommandResult r = runCommand(quote(STIRRUP_CMAKE) + " --install " + quote(STIRRUP_BINARY_DIR) + " --prefix " +
                                       quote(prefix_.string()));
    if (r.exit_code != 0) install_error_ = "cmake --install exited " + std::to_string(r.exit_code) + ": " + r.err + r.out;
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

  void SetUp() override { ASSERT_TRUE(install_error_.empty()) << install_error_; }

  // The installed program run in the work folder.
  static CommandResult run(const std::string& args) {
    return runCommand("cd " + quote(work_.string()) + " && " + kCleanEnv + quote((prefix_ / "bin/stirrup").string()) + " " + args);
  }
};
fs::path Installed::root_, Installed::prefix_, Installed::work_;
std::string Installed::install_error_;

TEST_F(Installed, LaysOutTheProgramAndItsData) {
  EXPECT_TRUE(fs::is_regular_file(prefix_ / "bin/stirrup"));
  // OpenImageIO's module, which the program loads from ../LIBDIR/stirrup when it needs image files.
  EXPECT_TRUE(fs::is_regular_file(prefix_ / STIRRUP_INSTALL_LIBDIR / "stirrup/libstirrup_openimageio.so"));
  for (const char* f : {"scenes/trot.json", "scenes/jump.json", "scenes/profiles/thesis.json", "scenes/profiles/english.json",
                        "scenes/characters/horse.glb", "scenes/characters/rider.glb", "scenes/characters/rider-mapping.json"})
    EXPECT_TRUE(fs::is_regular_file(prefix_ / "share/stirrup" / f)) << f;
  EXPECT_TRUE(fs::is_regular_file(prefix_ / "share/doc/stirrup/install.md"));
  EXPECT_TRUE(fs::is_regular_file(prefix_ / "share/doc/stirrup/LICENSE"));
  // Not a link back into the source tree: real files.
  EXPECT_FALSE(fs::is_symlink(prefix_ / "share/stirrup"));
  EXPECT_FALSE(fs::is_symlink(prefix_ / "share/stirrup/scenes"));
  // The Blender add-on (docs/blender.md), its own files.
  for (const char* f : {"__init__.py", "ride.py", "controls.py", "layer.py", "reduce.py", "live.py", "check.py", "review.py", "panel.py", "program.py"})
    EXPECT_TRUE(fs::is_regular_file(prefix_ / "share/stirrup/blender/stirrup_blender" / f)) << f;
  EXPECT_FALSE(fs::is_symlink(prefix_ / "share/stirrup/blender/stirrup_blender"));
  EXPECT_FALSE(fs::exists(prefix_ / "share/stirrup/blender/stirrup_blender/__pycache__"));
}

// The installed add-on, linked into Blender's add-ons folder as docs/blender.md says, enables and finds
// the program beside its install (P/bin/stirrup) with none on PATH.
TEST_F(Installed, TheBlenderAddOnFindsTheProgramBesideItsInstall) {
  if (runCommand("command -v blender >/dev/null").exit_code != 0) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)";
  const fs::path addons = work_ / "blender-scripts" / "addons";
  fs::create_directories(addons);
  fs::create_directory_symlink(prefix_ / "share/stirrup/blender/stirrup_blender", addons / "stirrup_blender");
  const CommandResult r = runCommand(
      "cd " + quote(work_.string()) + " && " + kCleanEnv + "BLENDER_USER_SCRIPTS=" + quote((work_ / "blender-scripts").string()) +
      " PATH=/usr/bin:/bin blender -b --factory-startup --python-exit-code 3 --python-expr "
      "'import addon_utils; m = addon_utils.enable(\"stirrup_blender\", default_set=True); "
      "from stirrup_blender import program; print(\"stirrup program:\", program.find_program())' 2>&1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("stirrup program: " + fs::weakly_canonical(prefix_ / "bin/stirrup").string() + "\n"), std::string::npos) << r.out;
}

TEST_F(Installed, HasNoSourceOrBuildPathCompiledIn) {
  std::ifstream in(prefix_ / "bin/stirrup", std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ASSERT_GT(bytes.size(), 100000u);
  for (const std::string& path : {fs::weakly_canonical(STIRRUP_SOURCE_DIR).string(), std::string(STIRRUP_SOURCE_DIR),
                                 fs::weakly_canonical(STIRRUP_BINARY_DIR).string()})
    EXPECT_EQ(bytes.find(path), std::string::npos) << "the installed program contains " << path;
}

TEST_F(Installed, FindsItsDataBesideItselfFromAnyFolder) {
  const CommandResult r = run("movies --list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string data = fs::weakly_canonical(prefix_ / "share/stirrup/scenes").string();
  EXPECT_NE(r.out.find("trot_side\t" + data + "/trot.json\tside"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(fs::weakly_canonical(STIRRUP_SOURCE_DIR).string()), std::string::npos) << r.out;
  // STIRRUP_DATA overrides; a folder without scenes/ is a one-line error naming it.
  const CommandResult bad = runCommand("cd " + quote(work_.string()) + " && STIRRUP_DATA=" + quote(work_.string()) + " " +
                                       quote((prefix_ / "bin/stirrup").string()) + " movies --list");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.err, "stirrup: STIRRUP_DATA: " + work_.string() +
                         ": no scenes/ folder there (expected stirrup's data folder, e.g. /usr/share/stirrup)\n");
}

TEST_F(Installed, RendersAShippedSceneByItsRelativeName) {
  const CommandResult r = run("render scenes/trot.json --frames 1-2 --preset draft --resolution 96x54 --out out/render");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(work_ / "out/render/trot_side.0001.png"));
  EXPECT_TRUE(fs::is_regular_file(work_ / "out/render/trot_side.0002.png"));
}

TEST_F(Installed, EvaluatesTheRigWithAnInstalledProfile) {
  std::ofstream(work_ / "horse.csv") << "frame,lfHoof.tx,rfHoof.tx,lfHoof.ty,rearPivot.rz\n1,70,-70,0,0\n2,0,0,12,2\n";
  const CommandResult thesis = run("rig eval horse.csv -o rider.csv");
  ASSERT_EQ(thesis.exit_code, 0) << thesis.err;
  const CommandResult english = run("rig eval horse.csv -o rider_english.csv --profile english");
  ASSERT_EQ(english.exit_code, 0) << english.err;
  const std::string a = readText(work_ / "rider.csv"), b = readText(work_ / "rider_english.csv");
  EXPECT_EQ(a.rfind("frame,", 0), 0u);
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), 3);
  EXPECT_NE(a, b) << "the english profile was not read";
}

TEST_F(Installed, MakesAReviewMovie) {
  const CommandResult r = run("movies --only trot_side --frames-limit 4 --preset draft --resolution 160x90 --out movies --date 2026-01-01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(work_ / "movies/index.html"));
  EXPECT_GT(fs::file_size(work_ / "movies/trot_side.mp4"), 1000u);
  EXPECT_TRUE(fs::is_regular_file(work_ / "movies/trot_side_sheet.png"));
}

// An installed tree moved elsewhere still finds OpenImageIO's module, beside its program (no build or
// install path is needed): a frame is rendered there and compared with itself by `diff`, which reads
// image files through the module.
TEST_F(Installed, AMovedInstallFindsItsImageModule) {
  const fs::path moved = root_ / "moved";
  fs::remove_all(moved);
  ASSERT_EQ(runCommand("cp -a " + quote(prefix_.string()) + " " + quote(moved.string())).exit_code, 0);
  const std::string program = "cd " + quote(work_.string()) + " && " + kCleanEnv + quote((moved / "bin/stirrup").string());
  const fs::path out = root_ / "moved_out";
  const CommandResult render = runCommand(program + " render scenes/trot.json --frames 3 --resolution 64x36 --preset draft --out " +
                                          quote(out.string()));
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const std::string frame = quote((out / "trot_side.0003.png").string());
  const CommandResult diff = runCommand(program + " diff " + frame + " " + frame);
  EXPECT_EQ(diff.exit_code, 0) << diff.out << diff.err;
  EXPECT_NE(diff.out.find("PASS"), std::string::npos) << diff.out;
  fs::remove_all(moved);
  fs::remove_all(out);
}

// `cpack -G DEB` (docs/install.md): the package holds the program under /usr and depends on the libraries
// it links (found by dpkg-shlibdeps) and on the programs and fonts it runs with.
TEST(DebianPackage, DependsOnWhatTheProgramLinksAndRuns) {
  if (runCommand("command -v dpkg-shlibdeps >/dev/null && command -v dpkg-deb >/dev/null").exit_code != 0)
    GTEST_SKIP() << "dpkg-dev is not installed (no dpkg-shlibdeps)";
  const fs::path dir = fs::temp_directory_path() / ("stirrup_deb_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const CommandResult pack = runCommand("cd " + quote(dir.string()) + " && " + quote(STIRRUP_CPACK) + " -G DEB --config " +
                                        quote((fs::path(STIRRUP_BINARY_DIR) / "CPackConfig.cmake").string()));
  ASSERT_EQ(pack.exit_code, 0) << pack.out << pack.err;
  fs::path deb;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".deb") deb = e.path();
  ASSERT_FALSE(deb.empty()) << pack.out;
  const CommandResult depends = runCommand("dpkg-deb -f " + quote(deb.string()) + " Depends");
  ASSERT_EQ(depends.exit_code, 0);
  for (const char* d : {"libembree3-3", "libopenimageio2.4", "libtbb12", "libstdc++6", "ffmpeg", "fonts-dejavu-core"})
    EXPECT_NE(depends.out.find(d), std::string::npos) << d << " missing from Depends: " << depends.out;
  const CommandResult contents = runCommand("dpkg-deb -c " + quote(deb.string()));
  for (const char* f : {"./usr/bin/stirrup", "./usr/share/stirrup/scenes/trot.json", "./usr/share/stirrup/scenes/profiles/thesis.json",
                        "./usr/share/stirrup/scenes/characters/rider.glb", "./usr/share/doc/stirrup/install.md",
                        "./usr/share/stirrup/blender/stirrup_blender/__init__.py",
                        "./usr/" STIRRUP_INSTALL_LIBDIR "/stirrup/libstirrup_openimageio.so"})
    EXPECT_NE(contents.out.find(std::string(f) + "\n"), std::string::npos) << f;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stirrup::test
