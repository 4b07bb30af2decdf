// Frame lists as render farms and ffmpeg users write them: "1-120", "1-120x2", "1-10,20-30", "7".
// Frames keep the order given, and a frame listed twice is rendered once.
//
// Limits (docs/install.md, "Input limits"): frame numbers are whole numbers from -kMaxFrameNumber to
// kMaxFrameNumber, and a list expands to at most kMaxFrameCount frames. Past either the list is a
// one-line InputError, checked before any frame is stored, so a typo such as 1-100000000 never
// allocates a hundred million frames.
#pragma once

#include <string>
#include <vector>

namespace stirrup::scene {

// 999999: six digits, the widest frame number a render farm's ###### padding writes.
inline constexpr int kMaxFrameNumber = 999999;
// 100000 frames: 69 minutes at 24 fps, far past any shot (the longest shipped scene has 96 frames);
// a baked glTF of that many frames is already ~100 MB.
inline constexpr int kMaxFrameCount = 100000;

// Parses a frame list; throws rig::InputError naming `context` (for example "--frames") and the
// part of the list that is wrong.
std::vector<int> parseFrameList(const std::string& spec, const std::string& context);

// The canonical text of a contiguous range, "first-last".
std::string formatFrameRange(int first, int last);

// The shortest text parseFrameList reads back as exactly `frames`, in the same order: runs of a constant
// positive step become FIRST-LAST or FIRST-LASTxSTEP, the rest single frames ("1-9x2,12,20-24"). How a
// render farm writes a chunk of a shot into a job script. Frames must not repeat.
std::string formatFrameList(const std::vector<int>& frames);

}  // namespace stirrup::scene
