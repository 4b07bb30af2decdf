#include "rig/io/json_fields.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include "rig/error.h"

namespace stirrup::rig {

nlohmann::json readJsonFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open the file (expected a readable JSON file)");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(file.string() + ": read failed");
  // Editors and spreadsheets on Windows save "UTF-8" with a byte-order mark; it is not part of the JSON.
  if (text.starts_with(kUtf8ByteOrderMark)) text.erase(0, kUtf8ByteOrderMark.size());
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // A syntax error (nlohmann's message carries the line and column; keep only that part), or a number
    // too large for a double, 1e400 (out_of_range.406, found by fuzzing): drop the "[json.exception...]" tag.
    std::string what = e.what();
    if (const auto pos = what.find("parse error"); pos != std::string::npos) what = what.substr(pos);
    else if (const auto tag = what.find("] "); what.rfind("[json.exception.", 0) == 0 && tag != std::string::npos)
      what = what.substr(tag + 2);
    throw InputError(file.string() + ": not valid JSON: " + what);
  }
}

std::string describeJson(const nlohmann::json& value) {
  if (value.is_object()) return "an object";
  if (value.is_array()) return "an array of " + std::to_string(value.size());
  if (value.is_null()) return "null";
  // Text from the command line (--set) need not be UTF-8: replace bad bytes rather than throw.
  std::string s = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

JsonObjectReader::JsonObjectReader(std::string file, std::string path, const nlohmann::json& object)
    : file_(std::move(file)), path_(std::move(path)), object_(object) {
  if (!object_.is_object()) {
    throw InputError(file_ + ": " + (path_.empty() ? std::string("top level") : path_) +
                     ": expected an object, got " + describeJson(object_));
  }
}

std::string JsonObjectReader::fieldPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonObjectReader::fail(const std::string& key, const std::string& expected) const {
  throw InputError(file_ + ": " + fieldPath(key) + ": " + expected);
}

bool JsonObjectReader::has(const std::string& key) const { return object_.contains(key); }

const nlohmann::json* JsonObjectReader::value(const std::string& key) {
  known_.insert(key);
  auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

double JsonObjectReader::number(const std::string& key, double fallback) {
  const nlohmann::json* v = value(key);
  if (!v) return fallback;
  if (!v->is_number()) fail(key, "expected a number, got " + describeJson(*v));
  const double d = v->get<double>();
  if (!std::isfinite(d)) fail(key, "expected a finite number");
  return d;
}

std::string JsonObjectReader::rangeText(double lo, double hi, double got, const char* what) {
  return std::string("expected ") + what + " from " + numberText(lo) + " to " + numberText(hi) + ", got " + numberText(got);
}

double JsonObjectReader::number(const std::string& key, double fallback, double lo, double hi, const char* what) {
  if (!has(key)) {
    known_.insert(key);
    return fallback;  // a default is the reader's, not the user's: not checked
  }
  const double d = number(key, fallback);
  if (!(d >= lo && d <= hi)) fail(key, rangeText(lo, hi, d, what));
  return d;
}

int JsonObjectReader::integer(const std::string& key, int fallback, int lo, int hi, const char* what) {
  const nlohmann::json* v = value(key);
  if (!v) return fallback;
  if (!v->is_number_integer()) fail(key, std::string("expected ") + what + ", got " + describeJson(*v));
  // Compared before the cast: a whole number past int's range would wrap.
  const double d = v->get<double>();
  if (!(d >= lo && d <= hi)) fail(key, rangeText(lo, hi, d, what));
  return static_cast<int>(d);
}

int JsonObjectReader::integer(const std::string& key, int fallback) {
  const nlohmann::json* v = value(key);
  if (!v) return fallback;
  if (!v->is_number_integer()) fail(key, "expected a whole number, got " + describeJson(*v));
  const double d = v->get<double>();
  if (!(d >= -2147483648.0 && d <= 2147483647.0)) fail(key, "expected a whole number from -2147483648 to 2147483647, got " + describeJson(*v));
  return v->get<int>();
}

bool JsonObjectReader::boolean(const std::string& key, bool fallback) {
  const nlohmann::json* v = value(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(key, "expected true or false, got " + describeJson(*v));
  return v->get<bool>();
}

std::string JsonObjectReader::string(const std::string& key, const std::string& fallback) {
  const nlohmann::json* v = value(key);
  if (!v) return fallback;
  if (!v->is_string()) fail(key, "expected a string, got " + describeJson(*v));
  return v->get<std::string>();
}

JsonObjectReader JsonObjectReader::object(const std::string& key) {
  const nlohmann::json* v = value(key);
  if (!v) fail(key, "missing (expected an object)");
  if (!v->is_object()) fail(key, "expected an object, got " + describeJson(*v));
  return JsonObjectReader(file_, fieldPath(key), *v);
}

void JsonObjectReader::finish() const {
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (!known_.count(it.key())) {
      throw InputError(file_ + ": " + fieldPath(it.key()) + ": unknown field");
    }
  }
}

}  // namespace stirrup::rig
