#include "scene/data_dir.h"

#include <cstdlib>
#include <string>
#include <system_error>

#include "rig/error.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;

bool holdsData(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / "scenes", ec);
}

fs::path canonicalOr(const fs::path& p) {
  std::error_code ec;
  const fs::path c = fs::canonical(p, ec);
  return ec ? p : c;
}

fs::path besideProgram() {
  const fs::path dir = programDir();
  // DATADIR/stirrup relative to BINDIR (render/CMakeLists.txt), normally ../share/stirrup.
  return dir.empty() ? fs::path() : (dir / STIRRUP_DATA_FROM_PROGRAM).lexically_normal();
}

}  // namespace

fs::path programDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

std::optional<fs::path> findDataDir() {
  if (const char* env = std::getenv("STIRRUP_DATA"); env && *env) {
    if (holdsData(env)) return canonicalOr(env);
    return std::nullopt;  // an explicit setting is never second-guessed
  }
  const fs::path beside = besideProgram();
  if (!beside.empty() && holdsData(beside)) return canonicalOr(beside);
  return std::nullopt;
}

fs::path dataDir() {
  if (std::optional<fs::path> d = findDataDir()) return *d;
  if (const char* env = std::getenv("STIRRUP_DATA"); env && *env)
    throw rig::InputError(std::string("STIRRUP_DATA: ") + env + ": no scenes/ folder there (expected stirrup's data folder, e.g. /usr/share/stirrup)");
  const fs::path beside = besideProgram();
  throw rig::InputError("stirrup's data folder not found (looked for scenes/ in " +
                   (beside.empty() ? std::string(STIRRUP_DATA_FROM_PROGRAM " beside the program") : beside.string()) +
                   "; install stirrup with cmake --install or set STIRRUP_DATA)");
}

}  // namespace stirrup::scene
