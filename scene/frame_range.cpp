#include "scene/frame_range.h"

#include <charconv>
#include <set>
#include <string_view>

#include "rig/error.h"

namespace stirrup::scene {
namespace {

bool parseInt(std::string_view s, int& out) {
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && ptr == end;
}

[[noreturn]] void fail(const std::string& context, std::string_view part, const std::string& why) {
  throw rig::InputError(context + ": \"" + std::string(part) + "\": " + why);
}

}  // namespace

std::vector<int> parseFrameList(const std::string& spec, const std::string& context) {
  if (spec.empty()) fail(context, spec, "expected a frame list like 1-120x2 or 1-10,20-30");
  std::vector<int> frames;
  std::set<int> seen;
  std::string_view rest(spec);
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view part = rest.substr(0, comma);
    int first = 0, last = 0, step = 1;
    std::string_view range = part;
    if (const std::size_t x = part.find('x'); x != std::string_view::npos) {
      if (!parseInt(part.substr(x + 1), step) || step <= 0)
        fail(context, part, "expected a positive step after 'x'");
      range = part.substr(0, x);
    }
    // A leading '-' is a negative frame number, so look for the separator after the first character.
    const std::size_t dash = range.size() > 1 ? range.find('-', 1) : std::string_view::npos;
    if (dash == std::string_view::npos) {
      if (!parseInt(range, first)) fail(context, part, "expected a frame number or a range FIRST-LAST");
      last = first;
    } else if (!parseInt(range.substr(0, dash), first) || !parseInt(range.substr(dash + 1), last)) {
      fail(context, part, "expected a range FIRST-LAST[xSTEP] of whole numbers");
    }
    for (const int f : {first, last})
      if (f < -kMaxFrameNumber || f > kMaxFrameNumber)
        fail(context, part, "expected frame numbers from " + std::to_string(-kMaxFrameNumber) + " to " +
                                std::to_string(kMaxFrameNumber) + ", got " + std::to_string(f));
    if (last < first) fail(context, part, "expected FIRST <= LAST");
    const std::string too_many = "expected at most " + std::to_string(kMaxFrameCount) + " frames in the list";
    if ((static_cast<long>(last) - first) / step + 1 > kMaxFrameCount) fail(context, part, too_many);
    for (long f = first; f <= last; f += step) {
      if (!seen.insert(static_cast<int>(f)).second) continue;
      if (frames.size() == static_cast<std::size_t>(kMaxFrameCount))
        fail(context, part, too_many);
      frames.push_back(static_cast<int>(f));
    }
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return frames;
}

std::string formatFrameRange(int first, int last) {
  return std::to_string(first) + "-" + std::to_string(last);
}

std::string formatFrameList(const std::vector<int>& frames) {
  std::string out;
  std::size_t i = 0;
  while (i < frames.size()) {
    if (!out.empty()) out += ',';
    // The longest run from i with one positive step; two frames a step apart only make a run at step 1
    // ("4-5" is no shorter than "4,5", but "4,6" is shorter than "4-6x2").
    std::size_t j = i;
    const long step = i + 1 < frames.size() ? static_cast<long>(frames[i + 1]) - frames[i] : 0;
    if (step > 0)
      while (j + 1 < frames.size() && static_cast<long>(frames[j + 1]) - frames[j] == step) ++j;
    if (j == i || (j == i + 1 && step != 1)) {
      out += std::to_string(frames[i]);
      ++i;
      continue;
    }
    out += formatFrameRange(frames[i], frames[j]);
    if (step != 1) out += "x" + std::to_string(step);
    i = j + 1;
  }
  return out;
}

}  // namespace stirrup::scene
