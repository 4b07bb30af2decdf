#include "scene/camera_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/shot.h"
#include "render/tracer/renderer.h"
#include "rig/rig_profile.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace stirrup::scene {
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
  std::unique_ptr<rig::Clip> clip = scene::makeClip(scene.clip);
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
  const auto clip = scene::makeClip(scene.clip);
  CameraSpec spec;
  spec.follow_target = "rider";
  spec.damping_s = 0.3;
  spec.position = {0.0, 0.0, 500.0};
  spec.target = {0.0, 0.0, 0.0};
  double worst = 0.0, travel_lo = 1e9, travel_hi = -1e9;
  for (int f : scene::parseFrameList(scene.frames, "frames")) {
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
    render::Shot shot(scene, resolveProfile(scene), *close, 0);
    const std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
    double first = 0.0, worst = 0.0;
    int worst_frame = 0;
    for (std::size_t i = 0; i < frames.size(); i += 2) {
      const render::Image image = shot.renderFrame(frames[i]);
      double sum = 0.0;
      int count = 0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
          if (image.object_id[std::size_t(y) * image.width + x] == uint32_t(render::ObjectId::Rider)) sum += x + 0.5, ++count;
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

// A horse circling to the right over rolling ground (issue 15): a circle of kCircleRadiusCm at
// kTurnRadPerS, so its heading (wrapped to ±180° as a path clip's is) is kTurnRadPerS t; the ground
// under it rises and falls kGroundAmplitudeCm slowly, with a fast gait-like ripple on top that a
// follow camera must not pass on.
constexpr double kCircleRadiusCm = 1000.0;
constexpr double kTurnRadPerS = 0.5;
constexpr double kGroundAmplitudeCm = 40.0;
constexpr double kGroundRadPerS = 0.5;
constexpr double kRippleCm = 4.0;
constexpr double kRippleHz = 3.0;

struct CircleOverHills : rig::Clip {
  std::string name() const override { return "circle"; }
  double duration() const override { return 30.0; }
  static double ground(double t) { return kGroundAmplitudeCm * std::sin(kGroundRadPerS * t); }
  static double ripple(double t) { return kRippleCm * std::sin(2.0 * kPi * kRippleHz * t); }
  rig::HorseFrame sample(double t) const override {
    rig::HorseFrame f;
    const double a = kTurnRadPerS * t;
    f.travel_cm = kCircleRadiusCm * std::sin(a);
    f.travel_z_cm = kCircleRadiusCm * (1.0 - std::cos(a));
    f.heading_deg = std::remainder(a * 180.0 / kPi, 360.0);
    f.ground_y_cm = ground(t) + ripple(t);
    return f;
  }
};

// The damped follower's gain at angular frequency w (DampedFollow's transfer function, camera_motion.h).
std::complex<double> followGain(double w, double tau) {
  return std::complex<double>(1.0, 3.0 * w * tau) / std::pow(std::complex<double>(1.0, w * tau), 3);
}

// A follow camera 6 m to the horse's right, damped 0.3 s: the side view the circle tests ride with.
CameraSpec sideFollowCamera() {
  CameraSpec spec;
  spec.damping_s = 0.3;
  spec.position = {0.0, 100.0, 600.0};
  spec.target = {0.0, 100.0, 0.0};
  return spec;
}

// The difference of two headings, degrees in (-180, 180].
double headingDifference(double a, double b) { return std::remainder(a - b, 360.0); }

// A side camera (on the horse's right, +Z of its travel frame) stays on the horse's right through a
// whole circle and more: the direction from its target to it is the horse's right, turned by the
// heading, as late as the filter's phase at the turn rate makes it (1.4° here) and no later.
TEST(FollowCamera, TurnsWithTheHorseThroughACircle) {
  const CircleOverHills clip;
  SceneSpec scene;
  const rig::RigProfile profile = rig::RigProfile::rigidRider();
  const CameraSpec spec = sideFollowCamera();
  constexpr double kSettleS = 3.0;  // 10 tau: the filter no longer sees before t = 0
  double worst = 0.0;
  for (int frame = 1 + int(kSettleS * scene.fps); frame <= int(16.0 * scene.fps); ++frame) {
    const double t = frameTime(scene, frame);
    const Camera c = cameraAtFrame(spec, scene, clip, profile, frame);
    const glm::dvec3 out = c.position - c.target;
    // Seen from above, the horse's right side is its heading turned 90° further right.
    const double camera_deg = std::atan2(out.z, out.x) * 180.0 / kPi - 90.0;
    worst = std::max(worst, std::abs(headingDifference(camera_deg, clip.sample(t).heading_deg)));
    // The target stays at the horse's travel across the ground.
    EXPECT_NEAR(c.target.x, clip.sample(t).travel_cm, 1e-6);
    EXPECT_NEAR(c.target.z, clip.sample(t).travel_z_cm, 1e-6);
  }
  const double lag_deg = std::abs(std::arg(followGain(kTurnRadPerS, spec.damping_s))) * 180.0 / kPi;
  EXPECT_LT(worst, lag_deg + 0.1) << "degrees between the camera's side and the horse's";
  EXPECT_LT(lag_deg, 2.0);
}

// Its height rides the ground: off the slow hills by no more than the filter's transfer function
// allows (the ripple damped to 9%), and with a per-frame change bounded likewise, well under the
// ripple's own per-frame change.
TEST(FollowCamera, RidesOverHillsWithoutTheRipple) {
  const CircleOverHills clip;
  SceneSpec scene;
  const rig::RigProfile profile = rig::RigProfile::rigidRider();
  const CameraSpec spec = sideFollowCamera();
  const double dt = 1.0 / scene.fps;
  const double hills_per_frame = kGroundAmplitudeCm * kGroundRadPerS * dt;
  const double ripple_per_frame = kRippleCm * 2.0 * kPi * kRippleHz * dt;  // 3.1 cm
  double previous = 0.0, worst_step = 0.0, worst_off = 0.0;
  for (int frame = 72; frame <= 480; ++frame) {
    const double t = frameTime(scene, frame);
    const double height = cameraAtFrame(spec, scene, clip, profile, frame).target.y - spec.target[1];
    if (frame > 72) worst_step = std::max(worst_step, std::abs(height - previous));
    previous = height;
    worst_off = std::max(worst_off, std::abs(height - CircleOverHills::ground(t)));
  }
  const double w_hills = kGroundRadPerS, w_ripple = 2.0 * kPi * kRippleHz, tau = spec.damping_s;
  constexpr double kSlackCm = 0.2;  // the filter's discrete sum and the frames' sampling of the peaks
  EXPECT_LT(worst_off, std::abs(followGain(w_hills, tau) - 1.0) * kGroundAmplitudeCm +
                           std::abs(followGain(w_ripple, tau)) * kRippleCm + kSlackCm)
      << "cm from the slow ground";
  EXPECT_LT(worst_step, std::abs(followGain(w_hills, tau)) * hills_per_frame +
                            std::abs(followGain(w_ripple, tau)) * ripple_per_frame + kSlackCm / 4.0)
      << "cm a frame";
  EXPECT_GT(ripple_per_frame, 2.0 * hills_per_frame);  // the bound above does exclude the raw ripple
}

// A straight clip turns nothing: the camera of a follow view is the one in the travel frame, bit for
// bit (the golden frames rely on it).
TEST_F(MotionFixture, StraightClipCameraIsNotTurned) {
  CameraSpec spec;
  spec.damping_s = 0.4;
  spec.position = {130.0, 210.0, 640.0};
  spec.target = {20.0, 100.0, 0.0};
  for (int frame : {1, 17, 40}) {
    const Camera c = cameraAtFrame(spec, scene, *clip, profile, frame);
    const glm::dvec3 offset = followOffset(spec, *clip, profile, frameTime(scene, frame), spec.damping_s);
    EXPECT_EQ(c.position, glm::dvec3(130.0, 210.0, 640.0) + offset);
    EXPECT_EQ(c.target, glm::dvec3(20.0, 100.0, 0.0) + offset);
  }
}

// A camera's motion does not depend on where the camera stands: the follow frame found for one spec
// places a spec moved, re-aimed and resized exactly as cameraAtFrame places it (framing a view finds
// each frame's follow frame once and moves the camera over it pass after pass).
TEST(FollowCamera, MotionIsFoundOnceForAnyPlaceAndSize) {
  const SceneSpec scene = loadScene(STIRRUP_SOURCE_DIR "/scenes/figure_eight.json");
  const auto clip = makeSceneClip(scene);
  const rig::RigProfile profile = rig::RigProfile::thesis();
  for (const char* motion : {"follow", "orbit", "fixed"}) {
    CameraSpec spec;
    spec.motion = motion;
    spec.follow = spec.motion == "follow";
    spec.damping_s = 0.3;
    spec.orbit_frames = 48;
    spec.position = {100, 200, 900};
    spec.target = {0, 100, 0};
    CameraSpec moved = spec;
    moved.position = {-340, 410, 1250};
    moved.target = {35, 90, -12};
    moved.fov_deg = 20.0;
    moved.ortho_height_cm = 555.0;
    for (int frame : {1, 30, 77}) {
      const FollowFrame follow = cameraFollowAtFrame(spec, scene, *clip, profile, frame);
      const Camera a = cameraFromFollow(moved, follow, frame), b = cameraAtFrame(moved, scene, *clip, profile, frame);
      EXPECT_EQ(a.position, b.position) << motion << " " << frame;
      EXPECT_EQ(a.target, b.target) << motion << " " << frame;
      EXPECT_EQ(a.fov_deg, b.fov_deg) << motion << " " << frame;
      EXPECT_EQ(a.ortho_height_cm, b.ortho_height_cm) << motion << " " << frame;
      EXPECT_EQ(follow.heading_deg, cameraHeadingAtFrame(spec, scene, *clip, profile, frame)) << motion << " " << frame;
    }
  }
  // And it does move: the follow camera turns with the horse on the figure eight.
  CameraSpec spec;
  spec.motion = "follow";
  spec.follow = true;
  spec.damping_s = 0.3;
  EXPECT_NE(cameraFollowAtFrame(spec, scene, *clip, profile, 1).heading_deg,
            cameraFollowAtFrame(spec, scene, *clip, profile, 100).heading_deg);
}

}  // namespace
}  // namespace stirrup::scene
