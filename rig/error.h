// Errors a user can fix: bad input files, fields, rows or values. The message is one line that names
// the file, the field or row, and what was expected; the command line prints it and exits non-zero.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace stirrup::rig {

// The message with its control characters written as escapes (a newline as \n, others as \xNN), so a
// message quoting the user's own text (a key, a field, a frame list holding a newline) stays one line
// and cannot drive the terminal. Idempotent: backslashes are left as they are.
inline std::string oneLineMessage(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) {
      out.push_back(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", u);
      out += buf;
    }
  }
  return out;
}

// A number as an error message quotes it: shortest of %g's forms, six significant digits ("0.5",
// "1e+300", "nan").
inline std::string numberText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A number in a report's own printf format ("%.1f"): one number a call, up to 63 characters.
inline std::string printfNumber(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// `v` with `digits` decimals (printf's %.*f).
inline std::string fixedNumber(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

struct InputError : std::runtime_error {
  explicit InputError(const std::string& message) : std::runtime_error(oneLineMessage(message)) {}
};

}  // namespace stirrup::rig
