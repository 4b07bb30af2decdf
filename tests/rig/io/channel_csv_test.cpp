#include "rig/io/channel_csv.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>

#include "rig/error.h"
#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
using H = HorseChannel;
using R = RiderChannel;

class ChannelCsv : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() /
                  ("stirrup_csv_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  void SetUp() override {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& text) {
    const fs::path f = dir_ / "horse.csv";
    std::ofstream(f, std::ios::binary) << text;
    return f;
  }
  std::string errorOf(const std::string& text) {
    const fs::path f = write(text);
    return stirrup::test::errorOf([&] { readHorseCsv(f); });
  }
  std::string file() const { return (dir_ / "horse.csv").string(); }
};

TEST_F(ChannelCsv, ReadsAnySubsetInAnyOrderAbsentIsZero) {
  const HorseTrack t = readHorseCsv(write("lfHoof.ty, frame ,rearPivot.rz\r\n12.5,1,-3\r\n\r\n0,2,+4e1\n"));
  ASSERT_EQ(t.frames.size(), 2u);
  EXPECT_EQ(t.frames[0], 1);
  EXPECT_EQ(t.frames[1], 2);
  EXPECT_EQ(t.horse[0][H::lfHoofTy], 12.5);
  EXPECT_EQ(t.horse[0][H::rearPivotRz], -3);
  EXPECT_EQ(t.horse[1][H::rearPivotRz], 40);
  EXPECT_EQ(t.horse[0][H::rbHoofTx], 0);
  EXPECT_EQ(t.horse[1][H::backMidRz], 0);
}

// A spreadsheet's "CSV UTF-8" (Excel, LibreOffice) writes a byte-order mark before the header.
TEST_F(ChannelCsv, AUtf8ByteOrderMarkBeforeTheHeaderIsSkipped) {
  const HorseTrack t = readHorseCsv(write("\xEF\xBB\xBF" "frame,lfHoof.ty\r\n1,12.5\r\n2,3\r\n"));
  ASSERT_EQ(t.frames.size(), 2u);
  EXPECT_EQ(t.frames[1], 2);
  EXPECT_EQ(t.horse[0][H::lfHoofTy], 12.5);
  // Only before the header: a mark inside the data is still not a number.
  EXPECT_EQ(errorOf("frame,lfHoof.ty\n\xEF\xBB\xBF" "1,2\n"),
            (dir_ / "horse.csv").string() + ": row 2, column frame: expected a number, got \"\xEF\xBB\xBF" "1\"");
}

TEST_F(ChannelCsv, HeaderOnlyIsNoFrames) { EXPECT_TRUE(readHorseCsv(write("frame,lfHoof.tx\n")).frames.empty()); }

TEST_F(ChannelCsv, ErrorsAreOneLineNamingFileRowAndColumn) {
  EXPECT_EQ(errorOf("frame,lfHoof.ty\n1,high\n"),
            file() + ": row 2, column lfHoof.ty: expected a number, got \"high\"");
  EXPECT_EQ(errorOf("frame,lfHoof.ty\n1,2\n2,nan\n"),
            file() + ": row 3, column lfHoof.ty: expected a finite number, got \"nan\"");
  EXPECT_EQ(errorOf("frame,lfHoof.ty\n1,-inf\n"),
            file() + ": row 2, column lfHoof.ty: expected a finite number, got \"-inf\"");
  EXPECT_EQ(errorOf("frame,lfHoof.ty\n1,1e999\n"),
            file() + ": row 2, column lfHoof.ty: expected a finite number, got \"1e999\"");
  EXPECT_EQ(errorOf("frame,lfHoof.ty\n1,\n"), file() + ": row 2, column lfHoof.ty: expected a number, got an empty field");
  EXPECT_EQ(errorOf("frame,lfHoof.ty\nx,1\n"), file() + ": row 2, column frame: expected a number, got \"x\"");
  EXPECT_EQ(errorOf("frame,lfHoof.ty\n1,2,3\n"),
            file() + ": row 2, column 3: expected 2 columns as in the header, got 3");
  EXPECT_EQ(errorOf("frame,lfHoof.ty,rfHoof.ty\n1,2\n"),
            file() + ": row 2, column 3: expected 3 columns as in the header, got 2");
  EXPECT_EQ(errorOf("frame,lfHoof.height\n"),
            file() + ": row 1, column lfHoof.height: expected `frame` or a horse channel name (lfHoof.tx ... "
                     "backMid.rz), got \"lfHoof.height\"");
  EXPECT_EQ(errorOf("frame,lowerBack.rz\n"),
            file() + ": row 1, column lowerBack.rz: expected `frame` or a horse channel name (lfHoof.tx ... "
                     "backMid.rz), got \"lowerBack.rz\"");
  EXPECT_EQ(errorOf("lfHoof.ty,rfHoof.ty\n1,2\n"),
            file() + ": row 1, column frame: expected a `frame` column in the header, got \"lfHoof.ty,rfHoof.ty\"");
  EXPECT_EQ(errorOf("frame,lfHoof.ty,lfHoof.ty\n"),
            file() + ": row 1, column lfHoof.ty: expected each column once, got it twice");
  EXPECT_EQ(errorOf("frame,frame\n"), file() + ": row 1, column frame: expected each column once, got `frame` twice");
  EXPECT_EQ(errorOf(""), file() + ": row 1: expected a header line starting `frame`, got an empty file");
  EXPECT_EQ(errorOf("\n\nframe,lfHoof.ty\n\n1,x\n"), file() + ": row 5, column lfHoof.ty: expected a number, got \"x\"");
}

TEST_F(ChannelCsv, MissingFileIsAnInputError) {
  try {
    readHorseCsv(dir_ / "nope.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "nope.csv").string() + ": cannot read the file (expected a horse channel CSV)");
  }
}

TEST_F(ChannelCsv, HorseWriteReadRoundTripsExactly) {
  std::vector<double> frames{1, 2, 3.5};
  std::vector<HorseChannels> horse(3);
  for (std::size_t i = 0; i < horse.size(); ++i)
    for (std::size_t c = 0; c < kHorseChannelCount; ++c) horse[i].value[c] = 0.1 * static_cast<double>(c) - 1.0 / 3 + i;
  const fs::path f = dir_ / "sub" / "h.csv";
  writeHorseCsv(f, frames, horse);
  const HorseTrack t = readHorseCsv(f);
  ASSERT_EQ(t.frames, frames);
  for (std::size_t i = 0; i < horse.size(); ++i) EXPECT_EQ(t.horse[i].value, horse[i].value);
  EXPECT_FALSE(fs::exists(f.string() + ".tmp"));
}

TEST_F(ChannelCsv, RiderCsvHasFrameAndEveryRiderChannel) {
  RiderChannels r;
  r[R::lowerBackRz] = 1.5;
  r[R::clothSide] = -2;
  r[R::hipRz] = -0.0;  // written as 0
  const fs::path f = dir_ / "r.csv";
  writeRiderCsv(f, std::vector<double>{7}, std::vector<RiderChannels>{r});
  std::ifstream in(f);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::string expected_header = "frame";
  for (std::string_view n : kRiderChannelNames) {
    expected_header += ',';
    expected_header += n;
  }
  EXPECT_EQ(header, expected_header);
  EXPECT_EQ(row.substr(0, 8), "7,1.5,0,");
  EXPECT_EQ(row.substr(row.size() - 3), ",-2");
  EXPECT_EQ(row.find("-0,"), std::string::npos);
}

TEST_F(ChannelCsv, FailedWriteLeavesNoFileBehind) {
  // The target is a directory: the rename fails, and neither FILE nor FILE.tmp remains as a file.
  const fs::path target = dir_ / "is_a_dir.csv";
  fs::create_directories(target / "x");
  EXPECT_THROW(writeRiderCsv(target, std::vector<double>{1}, std::vector<RiderChannels>(1)), InputError);
  EXPECT_FALSE(fs::exists(target.string() + ".tmp"));
  EXPECT_TRUE(fs::is_directory(target));
  // A parent that cannot be created (a file in the way).
  std::ofstream(dir_ / "plain") << "x";
  EXPECT_THROW(writeRiderCsv(dir_ / "plain" / "r.csv", std::vector<double>{1}, std::vector<RiderChannels>(1)), InputError);
  EXPECT_FALSE(fs::exists(dir_ / "plain" / "r.csv"));
}

}  // namespace
}  // namespace stirrup::rig
