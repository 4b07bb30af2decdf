// Errors a user can fix: bad input files, fields, rows or values. The message is one line that names
// the file, the field or row, and what was expected; the command line prints it and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace stirrup {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace stirrup
