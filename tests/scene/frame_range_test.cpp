#include "scene/frame_range.h"

#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

TEST(FrameRange, SingleFrameAndRange) {
  EXPECT_EQ(parseFrameList("7", "f"), (std::vector<int>{7}));
  EXPECT_EQ(parseFrameList("1-4", "f"), (std::vector<int>{1, 2, 3, 4}));
}

TEST(FrameRange, StepAndLists) {
  EXPECT_EQ(parseFrameList("1-10x4", "f"), (std::vector<int>{1, 5, 9}));
  EXPECT_EQ(parseFrameList("1-3,8-9", "f"), (std::vector<int>{1, 2, 3, 8, 9}));
  // A frame listed twice is rendered once, in the order first given.
  EXPECT_EQ(parseFrameList("3-5,1-4", "f"), (std::vector<int>{3, 4, 5, 1, 2}));
}

TEST(FrameRange, NegativeFrames) {
  EXPECT_EQ(parseFrameList("-2-1", "f"), (std::vector<int>{-2, -1, 0, 1}));
}

TEST(FrameRange, ErrorsNameTheContextAndThePart) {
  for (const char* bad : {"", "a", "1-", "5-1", "1-10x0", "1-10x-2", "1,,2", "1-2x", "1.5"}) {
    try {
      parseFrameList(bad, "--frames");
      FAIL() << "accepted \"" << bad << "\"";
    } catch (const rig::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--frames: ", 0), 0u) << e.what();
    }
  }
  try {
    parseFrameList("1-10,20-x", "--frames");
    FAIL();
  } catch (const rig::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"20-x\""), std::string::npos) << e.what();
  }
}

std::string errorOf(const std::string& spec) {
  return stirrup::test::errorOf([&] { parseFrameList(spec, "--frames"); }, "(accepted)");
}

// The example: a typo of a hundred million frames is a one-line error, not std::bad_alloc.
TEST(FrameRange, FrameNumbersPastTheMaximumAreOneLineErrors) {
  EXPECT_EQ(errorOf("1-100000000"), "--frames: \"1-100000000\": expected frame numbers from -999999 to 999999, got 100000000");
  EXPECT_EQ(errorOf("-1000000-1"), "--frames: \"-1000000-1\": expected frame numbers from -999999 to 999999, got -1000000");
  EXPECT_EQ(errorOf("5,1000000"), "--frames: \"1000000\": expected frame numbers from -999999 to 999999, got 1000000");
  // Past int: from_chars reports out of range, still one line naming the part.
  EXPECT_EQ(errorOf("1-99999999999"), "--frames: \"1-99999999999\": expected a range FIRST-LAST[xSTEP] of whole numbers");
  // The largest frame numbers themselves are fine.
  EXPECT_EQ(parseFrameList("999999", "f"), (std::vector<int>{999999}));
  EXPECT_EQ(parseFrameList("-999999--999998", "f"), (std::vector<int>{-999999, -999998}));
}

TEST(FrameRange, ListsPastTheMaximumCountAreOneLineErrors) {
  EXPECT_EQ(parseFrameList("1-100000", "f").size(), 100000u);
  EXPECT_EQ(parseFrameList("1-200000x2", "f").size(), 100000u);
  EXPECT_EQ(errorOf("1-100001"), "--frames: \"1-100001\": expected at most 100000 frames in the list");
  EXPECT_EQ(errorOf("-999999-999999"), "--frames: \"-999999-999999\": expected at most 100000 frames in the list");
  // Two ranges that fit alone but not together; a repeated frame counts once.
  EXPECT_EQ(errorOf("1-60000,100001-160000"), "--frames: \"100001-160000\": expected at most 100000 frames in the list");
  EXPECT_EQ(parseFrameList("1-100000,1-100000", "f").size(), 100000u);
}

TEST(FrameRange, FormatFrameListWritesTheShortestText) {
  EXPECT_EQ(formatFrameList({1, 2, 3, 4}), "1-4");
  EXPECT_EQ(formatFrameList({1, 3, 5, 7}), "1-7x2");
  EXPECT_EQ(formatFrameList({7}), "7");
  EXPECT_EQ(formatFrameList({4, 5}), "4-5");
  EXPECT_EQ(formatFrameList({4, 6}), "4,6");
  EXPECT_EQ(formatFrameList({1, 2, 3, 10, 20, 30, 31}), "1-3,10-30x10,31");
  EXPECT_EQ(formatFrameList({-3, -1, 1}), "-3-1x2");
  EXPECT_EQ(formatFrameList({9, 5, 1}), "9,5,1");  // order kept: no run with a negative step
  EXPECT_EQ(formatFrameList({}), "");
}

TEST(FrameRange, FormatFrameListReadsBackAsTheSameFrames) {
  const std::vector<std::vector<int>> lists = {
      {1, 2, 3, 10, 20, 30, 31}, {5, 3, 1, 2}, {-7, -5, -3, 0, 1}, {100}, {1, 4, 7, 8, 9, 13}, {999999, -999999}};
  for (const auto& frames : lists) EXPECT_EQ(parseFrameList(formatFrameList(frames), "test"), frames);
}

}  // namespace
}  // namespace stirrup::scene
