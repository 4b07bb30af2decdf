// A numbered image sequence, DIR/NAME.####.ext: the one place that turns a frame number into a file
// name and a folder's files back into frame numbers. `stirrup render`, `layer`, `diff`, the review
// movies, reference footage and the farm's manifest all name frames through it, so the farm's promise
// that its frames are the ones a local render writes holds by construction.
//
// A pattern is a file name holding one run of '#' (one a digit: name.####.png) or one printf-style
// %0Nd / %d (name.%04d.png, as ffmpeg and Nuke write it). The number is zero-padded to the padding and
// never cut: frame 12345 with #### is name.12345.png. A negative frame is written as printf's %0Nd
// writes it, the minus sign taking one of the digits' places (frame -3 with #### is name.-003.png).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace stirrup::scene {

// NAME.0001.png: the padding `stirrup render` (its --padding default), the review movies and the farm write.
inline constexpr int kDefaultFramePadding = 4;
// Nine digits: every frame number an int holds to 999999999, and far past scene::kMaxFrameNumber (six).
inline constexpr int kMaxFramePadding = 9;

// `frame` zero-padded to `padding` characters, the sign counting as one ("%0*d"): 7 -> "0007",
// 12345 -> "12345", -3 -> "-003"; padding 0 pads nothing.
std::string paddedFrameNumber(int frame, int padding = kDefaultFramePadding);

class FrameSequence {
 public:
  // folder/PREFIX<frame number>SUFFIX, the number padded to `padding` (0 to kMaxFramePadding).
  FrameSequence(std::filesystem::path folder, std::string prefix, int padding, std::string suffix);
  // folder/NAME.####.EXT (extension with its dot: ".png", ".sheet.exr").
  static FrameSequence named(const std::filesystem::path& folder, const std::string& name, const std::string& extension,
                             int padding = kDefaultFramePadding);
  // The sequence a pattern names ("out/trot_side.####.png", "plate.%04d.jpg", "f.%d.png"); nullopt when
  // the file name holds neither # nor %d (one image). InputError naming the pattern when it holds
  // two runs of #, or more than kMaxFramePadding of them. Only the file name is read: a folder may
  // contain # or %.
  static std::optional<FrameSequence> parse(const std::filesystem::path& pattern);
  // Whether `pattern` names a sequence rather than one image (parse would give one).
  static bool isPattern(const std::filesystem::path& pattern);

  const std::filesystem::path& folder() const { return folder_; }
  int padding() const { return padding_; }
  // The pattern with the number as #s (or %d when not padded), for messages: "out/trot_side.####.png".
  std::string pattern() const;
  // The file name of `frame`, without the folder.
  std::string fileName(int frame) const;
  // folder / fileName(frame).
  std::filesystem::path path(int frame) const;
  // The frames in the folder, by number (ascending): every regular file whose name is exactly
  // fileName(n) for some n with at most kMaxFramePadding digits. Look-alikes are left out: other
  // padding (name.00012.png for ####), signs other than a leading '-', other text or extensions.
  // InputError naming the pattern when the folder is missing or cannot be listed.
  std::map<int, std::filesystem::path> scan() const;

 private:
  std::filesystem::path folder_;
  std::string prefix_, suffix_;
  int padding_ = kDefaultFramePadding;
};

}  // namespace stirrup::scene
