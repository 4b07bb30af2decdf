#include "render/camera_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/renderer.h"
#include "render/scene.h"
#include "render/shot.h"
#include "rig/io/frame_range.h"
#include "rig/motion/clip_factory.h"
#include "rig/rig_profile.h"

namespace stirrup::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(DampedFollow, ReturnsAConstantPathExactly) {
  const glm::dvec3 p(3.0, -2.0, 7.0);
  const glm::dvec3 y = dampedFollow([&](double) { return p; }, 1.3, 0.4);
  EXPECT_NEAR(glm::length(y - p), 0.0, 1e-9);
}

TEST(DampedFollow, FollowsSteadyTravelWithoutLag) {
  // A horse at 360 cm/s: a plain critically damped follower would lag 2 tau v = 288 cm behind.
  const auto path = [](double t) { return glm::dvec3(360.0 * t, 0.0, 0.0); };
  for (double t : {0.0, 0.5, 2.0}) EXPECT_NEAR(dampedFollow(path, t, 0.4).x, 360.0 * t, 0.5) << t;
}

TEST(DampedFollow, DampsABobByItsTransferFunction) {
  // A 2 Hz bob of 10 cm, tau chosen so w tau = 5: |H| = |1 + 15i| / |1 + 5i|^3 = 0.113.
  const double w = 2.0 * kPi * 2.0, tau = 5.0 / w;
  const auto path = [&](double t) { return glm::dvec3(0.0, 10.0 * std::sin(w * t), 0.0); };
  double peak = 0.0;
  // From t = 5 s the filter's 10-tau window (4 s) no longer reaches before t = 0.
  for (int i = 0; i < 200; ++i) peak = std::max(peak, std::abs(dampedFollow(path, 5.0 + i * 0.0025, tau).y));
  const double expected = 10.0 * std::abs(std::complex<double>(1.0, 3.0 * w * tau) /
                                          std::pow(std::complex<double>(1.0, w * tau), 3));
  EXPECT_NEAR(peak, expected, 0.05 * expected);
  EXPECT_LT(peak, 1.5);
}

TEST(DampedFollow, ZeroTauIsThePathItself) {
  const auto path = [](double t) { return glm::dvec3(t, t * t, 0.0); };
  EXPECT_EQ(dampedFollow(path, 1.7, 0.0), path(1.7));
}

struct MotionFixture : ::testing::Test {
  SceneSpec scene = loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/trot.json");
  rig::RigProfile profile = resolveProfile(scene);
  std::unique_ptr<rig::Clip> clip = rig::makeClip(scene.clip);
};

TEST_F(MotionFixture, FollowCameraTravelsWithTheHorse) {
  CameraSpec spec;  // follow, damping 0: rigidly in the travel frame
  for (int f : {1, 10, 40}) {
    const Camera c = cameraAtFrame(spec, scene, *clip, profile, f);
    const double travel = clip->sample(frameTime(scene, f)).travel_cm;
    EXPECT_NEAR(c.position.x, spec.position[0] + travel, 1e-9);
    EXPECT_NEAR(c.target.x, spec.target[0] + travel, 1e-9);
  }
}

TEST_F(MotionFixture, FixedCameraStays) {
  CameraSpec spec;
  spec.motion = "fixed";
  const Camera a = cameraAtFrame(spec, scene, *clip, profile, 1), b = cameraAtFrame(spec, scene, *clip, profile, 40);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.target, b.target);
}

TEST_F(MotionFixture, DampedCameraIsAPureFunctionOfTheFrame) {
  CameraSpec spec;
  spec.follow_target = "rider";
  spec.damping_s = 0.3;
  const Camera later = cameraAtFrame(spec, scene, *clip, profile, 30);
  for (int f = 1; f < 30; ++f) (void)cameraAtFrame(spec, scene, *clip, profile, f);
  const Camera again = cameraAtFrame(spec, scene, *clip, profile, 30);
  EXPECT_EQ(later.position, again.position);
  // The rider's bob is smoothed: the damped camera's height moves less than the rider's seat does.
  double seat_lo = 1e9, seat_hi = -1e9, cam_lo = 1e9, cam_hi = -1e9;
  for (int f = 20; f <= 60; ++f) {
    const double seat = followPoint(spec, *clip, profile, frameTime(scene, f)).y;
    const double cam = cameraAtFrame(spec, scene, *clip, profile, f).target.y;
    seat_lo = std::min(seat_lo, seat), seat_hi = std::max(seat_hi, seat);
    cam_lo = std::min(cam_lo, cam), cam_hi = std::max(cam_hi, cam);
  }
  EXPECT_GT(seat_hi - seat_lo, 1.0);
  EXPECT_LT(cam_hi - cam_lo, 0.5 * (seat_hi - seat_lo));
}

TEST_F(MotionFixture, OrbitGoesOnceAroundOverItsFrames) {
  CameraSpec spec;
  spec.motion = "orbit";
  spec.treadmill = true;
  spec.orbit_frames = 36;
  spec.position = {0.0, 150.0, 500.0};
  spec.target = {0.0, 100.0, 0.0};
  const Camera start = cameraAtFrame(spec, scene, *clip, profile, 1);
  const Camera quarter = cameraAtFrame(spec, scene, *clip, profile, 10);
  const Camera full = cameraAtFrame(spec, scene, *clip, profile, 37);
  EXPECT_NEAR(glm::length(full.position - start.position), 0.0, 1e-6);
  // A quarter turn later the camera looks from the horse's front (+X), at the same height and radius.
  EXPECT_NEAR(quarter.position.x, 500.0, 1e-6);
  EXPECT_NEAR(quarter.position.z, 0.0, 1e-6);
  EXPECT_NEAR(quarter.position.y, 150.0, 1e-9);
}


// A clip heading along world +Z (a path clip's travel frame turned 90° right): the follow point moves
// with the travel frame in x and z, and the rider's seat, ahead of the rear pivot, is ahead along +Z.
struct AlongZ : rig::Clip {
  std::string name() const override { return "along_z"; }
  double duration() const override { return 4.0; }
  rig::HorseFrame sample(double t) const override {
    rig::HorseFrame f;
    f.travel_cm = 50.0;
    f.travel_z_cm = 300.0 * t;
    f.heading_deg = 90.0;
    return f;
  }
};

TEST(FollowCamera, FollowsATravelFrameThatTurned) {
  const AlongZ clip;
  SceneSpec scene;
  // The rigid rider: her channels at rest, so the seat is the saddle's and nothing else.
  const rig::RigProfile profile = rig::RigProfile::rigidRider();
  CameraSpec spec;
  EXPECT_NEAR(glm::length(followPoint(spec, clip, profile, 2.0) - glm::dvec3(50.0, 0.0, 600.0)), 0.0, 1e-9);
  spec.follow_target = "rider";
  spec.seat_from_pivot_cm = {70.0, 30.0, 0.0};
  // At rest the seat is where the lever puts it, so the point is the travel frame's origin; pitch the
  // body 10° up and the seat swings back along the heading (-Z) and up.
  EXPECT_NEAR(glm::length(followPoint(spec, clip, profile, 2.0) - glm::dvec3(50.0, 0.0, 600.0)), 0.0, 1e-6);
  struct Pitched : AlongZ {
    rig::HorseFrame sample(double t) const override {
      rig::HorseFrame f = AlongZ::sample(t);
      f.controls[rig::HorseChannel::rearPivotRz] = 10.0;
      return f;
    }
  } pitched;
  const glm::dvec3 p = followPoint(spec, pitched, profile, 2.0) - glm::dvec3(50.0, 0.0, 600.0);
  // The lever (70, 30) turned 10° up: 70 cos 10° - 30 sin 10° - 70 back, 70 sin 10° + 30 cos 10° - 30 up.
  const double c = std::cos(10.0 * kPi / 180.0), sn = std::sin(10.0 * kPi / 180.0);
  EXPECT_NEAR(p.x, 0.0, 1e-6);
  EXPECT_NEAR(p.z, 70.0 * c - 30.0 * sn - 70.0, 1e-6);
  EXPECT_NEAR(p.y, 70.0 * sn + 30.0 * c - 30.0, 1e-6);
}

// A horse decelerating from 9 m/s to a halt (the stop): along the travel the close camera follows the
// rider's seat exactly instead of overshooting it (the old filter, damping the travel too, ran 140 cm
// past her seat and came back); only its height is damped.
TEST(FollowCamera, StaysOverTheSeatWhileTheHorseStops) {
  const SceneSpec scene = loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/stop.json");
  const rig::RigProfile profile = resolveProfile(scene);
  const auto clip = rig::makeClip(scene.clip);
  CameraSpec spec;
  spec.follow_target = "rider";
  spec.damping_s = 0.3;
  spec.position = {0.0, 0.0, 500.0};
  spec.target = {0.0, 0.0, 0.0};
  double worst = 0.0, travel_lo = 1e9, travel_hi = -1e9;
  for (int f : rig::parseFrameList(scene.frames, "frames")) {
    const double t = frameTime(scene, f);
    const double seat = followPoint(spec, *clip, profile, t).x;
    worst = std::max(worst, std::abs(cameraAtFrame(spec, scene, *clip, profile, f).target.x - seat));
    const double travel = clip->sample(t).travel_cm;
    travel_lo = std::min(travel_lo, travel), travel_hi = std::max(travel_hi, travel);
  }
  EXPECT_GT(travel_hi - travel_lo, 1000.0);  // the horse does travel, and stops
  EXPECT_LT(worst, 1e-6) << "cm between the camera's aim and the rider's seat along the travel";
}

// Every scene's close view (the movie set's stop_close, trot_close and walk_close among them), rendered
// small: the rider's matte centroid (the pixels whose object id is the rider) stays within 5% of the
// frame's width of where the first frame puts it, on every other frame of the clip.
TEST(FollowCamera, RiderHoldsHerPlaceInEveryCloseView) {
  for (const char* name : {"stop", "trot", "walk", "canter", "gallop", "jump", "rear", "buck"}) {
    SceneSpec scene = loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + name + ".json");
    scene.width = 160;
    scene.height = 90;
    scene.samples = 1;
    const auto close = std::find_if(scene.cameras.begin(), scene.cameras.end(),
                                    [](const CameraSpec& c) { return c.view == "close"; });
    ASSERT_NE(close, scene.cameras.end()) << name;
    Shot shot(scene, resolveProfile(scene), *close, 0);
    const std::vector<int> frames = rig::parseFrameList(scene.frames, "frames");
    double first = 0.0, worst = 0.0;
    int worst_frame = 0;
    for (std::size_t i = 0; i < frames.size(); i += 2) {
      const Image image = shot.renderFrame(frames[i]);
      double sum = 0.0;
      int count = 0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
          if (image.object_id[std::size_t(y) * image.width + x] == uint32_t(ObjectId::Rider)) sum += x + 0.5, ++count;
      ASSERT_GT(count, 200) << name << " frame " << frames[i] << ": the rider is in the close view";
      const double centroid = sum / count / image.width;  // fraction of the width
      if (i == 0) first = centroid;
      if (std::abs(centroid - first) > worst) worst = std::abs(centroid - first), worst_frame = frames[i];
    }
    std::printf("%-7s close: the rider's matte centroid moves at most %.1f%% of the width (frame %d)\n", name,
                100.0 * worst, worst_frame);
    EXPECT_LE(worst, 0.05) << name << " frame " << worst_frame;
  }
}

}  // namespace
}  // namespace stirrup::render
