// `--resolution WIDTHxHEIGHT`, shared by the commands that render (render, movies).
#pragma once

#include <sstream>
#include <string>
#include <utility>

#include "rig/error.h"

namespace stirrup::cli {

// "320x180" -> {320, 180}; anything else is a one-line InputError naming the option.
inline std::pair<int, int> parseResolution(const std::string& text, const std::string& option = "--resolution") {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || w < 16 || h < 16 || w > 8192 || h > 8192 || !in.eof())
    throw InputError(option + ": expected WIDTHxHEIGHT (16-8192 each), got \"" + text + "\"");
  return {w, h};
}

}  // namespace stirrup::cli
