// Frame lists as render farms and ffmpeg users write them: "1-120", "1-120x2", "1-10,20-30", "7".
// Frames keep the order given, and a frame listed twice is rendered once.
#pragma once

#include <string>
#include <vector>

namespace stirrup::rig {

// Parses a frame list; throws stirrup::InputError naming `context` (for example "--frames") and the
// part of the list that is wrong.
std::vector<int> parseFrameList(const std::string& spec, const std::string& context);

// The canonical text of a contiguous range, "first-last".
std::string formatFrameRange(int first, int last);

}  // namespace stirrup::rig
