#include "scene/profile_resolver.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "scene/scene.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;

// A data folder, a $STIRRUP_PROFILES folder and a scene's folder, each holding profiles whose "doc"
// says where they are; STIRRUP_DATA and STIRRUP_PROFILES point at the first two for one test.
class ProfileResolver : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : {"STIRRUP_DATA", "STIRRUP_PROFILES"})
      if (const char* v = std::getenv(name)) saved_[name] = v;
    dir_ = fs::temp_directory_path() / ("stirrup_profile_resolver_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    data_ = dir_ / "data" / "scenes" / "profiles";
    env_ = dir_ / "mine";
    shot_ = dir_ / "shot";
    for (const fs::path& d : {data_, env_, shot_ / "profiles"}) fs::create_directories(d);
    profile(data_ / "thesis.json", "data thesis");
    profile(data_ / "english.json", "data english");
    profile(env_ / "english.json", "env english");
    profile(env_ / "steady.json", "env steady", R"(, "eq7.w2_scale": 0)");
    profile(shot_ / "profiles" / "english.json", "scene english");
    ::setenv("STIRRUP_DATA", (dir_ / "data").c_str(), 1);
    ::setenv("STIRRUP_PROFILES", env_.c_str(), 1);
    scene_.file = shot_ / "ride.json";
  }
  void TearDown() override {
    for (const char* name : {"STIRRUP_DATA", "STIRRUP_PROFILES"}) {
      if (saved_.count(name)) ::setenv(name, saved_[name].c_str(), 1);
      else ::unsetenv(name);
    }
    fs::remove_all(dir_);
  }
  static void profile(const fs::path& file, const std::string& doc, const std::string& more = "") {
    std::ofstream(file) << R"({"doc": ")" << doc << '"' << more << "}";
  }
  std::string sceneDoc(const std::string& value) {
    scene_.profile = value;
    return resolveProfile(scene_).doc;
  }
  std::map<std::string, std::string> saved_;
  fs::path dir_, data_, env_, shot_;
  SceneSpec scene_;
};

TEST_F(ProfileResolver, TheFoldersInOrder) {
  const ProfileSearch scene = profileSearch(shot_ / "ride.json");
  EXPECT_EQ(scene.base, shot_);
  EXPECT_EQ(scene.folders, (std::vector<fs::path>{shot_ / "profiles", env_, fs::canonical(data_)}));
  const ProfileSearch command_line = profileSearch();
  EXPECT_EQ(command_line.base, fs::path());
  EXPECT_EQ(command_line.folders, (std::vector<fs::path>{env_, fs::canonical(data_)}));
  ::unsetenv("STIRRUP_PROFILES");
  EXPECT_EQ(profileSearch().folders, (std::vector<fs::path>{fs::canonical(data_)}));
}

// A scene's name: its own folder, then $STIRRUP_PROFILES, then the data folder; first found wins.
TEST_F(ProfileResolver, AScenesNameIsFoundBesideItFirst) {
  EXPECT_EQ(sceneDoc("english"), "scene english");
  fs::remove(shot_ / "profiles" / "english.json");
  EXPECT_EQ(sceneDoc("english"), "env english");  // before this rule a scene never read $STIRRUP_PROFILES
  EXPECT_EQ(sceneDoc("thesis"), "data thesis");
  EXPECT_EQ(resolveProfile(scene_).name, "thesis");
}

// --profile NAME: $STIRRUP_PROFILES, then the data folder. Before this rule `rig eval` read only
// $STIRRUP_PROFILES when it was set, so a name it lacked was an error even where the data folder had it.
TEST_F(ProfileResolver, ACommandLineNameIsFoundInTheEnvironmentThenTheDataFolder) {
  EXPECT_EQ(resolveProfile("english").doc, "env english");
  EXPECT_EQ(resolveProfile("thesis").doc, "data thesis");
  EXPECT_EQ(resolveProfile("steady").rider_unit_cm, resolveProfile("thesis").rider_unit_cm);
  EXPECT_EQ(resolveProfile("steady").eq7.w2_scale, 0.0);
  ::unsetenv("STIRRUP_PROFILES");
  EXPECT_EQ(resolveProfile("english").doc, "data english");
}

TEST_F(ProfileResolver, RigidIsBuiltInUnlessAFolderHasOne) {
  EXPECT_TRUE(resolveProfile("rigid").rigid);
  scene_.profile = "rigid";
  EXPECT_TRUE(resolveProfile(scene_).rigid);
  profile(env_ / "rigid.json", "env rigid");
  EXPECT_EQ(resolveProfile("rigid").doc, "env rigid");
  EXPECT_FALSE(resolveProfile("rigid").rigid);
}

// A value ending in .json or holding a '/' is a file: a scene's relative to the scene, the command
// line's relative to the working folder.
TEST_F(ProfileResolver, PathsAreRelativeToTheSceneOrTheWorkingFolder) {
  EXPECT_TRUE(isProfilePath("english.json"));
  EXPECT_TRUE(isProfilePath("tuned/english"));
  EXPECT_FALSE(isProfilePath("english"));
  fs::create_directories(shot_ / "tuned");
  profile(shot_ / "tuned" / "loose.json", "scene file");
  profile(shot_ / "tuned" / "noext", "scene file without .json");
  EXPECT_EQ(sceneDoc("tuned/loose.json"), "scene file");
  EXPECT_EQ(sceneDoc("tuned/noext"), "scene file without .json");  // relative to the scene, not the working folder
  EXPECT_EQ(sceneDoc((shot_ / "tuned" / "loose.json").string()), "scene file");  // absolute
  const fs::path before = fs::current_path();
  fs::current_path(shot_);
  const std::string doc = resolveProfile("tuned/loose.json").doc;
  fs::current_path(before);
  EXPECT_EQ(doc, "scene file");
}

TEST_F(ProfileResolver, OverridesApplyAfterTheFileSceneThenCommandLine) {
  scene_.profile = "thesis";
  scene_.profile_overrides = {{"eq7.w2_scale", 0.012}, {"eq7.lift_limit", 9}};
  const rig::RigProfile scene_only = resolveProfile(scene_);
  EXPECT_EQ(scene_only.eq7.w2_scale, 0.012);
  EXPECT_EQ(scene_only.eq7.lift_limit, 9);
  const rig::RigProfile both = resolveProfile(scene_, {{"eq7.w2_scale", 0.015}});
  EXPECT_EQ(both.eq7.w2_scale, 0.015);  // --set last
  EXPECT_EQ(both.eq7.lift_limit, 9);
  EXPECT_EQ(resolveProfile("steady", {{"eq7.w2_scale", 0.02}}).eq7.w2_scale, 0.02);
  try {
    resolveProfile("thesis", {{"eq1.w9", 1}});
    FAIL() << "expected an InputError";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--set: eq1.w9: unknown rig profile parameter (see docs/rider-rig.md for the parameter keys)");
  }
}

TEST_F(ProfileResolver, AMissingNameIsOneLineNamingTheFoldersAndTheNames) {
  const std::string folders = (shot_ / "profiles").string() + ", " + env_.string() + ", " + fs::canonical(data_).string();
  try {
    sceneDoc("cowboy");
    FAIL() << "expected an InputError";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), (shot_ / "ride.json").string() + ": profile: no rig profile \"cowboy\" in " + folders +
                                         " (expected one of english, rigid, steady, thesis, or a path to a .json file)");
  }
  try {
    resolveProfile("");
    FAIL() << "expected an InputError";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--profile: expected a rig profile name or a .json path, got \"\"");
  }
  // A file that is not there is the file's own error.
  scene_.profile = "gone.json";
  EXPECT_THROW(resolveProfile(scene_), rig::InputError);
}

}  // namespace
}  // namespace stirrup::scene
