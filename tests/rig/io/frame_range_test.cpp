#include "rig/io/frame_range.h"

#include <gtest/gtest.h>

#include "rig/error.h"

namespace stirrup::rig {
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
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--frames: ", 0), 0u) << e.what();
    }
  }
  try {
    parseFrameList("1-10,20-x", "--frames");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"20-x\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stirrup::rig
