// Runs the stirrup program (or any shell command) for end-to-end tests: exit code, stdout, stderr.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace stirrup::test {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `command` through /bin/sh with stderr captured to a temporary file.
inline CommandResult runCommand(const std::string& command) {
  static int counter = 0;
  const std::filesystem::path err_file = std::filesystem::temp_directory_path() /
                                         ("stirrup_test_err_" + std::to_string(::getpid()) + "_" +
                                          std::to_string(counter++));
  CommandResult r;
  FILE* p = popen((command + " 2>" + quote(err_file.string())).c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = readText(err_file);
  std::filesystem::remove(err_file);
  return r;
}

// Runs the stirrup program with arguments (already quoted where needed).
inline CommandResult runStirrup(const std::string& args) {
  return runCommand(quote(STIRRUP_EXE) + " " + args);
}

inline std::size_t lineCount(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += (c == '\n');
  return n;
}

}  // namespace stirrup::test
