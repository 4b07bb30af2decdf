// Files a Blender script makes for tests (Blender's Rigify horses and riders), made once and shared by
// every test process of a run. CTest runs each test in a process of its own, so a fixture held in a
// static would launch Blender once per test; here the files are kept under the build folder with a stamp
// naming the command and the script's contents, and remade only when either changes. A lock serialises
// test processes running in parallel, so one makes the files and the others wait for them.
#pragma once

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace stirrup::test {

inline bool blenderInstalled() { return std::system("command -v blender >/dev/null 2>&1") == 0; }

struct BlenderMade {
  bool ok = false;
  std::string log;  // the script's output when it failed
};

// Runs `command` (a script under scripts/, named by `script`, writing into `dir`) unless `dir` already
// holds what the same command and script made. The command's output goes to dir/make.log.
inline BlenderMade madeByBlender(const std::filesystem::path& dir, const std::filesystem::path& script, const std::string& command) {
  namespace fs = std::filesystem;
  const auto slurp = [](const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::string stamp = command + "\n" + std::to_string(std::hash<std::string>{}(slurp(script))) + "\n";
  fs::create_directories(dir.parent_path());
  const fs::path lock_file = dir.parent_path() / (dir.filename().string() + ".lock");
  const int lock = ::open(lock_file.c_str(), O_CREAT | O_RDWR, 0644);
  if (lock >= 0) ::flock(lock, LOCK_EX);
  BlenderMade made;
  if (fs::exists(dir / "stamp") && slurp(dir / "stamp") == stamp) {
    made.ok = true;
  } else {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path log = dir / "make.log";
    made.ok = std::system((command + " >'" + log.string() + "' 2>&1").c_str()) == 0;
    if (made.ok) std::ofstream(dir / "stamp", std::ios::binary) << stamp;
    else made.log = slurp(log);
  }
  if (lock >= 0) {
    ::flock(lock, LOCK_UN);
    ::close(lock);
  }
  return made;
}

// Blender's own Rigify human (tests/blender/rigify-rider), made once for every test that rides her:
// the glTF file's path, or empty with `made.ok` false and the script's output in `made.log`. The same run
// saves her as a .blend beside it (blenderRigifyRiderBlend): the generated rig with its controls, as an
// animator has her in Blender.
inline std::filesystem::path blenderRigifyRider(BlenderMade* made = nullptr) {
  const std::filesystem::path dir = std::filesystem::path(STIRRUP_BINARY_DIR) / "test_blender_riders" / "rigify";
  const std::filesystem::path script = STIRRUP_SOURCE_DIR "/tests/blender/rigify-rider";
  const BlenderMade m = madeByBlender(dir, script, std::string("'") + script.string() + "' '" + (dir / "rigify-rider.glb").string() + "' --blend '" +
                                                       (dir / "rigify-rider.blend").string() + "'");
  if (made) *made = m;
  return m.ok ? dir / "rigify-rider.glb" : std::filesystem::path();
}

inline std::filesystem::path blenderRigifyRiderBlend(BlenderMade* made = nullptr) {
  const std::filesystem::path glb = blenderRigifyRider(made);
  return glb.empty() ? glb : glb.parent_path() / "rigify-rider.blend";
}

// Rigify's generated horse as an animator has it (tests/blender/rigify-horse --form generated, Rigify's
// own IK stretch kept), its 48-frame walk keyed on the leg IK controls (ik.blend) and on the FK controls
// (fk.blend), each with its thin body skinned to its DEF- bones: the folder holding both, made once.
inline std::filesystem::path blenderRigifyHorses(BlenderMade* made = nullptr) {
  const std::filesystem::path dir = std::filesystem::path(STIRRUP_BINARY_DIR) / "test_blender_riders" / "rigify-horses";
  const std::filesystem::path script = STIRRUP_SOURCE_DIR "/tests/blender/rigify-horse";
  const BlenderMade m = madeByBlender(dir, script, std::string("'") + script.string() + "' --batch '" + dir.string() +
                                                       "' 'ik:--form generated --walk --rigify-stretch --blend ik.blend'"
                                                       " 'fk:--form generated --walk --walk-controls fk --rigify-stretch --blend fk.blend'");
  if (made) *made = m;
  return m.ok ? dir : std::filesystem::path();
}

// Blender's Rigify horse with its keyed walk (tests/blender/rigify-horse OPTIONS --walk), made once for
// every test that rides it, in STIRRUP_BINARY_DIR/test_own_horse/NAME: horse.glb and, as the oracle of its
// walk, blender.json (Blender's own world place of every joint at every frame). The folder, or empty
// with `made.ok` false and the script's output in `made.log`.
inline std::filesystem::path blenderRigifyHorse(const std::string& name, const std::string& options, BlenderMade* made = nullptr) {
  const std::filesystem::path dir = std::filesystem::path(STIRRUP_BINARY_DIR) / "test_own_horse" / name;
  const std::filesystem::path script = STIRRUP_SOURCE_DIR "/tests/blender/rigify-horse";
  const BlenderMade m = madeByBlender(dir, script, std::string("'") + script.string() + "' '" + (dir / "horse.glb").string() + "' " + options +
                                                       " --walk --expected '" + (dir / "blender.json").string() + "'");
  if (made) *made = m;
  return m.ok ? dir : std::filesystem::path();
}

}  // namespace stirrup::test
