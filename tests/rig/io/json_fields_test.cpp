#include "rig/io/json_fields.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

class JsonFile : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() /
                  ("stirrup_json_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  void SetUp() override {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& text) {
    const fs::path f = dir_ / "file.json";
    std::ofstream(f, std::ios::binary) << text;
    return f;
  }
  std::string errorOf(const std::string& text) {
    return stirrup::test::errorOf([&] { readJsonFile(write(text)); });
  }
};

// Notepad's and many editors' "UTF-8 with BOM".
TEST_F(JsonFile, AUtf8ByteOrderMarkIsSkipped) {
  const nlohmann::json j = readJsonFile(write("\xEF\xBB\xBF{\"name\": \"trot\", \"fps\": 24}\r\n"));
  EXPECT_EQ(j.at("name"), "trot");
  EXPECT_EQ(j.at("fps"), 24);
}

TEST_F(JsonFile, APartialByteOrderMarkOrOneInsideIsAnError) {
  const std::string file = (dir_ / "file.json").string();
  EXPECT_EQ(errorOf("\xEF\xBB{}").rfind(file + ": not valid JSON: parse error at line 1, column ", 0), 0u) << errorOf("\xEF\xBB{}");
  EXPECT_EQ(errorOf("{\"a\": \xEF\xBB\xBF 1}").rfind(file + ": not valid JSON: parse error", 0), 0u);
}

// Found by fuzzing (tests/fuzz/regressions/scene_json/number_overflow): nlohmann throws out_of_range,
// not parse_error, for a number past a double; it escaped as "stirrup: error: [json.exception...".
TEST_F(JsonFile, ANumberPastADoubleIsOneLineNamingTheFile) {
  EXPECT_EQ(errorOf("{\"fps\": 1e400}"), (dir_ / "file.json").string() + ": not valid JSON: number overflow parsing '1e400'");
}

TEST_F(JsonFile, MissingFileAndSyntaxErrorsNameTheFile) {
  EXPECT_EQ(errorOf("{\"a\": }").rfind((dir_ / "file.json").string() + ": not valid JSON: parse error at line 1, column 7", 0), 0u)
      << errorOf("{\"a\": }");
  try {
    readJsonFile(dir_ / "none.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "none.json").string() + ": cannot open the file (expected a readable JSON file)");
  }
}

// Found by fuzzing (tests/fuzz/regressions/profile_sets/set_value_not_utf8): `--set KEY=b\xE9g` (Latin-1
// from a shell) made nlohmann's dump throw its own type_error instead of the one-line InputError.
TEST(DescribeJson, TextThatIsNotUtf8IsDescribedNotThrown) {
  EXPECT_EQ(describeJson(nlohmann::json("b\xE9g")), "\"b\xEF\xBF\xBDg\"");  // U+FFFD for the bad byte
  EXPECT_EQ(describeJson(nlohmann::json("big")), "\"big\"");
}

}  // namespace
}  // namespace stirrup::rig
