// An output folder a command creates for its files, taken back if the command fails before it wrote
// anything there: a failed render (a mapping that names no joint, a frame that cannot be posed) leaves
// no empty folder behind that looks like a shot in progress. Folders that existed before are never
// touched; a folder holding any file is kept.
//
//   OutputFolder out(dir);   // creates dir and any missing parents
//   ... write files ...      // on an exception, the destructor removes what it created, if still empty
#pragma once

#include <exception>
#include <filesystem>
#include <system_error>
#include <vector>

namespace stirrup::cli {

class OutputFolder {
 public:
  explicit OutputFolder(const std::filesystem::path& dir) : exceptions_(std::uncaught_exceptions()) {
    namespace fs = std::filesystem;
    // The folders this creates, deepest first: dir and each missing parent.
    for (fs::path p = dir; !p.empty() && !fs::exists(p); p = p.parent_path()) {
      created_.push_back(p);
      if (p == p.parent_path()) break;
    }
    fs::create_directories(dir);
  }
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  ~OutputFolder() {
    if (std::uncaught_exceptions() <= exceptions_) return;  // finished, or nothing failed
    std::error_code ec;
    for (const std::filesystem::path& p : created_) {
      if (!std::filesystem::is_empty(p, ec) || ec) return;
      std::filesystem::remove(p, ec);
    }
  }

 private:
  int exceptions_;
  std::vector<std::filesystem::path> created_;
};

}  // namespace stirrup::cli
