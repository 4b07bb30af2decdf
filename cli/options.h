// Option parsers shared by subcommands: --resolution (render, movies), --set (rig eval, render) and the
// free "--name value" parameters of clip make and character make.
#pragma once

#include <charconv>
#include <cmath>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/error.h"

namespace stirrup::cli {

// "320x180" -> {320, 180}; anything else is a one-line InputError naming the option.
inline std::pair<int, int> parseResolution(const std::string& text, const std::string& option = "--resolution") {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || w < 16 || h < 16 || w > 8192 || h > 8192 || !in.eof())
    throw rig::InputError(option + ": expected WIDTHxHEIGHT (16-8192 each), got \"" + text + "\"");
  return {w, h};
}

// --set key=value pairs as a JSON object; a value that is not a number stays a string so the
// profile's own check reports it ("expected a number, got ...").
inline nlohmann::json parseSets(const std::vector<std::string>& sets) {
  nlohmann::json j = nlohmann::json::object();
  for (const std::string& s : sets) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw rig::InputError("--set: expected key=value (e.g. eq1.w1_pivot_pitch=0.05), got \"" + s + "\"");
    const std::string key = s.substr(0, eq);
    const std::string text = s.substr(eq + 1);
    double v = 0;
    const char* begin = text.data() + (text.size() > 1 && text[0] == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(begin, text.data() + text.size(), v);
    const bool number = !text.empty() && ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(v);
    if (number) j[key] = v;
    else j[key] = text;
  }
  return j;
}

// "--fence-height 90 --lead=left" -> {{"fence_height", "90"}, {"lead", "left"}}: each name without its
// dashes, with '-' read as '_'. A word that is not "--name", or a name with no value, is a one-line error
// naming `command`.
inline std::vector<std::pair<std::string, std::string>> namedParameters(const std::string& command,
                                                                        const std::vector<std::string>& args) {
  std::vector<std::pair<std::string, std::string>> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0 || a.size() < 3)
      throw rig::InputError(command + ": expected --parameter value, got \"" + a + "\"");
    std::string key = a.substr(2);
    std::string value;
    if (const auto eq = key.find('='); eq != std::string::npos) {
      value = key.substr(eq + 1);
      key = key.substr(0, eq);
    } else {
      if (i + 1 >= args.size()) throw rig::InputError(command + ": --" + key + ": expected a value");
      value = args[++i];
    }
    for (char& c : key)
      if (c == '-') c = '_';
    out.emplace_back(std::move(key), std::move(value));
  }
  return out;
}

}  // namespace stirrup::cli
