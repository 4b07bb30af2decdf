// Channel CSV files: a header row naming the columns, then one row per frame.
//
// Reading (horse channels): the header holds `frame` and any subset of the horse channel names of
// docs/channels.md (lfHoof.tx ... backMid.rz), in any order; absent channels are 0 (rest).
// Values are plain decimal numbers (cm and degrees). A UTF-8 byte-order mark before the header (a
// spreadsheet's "CSV UTF-8") is skipped. Blank lines are skipped; spaces around a field
// are ignored. Every problem is one InputError line "FILE: row N, column NAME: expected ..., got ...",
// where row N is the line number in the file (the header is row 1).
//
// Writing: `frame` then the given channels, shortest round-trip numbers. The file is written to
// FILE.tmp and renamed over FILE, so a failed write never leaves a partial FILE behind.
#pragma once

#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "rig/channels.h"

namespace stirrup::rig {

struct HorseTrack {
  std::vector<double> frames;
  std::vector<HorseChannels> horse;  // one per frame, same order
};

HorseTrack readHorseCsv(const std::filesystem::path& file);

// Writes `frame` + the named columns; rows[i] holds the values of frames[i] in `names` order.
void writeChannelCsv(const std::filesystem::path& file, std::span<const std::string_view> names,
                     std::span<const double> frames, std::span<const double* const> rows);

void writeHorseCsv(const std::filesystem::path& file, std::span<const double> frames,
                   std::span<const HorseChannels> horse);
void writeRiderCsv(const std::filesystem::path& file, std::span<const double> frames,
                   std::span<const RiderChannels> rider);

}  // namespace stirrup::rig
