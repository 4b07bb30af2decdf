#include "rig/io/channel_csv.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "rig/error.h"
#include "rig/io/atomic_file.h"

namespace stirrup::rig {
namespace {

constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

std::string inQuotes(std::string_view s) {
  std::string q(1, '"');
  q.append(s);
  q.push_back('"');
  return q;
}

std::string where(const std::filesystem::path& file, std::size_t row) {
  return file.string() + ": row " + std::to_string(row);
}

// Decimal numbers only: from_chars also reads "nan" and "inf", which are not frame values.
double parseNumber(std::string_view text, const std::filesystem::path& file, std::size_t row,
                   std::string_view column) {
  double v = 0;
  // from_chars reads no leading '+', which spreadsheets sometimes write.
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  const std::string at = where(file, row) + ", column " + std::string(column) + ": ";
  if (text.empty()) throw InputError(at + "expected a number, got an empty field");
  if (ec == std::errc::result_out_of_range || (ec == std::errc() && ptr == end && !std::isfinite(v)))
    throw InputError(at + "expected a finite number, got " + inQuotes(text));
  if (ec != std::errc() || ptr != end) throw InputError(at + "expected a number, got " + inQuotes(text));
  return v;
}

std::string formatNumber(double v) {
  if (v == 0) v = 0;  // "-0" (e.g. -1 x 0) reads as noise in a CSV
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
}

}  // namespace

HorseTrack readHorseCsv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read the file (expected a horse channel CSV)");

  std::string line;
  std::size_t row = 0;
  // The header: the first non-blank line.
  bool have_header = false;
  while (std::getline(in, line)) {
    ++row;
    // A spreadsheet's "CSV UTF-8" starts with a byte-order mark; it is not part of the header.
    if (row == 1 && line.starts_with(kUtf8ByteOrderMark)) line.erase(0, kUtf8ByteOrderMark.size());
    if (!trim(line).empty()) {
      have_header = true;
      break;
    }
  }
  if (!have_header) throw InputError(where(file, 1) + ": expected a header line starting `frame`, got an empty file");

  const std::vector<std::string_view> header_fields = splitFields(line);
  std::vector<std::string> header(header_fields.begin(), header_fields.end());
  const std::size_t header_row = row;
  std::optional<std::size_t> frame_column;
  // Per column: the horse channel it fills, or none for `frame`.
  std::vector<std::optional<HorseChannel>> channel_of(header.size());
  std::vector<bool> seen(kHorseChannelCount, false);
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string& name = header[c];
    const std::string at = where(file, header_row) + ", column " + (name.empty() ? std::to_string(c + 1) : name) + ": ";
    if (name == "frame") {
      if (frame_column) throw InputError(at + "expected each column once, got `frame` twice");
      frame_column = c;
      continue;
    }
    const std::optional<HorseChannel> ch = horseChannelFromName(name);
    if (!ch)
      throw InputError(at + "expected `frame` or a horse channel name (lfHoof.tx ... backMid.rz), got " + inQuotes(name));
    if (seen[static_cast<std::size_t>(*ch)]) throw InputError(at + "expected each column once, got it twice");
    seen[static_cast<std::size_t>(*ch)] = true;
    channel_of[c] = ch;
  }
  if (!frame_column)
    throw InputError(where(file, header_row) + ", column frame: expected a `frame` column in the header, got " +
                     inQuotes(trim(line)));

  HorseTrack track;
  while (std::getline(in, line)) {
    ++row;
    if (trim(line).empty()) continue;
    const std::vector<std::string_view> fields = splitFields(line);
    if (fields.size() != header.size())
      throw InputError(where(file, row) + ", column " + std::to_string(std::min(fields.size(), header.size()) + 1) +
                       ": expected " + std::to_string(header.size()) + " columns as in the header, got " +
                       std::to_string(fields.size()));
    HorseChannels horse;
    double frame = 0;
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const double v = parseNumber(fields[c], file, row, header[c]);
      if (channel_of[c]) horse[*channel_of[c]] = v;
      else frame = v;
    }
    track.frames.push_back(frame);
    track.horse.push_back(horse);
  }
  if (in.bad()) throw InputError(file.string() + ": read failed");
  return track;
}

void writeChannelCsv(const std::filesystem::path& file, std::span<const std::string_view> names,
                     std::span<const double> frames, std::span<const double* const> rows) {
  namespace fs = std::filesystem;
  if (frames.size() != rows.size())
    throw std::invalid_argument("writeChannelCsv: frames and rows differ in length");
  std::error_code ec;
  if (!file.parent_path().empty()) fs::create_directories(file.parent_path(), ec);
  replaceFileAtomically(file, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(file.string() + ": cannot write the file (expected a writable path)");
    out << "frame";
    for (std::string_view n : names) out << ',' << n;
    out << '\n';
    std::string line;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      line = formatNumber(frames[i]);
      for (std::size_t c = 0; c < names.size(); ++c) {
        line += ',';
        line += formatNumber(rows[i][c]);
      }
      line += '\n';
      out << line;
    }
    out.flush();
    if (!out) throw InputError(file.string() + ": write failed (disk full?)");
  });
}

void writeHorseCsv(const std::filesystem::path& file, std::span<const double> frames,
                   std::span<const HorseChannels> horse) {
  std::vector<const double*> rows;
  rows.reserve(horse.size());
  for (const HorseChannels& h : horse) rows.push_back(h.value.data());
  writeChannelCsv(file, kHorseChannelNames, frames, rows);
}

void writeRiderCsv(const std::filesystem::path& file, std::span<const double> frames,
                   std::span<const RiderChannels> rider) {
  std::vector<const double*> rows;
  rows.reserve(rider.size());
  for (const RiderChannels& r : rider) rows.push_back(r.value.data());
  writeChannelCsv(file, kRiderChannelNames, frames, rows);
}

}  // namespace stirrup::rig
