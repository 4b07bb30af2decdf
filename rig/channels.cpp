#include "rig/channels.h"

namespace stirrup::rig {

std::optional<HorseChannel> horseChannelFromName(std::string_view n) {
  for (std::size_t i = 0; i < kHorseChannelCount; ++i)
    if (kHorseChannelNames[i] == n) return static_cast<HorseChannel>(i);
  return std::nullopt;
}

std::optional<RiderChannel> riderChannelFromName(std::string_view n) {
  for (std::size_t i = 0; i < kRiderChannelCount; ++i)
    if (kRiderChannelNames[i] == n) return static_cast<RiderChannel>(i);
  return std::nullopt;
}

}  // namespace stirrup::rig
