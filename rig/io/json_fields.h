// Reading user JSON with errors a user can act on: every problem is one line naming the file, the
// field path (for example `cameras[1].fov`) and what was expected. Unknown fields are errors too, so a
// typo never silently falls back to a default.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace stirrup::rig {

// The UTF-8 byte-order mark some editors put first in a file ("CSV UTF-8", "UTF-8 with BOM"). JSON and
// channel CSV readers skip it.
inline constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

// Reads and parses a JSON file (a leading UTF-8 byte-order mark is skipped); a missing file or a
// syntax error is an InputError naming the file.
nlohmann::json readJsonFile(const std::filesystem::path& file);

// A short rendering of a JSON value for error messages: "wide", 12, [1,2], {...}.
std::string describeJson(const nlohmann::json& value);

// No limit but finiteness, for numbers() without a range.
inline constexpr double kNoLimit = 1.7976931348623157e308;

// A view of one JSON object at a field path. Reading a field marks it known; finish() rejects the rest.
class JsonObjectReader {
 public:
  JsonObjectReader(std::string file, std::string path, const nlohmann::json& object);

  bool has(const std::string& key) const;
  // A finite number (a field whose sensible range is its reader's to check).
  double number(const std::string& key, double fallback);
  // A number from `lo` to `hi` (the range that makes sense for the field: a value outside it is a typo or
  // a unit slip, and an absurd one, 1e-320 frames a second or 1e308 cm, turns into NaN downstream):
  // "FILE: FIELD: expected WHAT from LO to HI, got V".
  double number(const std::string& key, double fallback, double lo, double hi, const char* what = "a number");
  int integer(const std::string& key, int fallback);
  int integer(const std::string& key, int fallback, int lo, int hi, const char* what = "a whole number");
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key, const std::string& fallback);
  // The raw value (marked known) or nullptr when absent.
  const nlohmann::json* value(const std::string& key);
  // A fixed-size array of numbers, each from `lo` to `hi`.
  template <std::size_t N>
  std::array<double, N> numbers(const std::string& key, std::array<double, N> fallback, double lo, double hi);
  // The same with no range (each one finite): for fields whose reader checks them together.
  template <std::size_t N>
  std::array<double, N> numbers(const std::string& key, std::array<double, N> fallback) {
    return numbers<N>(key, fallback, -kNoLimit, kNoLimit);
  }
  // The message for a number outside [lo, hi].
  static std::string rangeText(double lo, double hi, double got, const char* what = "a number");
  JsonObjectReader object(const std::string& key);

  // The path of a field, for messages: "cameras[1].fov".
  std::string fieldPath(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;
  // Rejects any field that was never read.
  void finish() const;

  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::string path_;
  const nlohmann::json& object_;
  std::set<std::string> known_;
};

template <std::size_t N>
std::array<double, N> JsonObjectReader::numbers(const std::string& key, std::array<double, N> fallback, double lo, double hi) {
  const nlohmann::json* v = value(key);
  if (!v) return fallback;
  if (!v->is_array() || v->size() != N)
    fail(key, "expected an array of " + std::to_string(N) + " numbers, got " + describeJson(*v));
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    if (!(*v)[i].is_number())
      fail(key + "[" + std::to_string(i) + "]", "expected a number, got " + describeJson((*v)[i]));
    out[i] = (*v)[i].get<double>();
    if (!(out[i] >= lo && out[i] <= hi)) fail(key + "[" + std::to_string(i) + "]", rangeText(lo, hi, out[i]));
  }
  return out;
}

}  // namespace stirrup::rig
