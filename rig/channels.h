// The channel contract (docs/channels.md): the horse controls a clip produces and the
// rider controls the rider rig evaluates. Channels are addressed by enum and named
// `control.channel` exactly as the contract names them, so CSV columns, profiles and code agree.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace stirrup::rig {

// Horse controls: centimetres and degrees, offsets from the rest pose in the horse's travel frame.
enum class HorseChannel : std::size_t {
  lfHoofTx, lfHoofTy, lfHoofTz,
  rfHoofTx, rfHoofTy, rfHoofTz,
  lbHoofTx, lbHoofTy, lbHoofTz,
  rbHoofTx, rbHoofTy, rbHoofTz,
  rearPivotTx, rearPivotTy, rearPivotTz, rearPivotRx, rearPivotRy, rearPivotRz,
  backMidRx, backMidRy, backMidRz,
  Count
};
inline constexpr std::size_t kHorseChannelCount = static_cast<std::size_t>(HorseChannel::Count);

// Rider controls: degrees; translations in rider units (see RigProfile::rider_unit_cm).
enum class RiderChannel : std::size_t {
  lowerBackRz, lowerBackRy, lowerBackRx,
  waistRz,
  hipRz, hipRy,
  cogTy, cogTx,
  spineCTy, spineDTy, spineFTy, neckTy, headATy,
  headRz, headRy,
  lWristTx, rWristTx, lWristTy, rWristTy,
  lFootTx, rFootTx, lFootRz, rFootRz, lFootRy, rFootRy, lFootRx, rFootRx, lFootTz, rFootTz,
  lKneeTz, rKneeTz, lKneeTy, rKneeTy,
  hairUp, hairSide, clothUp, clothSide,
  Count
};
inline constexpr std::size_t kRiderChannelCount = static_cast<std::size_t>(RiderChannel::Count);

// Contract names, in enum order.
inline constexpr std::array<std::string_view, kHorseChannelCount> kHorseChannelNames = {
    "lfHoof.tx", "lfHoof.ty", "lfHoof.tz", "rfHoof.tx", "rfHoof.ty", "rfHoof.tz",
    "lbHoof.tx", "lbHoof.ty", "lbHoof.tz", "rbHoof.tx", "rbHoof.ty", "rbHoof.tz",
    "rearPivot.tx", "rearPivot.ty", "rearPivot.tz", "rearPivot.rx", "rearPivot.ry", "rearPivot.rz",
    "backMid.rx", "backMid.ry", "backMid.rz"};

inline constexpr std::array<std::string_view, kRiderChannelCount> kRiderChannelNames = {
    "lowerBack.rz", "lowerBack.ry", "lowerBack.rx", "waist.rz", "hip.rz", "hip.ry",
    "cog.ty", "cog.tx", "spineC.ty", "spineD.ty", "spineF.ty", "neck.ty", "headA.ty",
    "head.rz", "head.ry", "lWrist.tx", "rWrist.tx", "lWrist.ty", "rWrist.ty",
    "lFoot.tx", "rFoot.tx", "lFoot.rz", "rFoot.rz", "lFoot.ry", "rFoot.ry", "lFoot.rx", "rFoot.rx",
    "lFoot.tz", "rFoot.tz", "lKnee.tz", "rKnee.tz", "lKnee.ty", "rKnee.ty",
    "hair.up", "hair.side", "cloth.up", "cloth.side"};

inline constexpr std::string_view name(HorseChannel c) {
  return kHorseChannelNames[static_cast<std::size_t>(c)];
}
inline constexpr std::string_view name(RiderChannel c) {
  return kRiderChannelNames[static_cast<std::size_t>(c)];
}
std::optional<HorseChannel> horseChannelFromName(std::string_view n);
std::optional<RiderChannel> riderChannelFromName(std::string_view n);

// A value per channel, indexed by the channel enum. Zero is the rest pose.
template <typename Channel, std::size_t N>
struct ChannelValues {
  std::array<double, N> value{};
  constexpr double operator[](Channel c) const { return value[static_cast<std::size_t>(c)]; }
  constexpr double& operator[](Channel c) { return value[static_cast<std::size_t>(c)]; }
};

using HorseChannels = ChannelValues<HorseChannel, kHorseChannelCount>;
using RiderChannels = ChannelValues<RiderChannel, kRiderChannelCount>;

}  // namespace stirrup::rig
