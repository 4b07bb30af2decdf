#include "rig/error.h"

#include <string>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

// Found by fuzzing (tests/fuzz/regressions/frame_spec/newline_in_part): a frame list holding a newline
// made a two-line error. Every InputError is one line whatever user text it quotes.
TEST(InputError, ControlCharactersInTheMessageAreEscapedSoItStaysOneLine) {
  EXPECT_STREQ(InputError("--frames: \"1\n2\": expected ...").what(), "--frames: \"1\\n2\": expected ...");
  EXPECT_STREQ(InputError(std::string("a\r\tb\x1b[31m\x7f") + '\0' + "c").what(), "a\\r\\tb\\x1B[31m\\x7F\\x00c");
  // Printable text, UTF-8 and backslashes are unchanged, so escaping twice changes nothing.
  EXPECT_STREQ(InputError("scene.json: cameras[1].fov: caf\xC3\xA9 \\n").what(), "scene.json: cameras[1].fov: caf\xC3\xA9 \\n");
  const InputError once("x\ny");
  EXPECT_STREQ(InputError(once.what()).what(), once.what());
}

TEST(InputError, NumbersAreQuotedShortOrInAReportsOwnFormat) {
  EXPECT_EQ(numberText(0.5), "0.5");
  EXPECT_EQ(numberText(1e300), "1e+300");
  EXPECT_EQ(printfNumber("%.1f", 1.26), "1.3");
  EXPECT_EQ(printfNumber("%.0f cm", 41.6), "42 cm");
}

}  // namespace
}  // namespace stirrup::rig
