// Channel names (rig/channels.cpp): the contract's `control.channel` names looked up to the enums, and
// nothing else accepted.
#include "rig/channels.h"

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// docs/channels.md: 4 hooves x 3 translations, rearPivot's 3 translations and 3 rotations, backMid's
// 3 rotations; the rider's 37 controls.
TEST(Channels, TheContractsCounts) {
  EXPECT_EQ(kHorseChannelCount, 21u);
  EXPECT_EQ(kRiderChannelCount, 37u);
}

TEST(Channels, NamesLookUpTheirChannel) {
  EXPECT_EQ(horseChannelFromName("lfHoof.tx"), HorseChannel::lfHoofTx);
  EXPECT_EQ(horseChannelFromName("rbHoof.tz"), HorseChannel::rbHoofTz);
  EXPECT_EQ(horseChannelFromName("rearPivot.rz"), HorseChannel::rearPivotRz);
  EXPECT_EQ(horseChannelFromName("backMid.rz"), HorseChannel::backMidRz);
  EXPECT_EQ(riderChannelFromName("lowerBack.rz"), RiderChannel::lowerBackRz);
  EXPECT_EQ(riderChannelFromName("cog.ty"), RiderChannel::cogTy);
  EXPECT_EQ(riderChannelFromName("cloth.side"), RiderChannel::clothSide);
  // Every name finds its own place in the table, and name() gives it back.
  for (std::size_t i = 0; i < kHorseChannelCount; ++i) {
    const auto c = horseChannelFromName(kHorseChannelNames[i]);
    ASSERT_TRUE(c) << kHorseChannelNames[i];
    EXPECT_EQ(static_cast<std::size_t>(*c), i);
    EXPECT_EQ(name(*c), kHorseChannelNames[i]);
  }
  for (std::size_t i = 0; i < kRiderChannelCount; ++i) {
    const auto c = riderChannelFromName(kRiderChannelNames[i]);
    ASSERT_TRUE(c) << kRiderChannelNames[i];
    EXPECT_EQ(static_cast<std::size_t>(*c), i);
  }
}

TEST(Channels, OtherTextIsNoChannel) {
  EXPECT_FALSE(horseChannelFromName("lowerBack.rz"));  // a rider channel
  EXPECT_FALSE(riderChannelFromName("lfHoof.tx"));     // a horse channel
  EXPECT_FALSE(horseChannelFromName("LFHOOF.TX"));     // names are case-sensitive
  EXPECT_FALSE(horseChannelFromName("lfHoof.tx "));
  EXPECT_FALSE(horseChannelFromName("lfHoof"));
  EXPECT_FALSE(horseChannelFromName(""));
  EXPECT_FALSE(riderChannelFromName("hair"));
}

}  // namespace
}  // namespace stirrup::rig
