// Where stirrup finds the data it ships (docs/install.md): the default scenes, the rig profiles
// (scenes/profiles) and the characters (scenes/characters). In order:
//   1. $STIRRUP_DATA, when set (a folder holding scenes/);
//   2. ../share/stirrup beside the running program (/proc/self/exe): P/share/stirrup for P/bin/stirrup
//      after `cmake --install build --prefix P` or the Debian package; in the build tree
//      BUILD/share/stirrup, a link to the source tree made at configure time.
// The program has no source path compiled in, so an installed stirrup runs from any folder.
#pragma once

#include <filesystem>
#include <optional>

namespace stirrup::scene {

// The data folder (canonical), or nullopt when neither place holds a scenes/ folder.
std::optional<std::filesystem::path> findDataDir();
// The data folder; throws rig::InputError naming the places looked in when there is none.
std::filesystem::path dataDir();
// The folder of the running program (/proc/self/exe's folder); empty if the system does not say.
std::filesystem::path programDir();

}  // namespace stirrup::scene
