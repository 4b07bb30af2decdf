// What a reader of user input says when it refuses: the tests compare the whole one-line message.
#pragma once

#include <string>

#include "rig/error.h"

namespace stirrup::test {

// The InputError message that f throws, or "(no error)" when it throws none.
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace stirrup::test
