#include "render/review/channel_plot.h"

#include <algorithm>
#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace stirrup::render {
namespace {

namespace fs = std::filesystem;

TEST(NiceTicks, StepsOfOneTwoOrFive) {
  EXPECT_EQ(niceTicks(0.0, 10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(niceTicks(-3.0, 22.0, 5), (std::vector<double>{0, 5, 10, 15, 20}));
  // 10 ticks over 5.2 s would be 0.52 apart: the next nice step is 1.
  EXPECT_EQ(niceTicks(0.0, 5.2, 10), (std::vector<double>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(niceTicks(0.0, 3.0, 10), (std::vector<double>{0, 0.5, 1, 1.5, 2, 2.5, 3}));
}

TEST(ChannelPlot, PlotsTheBakedChannelsOfTheMovement) {
  const scene::SceneSpec scene = scene::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/trot.json");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const auto clip = scene::makeClip(scene.clip);
  std::vector<rig::BakedFrame> baked;
  for (int f = 1; f <= 24; ++f) baked.push_back(rig::bakeFrame(*clip, profile, f, scene::frameTime(scene, f)));
  const ChannelPlot plot = movementPlot("trot", baked, profile.rider_unit_cm);
  ASSERT_EQ(plot.frames.size(), 24u);
  ASSERT_GE(plot.panels.size(), 3u);
  EXPECT_EQ(plot.panels[0].series.size(), 4u);  // the four hooves
  EXPECT_DOUBLE_EQ(plot.panels[0].series[0].values[5], baked[5].horse.controls[rig::HorseChannel::lfHoofTy]);
  EXPECT_DOUBLE_EQ(plot.panels.back().series[1].values[7],
                   baked[7].rider[rig::RiderChannel::cogTy] * profile.rider_unit_cm);

  const fs::path file = fs::path(STIRRUP_BINARY_DIR) / "test_channel_plot" / "trot_plot.png";
  fs::remove_all(file.parent_path());
  writeChannelPlot(plot, file, 900);
  OIIO::ImageBuf im(file.string());
  ASSERT_TRUE(im.read());
  EXPECT_EQ(im.spec().width, 900);
  // Each series' colour is drawn somewhere (its curve and its legend swatch).
  std::vector<float> px(std::size_t(im.spec().width) * im.spec().height * 3);
  ASSERT_TRUE(im.get_pixels(im.roi(), OIIO::TypeDesc::FLOAT, px.data()));
  for (const PlotPanel& p : plot.panels)
    for (const ChannelSeries& s : p.series) {
      int hits = 0;
      for (std::size_t i = 0; i < px.size(); i += 3)
        if (std::abs(px[i] - s.colour[0]) < 0.02f && std::abs(px[i + 1] - s.colour[1]) < 0.02f &&
            std::abs(px[i + 2] - s.colour[2]) < 0.02f)
          ++hits;
      EXPECT_GT(hits, 40) << s.label;
    }
}

// A path scene's plot adds speed and gait, and roll, slope and the rider's sideways lean: the gait
// steps walk (1), trot (2), canter (3) on the cross-country ride, the lead's sign follows the turns,
// and the roll is the clip's own rearPivot.rx.
TEST(ChannelPlot, PathScenesAddSpeedGaitAndRoll) {
  const scene::SceneSpec scene = scene::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/cross_country.json");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  const auto clip = scene::makeSceneClip(scene);
  const auto* path = dynamic_cast<const rig::PathClip*>(clip.get());
  ASSERT_NE(path, nullptr);
  std::vector<rig::BakedFrame> baked;
  for (int f = 1; f <= 687; f += 6) baked.push_back(rig::bakeFrame(*clip, profile, f, scene::frameTime(scene, f)));
  const std::vector<PlotPanel> panels = pathPanels(*path, baked);
  ASSERT_EQ(panels.size(), 2u);
  const std::vector<double>& gait = panels[0].series[1].values;
  EXPECT_EQ(gait.front(), 1.0) << "a walk at the start";
  EXPECT_NE(std::find(gait.begin(), gait.end(), 2.0), gait.end()) << "a trot";
  EXPECT_NE(std::find(gait.begin(), gait.end(), 3.0), gait.end()) << "a canter on the right lead";
  EXPECT_EQ(gait.back(), -3.0) << "a canter on the left lead at the end";
  for (std::size_t i = 0; i < baked.size(); ++i) {
    EXPECT_NEAR(panels[0].series[0].values[i], path->speedAt(baked[i].seconds) / 100.0, 1e-12);
    EXPECT_EQ(panels[1].series[0].values[i], baked[i].horse.controls[rig::HorseChannel::rearPivotRx]);
    EXPECT_EQ(panels[1].series[1].values[i], baked[i].horse.ground_pitch_deg);
  }
  EXPECT_GT(*std::max_element(panels[0].series[0].values.begin(), panels[0].series[0].values.end()), 5.0);
}

}  // namespace
}  // namespace stirrup::render
