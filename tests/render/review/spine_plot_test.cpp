// The curve-spine plot (render/review/spine_plot.cpp): its layout (two panels a pose, poses_per_row to
// a row), that each pose is drawn where its panel's centre is, and bad input.
#include "render/review/spine_plot.h"

#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "tests/input_error.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

class SpinePlot : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("stirrup_spine_plot_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Width, height and 8-bit RGB pixels of a written plot.
  struct Read {
    int width = 0, height = 0;
    std::vector<uint8_t> px;
    std::array<int, 3> at(int x, int y) const {
      const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
      return {px[i], px[i + 1], px[i + 2]};
    }
  };
  static Read read(const fs::path& file) {
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(file.string());
    Read r;
    if (!in) return r;
    r.width = in->spec().width;
    r.height = in->spec().height;
    r.px.resize(std::size_t(r.width) * std::size_t(r.height) * 3);
    in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, r.px.data());
    return r;
  }
  fs::path dir_;
};

// The rest pose is straight, so its middle is the middle of the plot's bounding box and lands on the
// centre of each panel; a panel's quarter point lies off the pose, the ground line and the frame.
// The background, 0.97 0.97 0.95, is 247 247 242 in 8 bits.
TEST_F(SpinePlot, TwoPanelsAPoseAndEachPoseAtItsPanelsCentre) {
  const rig::CurveSpine spine({14.0, 16.0, 18.0}, 10);
  const rig::SpineResult rest = spine.solve({});
  SpinePlotStyle style;
  style.panel_size = 100;
  style.margin = 10;
  style.poses_per_row = 3;
  const fs::path four = dir_ / "sub" / "four.png";  // the folder is made
  writeSpinePlot({rest, rest, rest, rest}, four, style);
  const Read r = read(four);
  EXPECT_EQ(r.width, 600);  // 3 poses x 2 panels x 100
  EXPECT_EQ(r.height, 200);  // 2 rows
  const std::array<int, 3> background = {247, 247, 242};
  for (const auto& [cx, cy] : {std::pair{50, 50}, std::pair{150, 50}, std::pair{250, 50}, std::pair{50, 150}}) {
    EXPECT_NE(r.at(cx, cy), background) << "no pose at " << cx << ", " << cy;
    EXPECT_EQ(r.at(cx - 25, cy - 25), background) << cx - 25 << ", " << cy - 25;
  }
  EXPECT_EQ(r.at(350, 150), background);  // no fifth pose
  EXPECT_FALSE(fs::exists(four.string() + ".tmp.png"));
  const fs::path two = dir_ / "two.png";
  writeSpinePlot({rest, rest}, two, style);  // fewer poses than a row: the row is as wide as they are
  EXPECT_EQ(read(two).width, 400);
  EXPECT_EQ(read(two).height, 100);
}

TEST_F(SpinePlot, NoPosesIsAnError) {
  EXPECT_EQ(test::errorOf([&] { writeSpinePlot({}, dir_ / "none.png"); }), (dir_ / "none.png").string() + ": no poses to plot");
  EXPECT_FALSE(fs::exists(dir_ / "none.png"));
}

}  // namespace
}  // namespace stirrup::render
