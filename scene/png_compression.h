// PNG's zlib levels for review frames (0: stored, no compression, to 9: smallest). Every level holds
// the same pixels (PNG is lossless); they trade the write's time for the file's size. Level 1 is the
// review frames' default (a 640x360 frame in about 6 ms, against 40 at zlib's default 6); level 0 is
// draft's: the frame's bytes are stored as they are (about 0.7 MB at 640x360, three to four times
// level 1's file), and the write is little more than the sRGB encode, the checksums and the copy to
// disk (docs/performance.md, "Frames overlapped"). Here, below the tracer, because a scene's preset
// picks its level (scene/preset.h) and the tracer's writePng takes it.
#pragma once

namespace stirrup::scene {

inline constexpr int kPngCompressionMin = 0, kPngCompressionMax = 9;
inline constexpr int kReviewPngCompression = 1;
inline constexpr int kDraftPngCompression = 0;

}  // namespace stirrup::scene
