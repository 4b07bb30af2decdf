// A file written whole or not at all: its content goes to a temporary name beside it, which then
// replaces it in one rename, so a reader (a farm's monitor, a DCC watching a folder, a resumed render)
// never sees half a file. Every writer of a finished file uses this (frames, movies, plots, bakes, CSV,
// reports, manifests).
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

namespace stirrup::rig {

// The temporary's name: FILE.tmp, or FILE.tmp.EXT for writers that choose a format by the extension
// (OpenImageIO, ffmpeg). A frame being written is NAME.####.png.tmp, which the farm recognises.
enum class TempName { Plain, KeepExtension };
std::filesystem::path temporaryFor(const std::filesystem::path& file, TempName name = TempName::Plain);

// `write` fills the temporary (its path given); then it replaces `file`. When `write` throws, or the
// rename fails, the temporary is removed and `file` is left as it was; a failed rename is an InputError
// "FILE: cannot write (REASON)". The folder must exist.
void replaceFileAtomically(const std::filesystem::path& file, const std::function<void(const std::filesystem::path& tmp)>& write,
                           TempName name = TempName::Plain);

// `bytes` as the whole of `file`, its folder made first; "FILE: cannot write" when they cannot all be
// written. `add` permissions are added to the file (a script's execute bits).
void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes,
                         std::filesystem::perms add = std::filesystem::perms::none);
void writeFileAtomically(const std::filesystem::path& file, const std::vector<unsigned char>& bytes);

}  // namespace stirrup::rig
