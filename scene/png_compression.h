// PNG's compression levels for review frames (0: stored, no compression, to 9: smallest), on zlib's
// scale; libdeflate deflates the frames (render/tracer/png_encoder.h). Every level holds the same
// pixels (PNG is lossless); they trade the write's time for the file's size. Level 1 is the review
// frames' default (a 640x360 frame's whole write in about 4 ms of CPU); level 0 is draft's: the
// frame's bytes are stored as they are (about 0.7 MB at 640x360, four times level 1's file), and the
// write is little more than the sRGB encode, the checksums and the copy to disk (about 2 ms;
// docs/performance-history.md, "The frames' write"). Here, below the tracer, because a scene's preset picks
// its level (scene/preset.h) and the tracer's writePng takes it.
#pragma once

namespace stirrup::scene {

inline constexpr int kPngCompressionMin = 0, kPngCompressionMax = 9;
inline constexpr int kReviewPngCompression = 1;
inline constexpr int kDraftPngCompression = 0;

}  // namespace stirrup::scene
