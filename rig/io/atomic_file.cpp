#include "rig/io/atomic_file.h"

#include <fstream>
#include <system_error>

#include "rig/error.h"

namespace stirrup::rig {
namespace fs = std::filesystem;

fs::path temporaryFor(const fs::path& file, TempName name) {
  fs::path tmp = file;
  tmp += ".tmp";
  if (name == TempName::KeepExtension) tmp += file.extension();
  return tmp;
}

void replaceFileAtomically(const fs::path& file, const std::function<void(const fs::path& tmp)>& write, TempName name) {
  const fs::path tmp = temporaryFor(file, name);
  std::error_code ec;
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw InputError(file.string() + ": cannot write (" + ec.message() + ")");
  }
}

void writeFileAtomically(const fs::path& file, std::string_view bytes, fs::perms add) {
  if (!file.parent_path().empty()) {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);  // a folder that cannot be made fails the write below
  }
  replaceFileAtomically(file, [&](const fs::path& tmp) {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      if (!out.flush()) throw InputError(file.string() + ": cannot write");
    }
    if (add != fs::perms::none) fs::permissions(tmp, add, fs::perm_options::add);
  });
}

void writeFileAtomically(const fs::path& file, const std::vector<unsigned char>& bytes) {
  writeFileAtomically(file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace stirrup::rig
