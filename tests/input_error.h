// What a reader of user input says when it refuses: the tests compare the whole one-line message.
#pragma once

#include <string>

#include "rig/error.h"

namespace stirrup::test {

// The InputError message that f throws, or `none` when it throws none. Each test file's own errorOf(INPUT)
// is this over the reader it tests.
template <typename F>
std::string errorOf(F&& f, const char* none = "(no error)") {
  try {
    f();
  } catch (const rig::InputError& e) {
    return e.what();
  }
  return none;
}

}  // namespace stirrup::test
