#include "scene/frame_sequence.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <system_error>

#include "rig/error.h"

namespace stirrup::scene {

namespace fs = std::filesystem;

namespace {

bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

void checkPadding(int padding, const std::string& context) {
  if (padding < 0 || padding > kMaxFramePadding)
    throw rig::InputError(context + ": expected a frame number padding from 0 to " + std::to_string(kMaxFramePadding) +
                     " digits, got " + std::to_string(padding));
}

}  // namespace

std::string paddedFrameNumber(int frame, int padding) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%0*d", std::clamp(padding, 0, kMaxFramePadding), frame);
  return digits;
}

FrameSequence::FrameSequence(fs::path folder, std::string prefix, int padding, std::string suffix)
    : folder_(std::move(folder)), prefix_(std::move(prefix)), suffix_(std::move(suffix)), padding_(padding) {
  checkPadding(padding_, (folder_ / (prefix_ + "#" + suffix_)).string());
}

FrameSequence FrameSequence::named(const fs::path& folder, const std::string& name, const std::string& extension,
                                   int padding) {
  return FrameSequence(folder, name + ".", padding, extension);
}

std::optional<FrameSequence> FrameSequence::parse(const fs::path& pattern) {
  const std::string name = pattern.filename().string();
  const std::string context = pattern.string();
  const size_t hash = name.find('#');
  if (hash != std::string::npos) {
    size_t end = hash;
    while (end < name.size() && name[end] == '#') ++end;
    if (name.find('#', end) != std::string::npos)
      throw rig::InputError(context + ": expected one run of # for the frame number, got two");
    const int padding = int(std::min<size_t>(end - hash, 99));
    if (padding > kMaxFramePadding)
      throw rig::InputError(context + ": expected at most " + std::to_string(kMaxFramePadding) +
                       " # for the frame number, got " + std::to_string(end - hash));
    return FrameSequence(pattern.parent_path(), name.substr(0, hash), padding, name.substr(end));
  }
  // printf style: %d or %0Nd (a width without the 0 is read as zero padding too, as it always was).
  for (size_t pct = name.find('%'); pct != std::string::npos; pct = name.find('%', pct + 1)) {
    size_t i = pct + 1;
    while (i < name.size() && isDigit(name[i])) ++i;
    if (i >= name.size() || name[i] != 'd') continue;
    if (i - pct - 1 > 2)
      throw rig::InputError(context + ": expected %d or %0Nd with N at most " + std::to_string(kMaxFramePadding) +
                       " for the frame number, got " + name.substr(pct, i + 1 - pct));
    const int padding = i == pct + 1 ? 0 : std::stoi(name.substr(pct + 1, i - pct - 1));
    if (padding > kMaxFramePadding)
      throw rig::InputError(context + ": expected %d or %0Nd with N at most " + std::to_string(kMaxFramePadding) +
                       " for the frame number, got " + name.substr(pct, i + 1 - pct));
    return FrameSequence(pattern.parent_path(), name.substr(0, pct), padding, name.substr(i + 1));
  }
  return std::nullopt;
}

bool FrameSequence::isPattern(const fs::path& pattern) {
  try {
    return parse(pattern).has_value();
  } catch (const rig::InputError&) {
    return true;  // a sequence pattern, if a wrong one: parse names the mistake
  }
}

std::string FrameSequence::pattern() const {
  const std::string number = padding_ > 0 ? std::string(size_t(padding_), '#') : "%d";
  return (folder_ / (prefix_ + number + suffix_)).string();
}

std::string FrameSequence::fileName(int frame) const { return prefix_ + paddedFrameNumber(frame, padding_) + suffix_; }

fs::path FrameSequence::path(int frame) const { return folder_ / fileName(frame); }

std::map<int, fs::path> FrameSequence::scan() const {
  const fs::path dir = folder_.empty() ? fs::path(".") : folder_;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw rig::InputError(pattern() + ": no such folder " + dir.string());
  std::map<int, fs::path> frames;
  fs::directory_iterator it(dir, ec);
  for (; !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix_.size() + suffix_.size() || name.compare(0, prefix_.size(), prefix_) != 0 ||
        name.compare(name.size() - suffix_.size(), suffix_.size(), suffix_) != 0)
      continue;
    const std::string number = name.substr(prefix_.size(), name.size() - prefix_.size() - suffix_.size());
    const size_t sign = number[0] == '-' ? 1 : 0;
    if (number.size() == sign || number.size() - sign > size_t(kMaxFramePadding) ||
        !std::all_of(number.begin() + long(sign), number.end(), isDigit))
      continue;
    const int frame = std::stoi(number);
    if (fileName(frame) != name) continue;  // other padding: name.00012.png is not frame 12 of ####
    std::error_code file_ec;
    if (!it->is_regular_file(file_ec)) continue;
    frames[frame] = it->path();
  }
  if (ec) throw rig::InputError(pattern() + ": cannot list the folder " + dir.string() + " (" + ec.message() + ")");
  return frames;
}

}  // namespace stirrup::scene
