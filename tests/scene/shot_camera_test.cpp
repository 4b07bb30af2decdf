// A shot's camera (scene/shot_camera.h): it travels with what it follows (a single pair's clip, a
// crowd's followed pair at its start phase), and a crowd's camera out of the scene's reach is a
// one-line error naming the camera's field.
#include "scene/profile_resolver.h"
#include "scene/shot_camera.h"

#include <gtest/gtest.h>

#include "rig/error.h"
#include "rig/motion/crowd.h"
#include "scene/scene.h"
#include "tests/render/crowd_of_four.h"

namespace stirrup::scene {
namespace {

// A follow camera (no view, no damping) sits at its position in the travel frame of what it follows:
// on these straight paths along +X (heading 0, flat ground) the travel origin plus (20, 255, 900).
TEST(ShotCamera, TravelsWithThePairItFollows) {
  const SceneSpec scene = render::test::crowdOfFour();
  ShotEvaluator characters(scene, resolveProfile(scene), 1);
  CameraSpec spec;
  spec.follow_pair = 2;
  const ShotCamera camera(characters, spec);
  const auto clip = rig::makePairClip(scene.pairs[2], nullptr, "test");
  for (int frame : {1, 13}) {
    const rig::HorseFrame h = clip->sample((frame - 1) / 24.0 + 0.6);  // pair 2 starts 0.6 s into its ride
    const Camera c = camera.at(frame);
    EXPECT_NEAR(c.position.x, h.travel_cm + 20.0, 1e-9) << frame;
    EXPECT_NEAR(c.position.y, 255.0, 1e-9) << frame;
    EXPECT_NEAR(c.position.z, h.travel_z_cm + 900.0, 1e-9) << frame;
    EXPECT_NEAR(h.travel_z_cm, -300.0, 1e-6);
  }
  // A single pair's camera follows the scene's clip.
  const SceneSpec trot = loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json");
  ShotEvaluator one(trot, resolveProfile(trot), 1);
  CameraSpec plain;
  const ShotCamera side(one, plain);
  const auto trot_clip = makeSceneClip(trot);
  EXPECT_NEAR(side.at(25).position.x, trot_clip->sample(1.0).travel_cm + 20.0, 1e-9);
}

TEST(ShotCamera, ACrowdsCameraMustFollowAPairOfItAndStayOffTheTreadmill) {
  const SceneSpec scene = render::test::crowdOfFour();
  ShotEvaluator characters(scene, resolveProfile(scene), 1);
  CameraSpec far;
  far.name = "far";
  far.follow_pair = 4;
  try {
    ShotCamera camera(characters, far);
    FAIL() << "no error";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), scene.file.string() + ": cameras.far.follow_pair: expected a pair index from 0 to 3, got 4");
  }
  CameraSpec treadmill;
  treadmill.name = "mill";
  treadmill.treadmill = true;
  try {
    ShotCamera camera(characters, treadmill);
    FAIL() << "no error";
  } catch (const rig::InputError& e) {
    EXPECT_EQ(std::string(e.what()), scene.file.string() + ": cameras.mill.treadmill: expected false in a crowd scene");
  }
}

// A view is framed from every frame's points and follow frame, found in parallel on the evaluator's
// threads: the same camera to the bit at one thread and at two, for a pair's views and a crowd's.
TEST(ShotCamera, FramesTheSameViewAtAnyThreadCount) {
  for (const SceneSpec& scene : {loadScene(STIRRUP_SOURCE_DIR "/scenes/trot.json"), render::test::crowdOfFour()}) {
    for (const char* view : {"side", "persp", "close", "top"}) {
      CameraSpec spec;
      spec.name = view;
      spec.view = view;
      ShotEvaluator one(scene, resolveProfile(scene), 1), two(scene, resolveProfile(scene), 2);
      const CameraSpec a = ShotCamera(one, spec).spec(), b = ShotCamera(two, spec).spec();
      EXPECT_EQ(a.position, b.position) << scene.name << " " << view;
      EXPECT_EQ(a.target, b.target) << scene.name << " " << view;
      EXPECT_EQ(a.ortho_height_cm, b.ortho_height_cm) << scene.name << " " << view;
      EXPECT_EQ(a.fov_deg, b.fov_deg) << scene.name << " " << view;
      EXPECT_NE(a.position, spec.position) << "framed: " << scene.name << " " << view;
    }
  }
}

}  // namespace
}  // namespace stirrup::scene
