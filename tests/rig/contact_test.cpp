// Contact between the rider and the horse on every default clip (the scenes in scenes/*.json), every
// frame, with the default characters posed as the shot poses them (rig::poseMounted):
//  - seat: the rider's pelvis stays over the saddle's seat, in the saddle's frame;
//  - feet: the ball of each foot stays on its stirrup tread;
//  - depth: no rider vertex is inside the horse by more than kMaxDepthCm, however deep it is
//    (rig/contact_depth.h: the nearest point on the skinned horse's surface at any distance,
//    and the side from the horse's vertex normals there). The thin tack the rider holds or stands in
//    (reins and stirrup irons) is left out.
// The measurement itself is checked first: a point at a known depth inside a sphere, and a rider
// vertex planted 15 cm inside the posed horse.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <string>
#include <unordered_map>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "rig/bake.h"
#include "rig/characters/horse_character.h"
#include "rig/characters/rider_character.h"
#include "rig/characters/seating.h"
#include "rig/contact_depth.h"
#include "rig/loose_tack.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "rig/skin.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "tests/rig/default_characters.h"

namespace stirrup::rig {
namespace {

// Limits, stated: the seat's place in the saddle (cm, saddle frame, from the seat centre), the foot
// on the tread (cm), how deep a rider vertex may sink into the horse (cm: cloth pressed on the saddle).
constexpr float kSeatHalfLengthCm = 20.0f;  // the seat (tree) is 48 cm long: ±24 about its centre
constexpr float kSeatHalfWidthCm = 8.0f;
constexpr float kSeatMaxRiseCm = 22.0f;     // pelvis joint rests 10 cm above the seat centre
constexpr float kFootOnTreadCm = 1.0f;
// Every clip: knees and calves on the flaps, seat and coat skirt against the cantle. Measured deepest
// (docs/characters.md, "Contact"): walk 2.7, trot 2.6, canter 2.4, gallop 2.8, stop 2.8, jump 3.9,
// rear 3.0, buck 3.2 cm.
constexpr float kMaxDepthCm = 4.0f;

// A sphere of radius r about c, as a closed mesh of `slices` x `stacks` quads with outward normals: its
// faces lie within r (1 - cos(pi / stacks)) of the true sphere (0.03 cm for 30 cm and 48 stacks).
struct SphereMesh {
  std::vector<glm::vec3> points, normals;
  std::vector<std::uint32_t> indices;
};
SphereMesh sphere(glm::vec3 c, float r, int slices, int stacks) {
  SphereMesh m;
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const float theta = glm::pi<float>() * float(i) / float(stacks), phi = 2.0f * glm::pi<float>() * float(j) / float(slices);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.points.push_back(c + r * n);
      m.normals.push_back(n);
    }
  const auto at = [&](int i, int j) { return std::uint32_t(i * slices + (j % slices)); };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j)
      for (std::uint32_t v : {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)})
        m.indices.push_back(v);
  return m;
}

// Depth is measured however deep: inside a 30 cm sphere, a point 15 cm in is 15 cm deep, the centre
// 30 cm, and points outside are not inside at all. (A search bounded at 10 cm from the surface, as
// this test used until issue 37, saw neither deep point.)
TEST(ContactDepth, IsMeasuredHoweverDeep) {
  const glm::vec3 c(10.0f, 120.0f, -5.0f);
  const SphereMesh s = sphere(c, 30.0f, 96, 48);
  const std::vector<bool> skip(s.points.size(), false);
  const glm::vec3 right(1, 0, 0), up(0, 1, 0);
  const std::vector<glm::vec3> outside = {c + 35.0f * right, c + 80.0f * up, c - 31.0f * up};
  const auto deepest = [&](std::vector<glm::vec3> rider) {
    return deepestRiderVertexInside(s.points, s.normals, s.indices, skip, rider);
  };
  const ContactDepth none = deepest(outside);
  EXPECT_EQ(none.vertex, -1);
  EXPECT_EQ(none.depth_cm, 0.0f);
  std::vector<glm::vec3> rider = outside;
  rider.push_back(c + 28.0f * glm::normalize(glm::vec3(1, 1, 1)));  // 2 cm in, in the band
  rider.push_back(c + 15.0f * glm::normalize(glm::vec3(-1, 2, 0)));  // 15 cm in
  ContactDepth d = deepest(rider);
  EXPECT_EQ(d.vertex, 4);
  EXPECT_NEAR(d.depth_cm, 15.0f, 0.05f);
  rider.push_back(c);  // the centre: 30 cm in
  d = deepest(rider);
  EXPECT_EQ(d.vertex, 5);
  EXPECT_NEAR(d.depth_cm, 30.0f, 0.05f);
}

// A rider's leg vertex moved 15 cm up into the posed horse's belly (from the belly's surface, along
// its inward normal) is found, 15 cm deep, by the measurement the clip tests use: far past the
// contact limit.
TEST(ContactDepth, ALegVertexPlanted15CmInsideTheHorseIsFound) {
  const Character& horse = test::defaultHorse();
  const Character& rider = test::defaultRider();
  const MountedPose pose = poseMounted(horse, rider, HorseFrame{}, RiderChannels{}, RigProfile::thesis());
  std::vector<glm::vec3> hp, hn, rp, rn;
  skinMesh(horse.mesh, horse.skeleton, pose.horse, hp, hn);
  skinMesh(rider.mesh, rider.skeleton, pose.rider, rp, rn);
  const std::vector<bool> tack = horseLooseTack(horse);
  const ContactDepth before = deepestRiderVertexInside(hp, hn, horse.mesh.indices, tack, rp);
  EXPECT_LE(before.depth_cm, kMaxDepthCm);
  // The belly: the horse vertex nearest the bottom of its barrel (HorseParams: centre 121 cm up, 31 cm
  // half height), its normal pointing down.
  const HorseParams params;
  const glm::vec3 belly = params.barrel_center - glm::vec3(0.0f, params.barrel_radii.y, 0.0f);
  std::size_t h = 0;
  for (std::size_t v = 0; v < hp.size(); ++v)
    if (!tack[v] && glm::length(hp[v] - belly) < glm::length(hp[h] - belly)) h = v;
  ASSERT_LT(glm::length(hp[h] - belly), 3.0f);
  ASSERT_LT(hn[h].y, -0.95f);
  // A vertex of the left lower leg (bound most to lKnee).
  int leg = -1;
  for (std::size_t v = 0; v < rp.size() && leg < 0; ++v) {
    const glm::vec4 w = rider.mesh.weights[v];
    int k = 0;
    for (int q = 1; q < 4; ++q)
      if (w[q] > w[k]) k = q;
    if (rider.mesh.joints[v][k] == rider.role("lKnee") && w[k] > 0.9f) leg = static_cast<int>(v);
  }
  ASSERT_GE(leg, 0);
  rp[static_cast<std::size_t>(leg)] = hp[h] - 15.0f * glm::normalize(hn[h]);
  const ContactDepth planted = deepestRiderVertexInside(hp, hn, horse.mesh.indices, tack, rp);
  EXPECT_EQ(planted.vertex, leg);
  EXPECT_NEAR(planted.depth_cm, 15.0f, 0.5f);
  EXPECT_GT(planted.depth_cm, kMaxDepthCm);
}

struct ClipContact {
  float seat_x = 0, seat_z = 0, seat_y_min = 1e9f, seat_y_max = -1e9f, foot = 0, depth = 0;
  int depth_frame = 0;
  std::string depth_joint;
};

ClipContact measure(const std::string& scene_name) {
  const Character& horse = test::defaultHorse();
  const Character& rider = test::defaultRider();
  const scene::SceneSpec scene = scene::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + scene_name + ".json");
  const RigProfile profile = scene::resolveProfile(scene);
  const auto clip = scene::makeClip(scene.clip);
  const std::vector<bool> tack = horseLooseTack(horse);
  const glm::vec3 rest_pelvis = rider.skeleton.restPosition(rider.role("pelvis"));
  ClipContact out;
  std::vector<glm::vec3> hp, hn, rp, rn;
  const std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const int frame = frames[i];
    const BakedFrame b = bakeFrame(*clip, profile, frame, scene::frameTime(scene, frame));
    const MountedPose pose = poseMounted(horse, rider, b.horse, b.rider, profile);
    // Seat, in the saddle's frame (the rider is built in saddle space, so rest = rest_pelvis).
    const glm::vec3 pelvis = glm::vec3(glm::inverse(pose.horse[horse.role("saddle")]) * pose.rider[rider.role("pelvis")][3]);
    const glm::vec3 d = pelvis - glm::vec3(rest_pelvis.x, 0.0f, rest_pelvis.z);
    out.seat_x = std::max(out.seat_x, std::abs(d.x));
    out.seat_z = std::max(out.seat_z, std::abs(d.z));
    out.seat_y_min = std::min(out.seat_y_min, d.y);
    out.seat_y_max = std::max(out.seat_y_max, d.y);
    for (const auto& [ball, tread] : {std::pair{"lBall", "lStirrup"}, std::pair{"rBall", "rStirrup"}})
      out.foot = std::max(out.foot, glm::length(glm::vec3(pose.rider[rider.role(ball)][3]) - glm::vec3(pose.horse[horse.role(tread)][3])));
    // Depth of rider vertices inside the skinned horse.
    skinMesh(horse.mesh, horse.skeleton, pose.horse, hp, hn);
    skinMesh(rider.mesh, rider.skeleton, pose.rider, rp, rn);
    const ContactDepth deepest = deepestRiderVertexInside(hp, hn, horse.mesh.indices, tack, rp);
    if (deepest.depth_cm > out.depth) {
      out.depth = deepest.depth_cm;
      out.depth_frame = frame;
      const glm::u16vec4 j = rider.mesh.joints[deepest.vertex];
      const glm::vec4 w = rider.mesh.weights[deepest.vertex];
      int k = 0;
      for (int q = 1; q < 4; ++q)
        if (w[q] > w[k]) k = q;
      out.depth_joint = rider.skeleton.joints[j[k]].name;
    }
  }
  std::printf("%-7s seat |dx| %.1f |dz| %.1f dy %.1f..%.1f cm, feet %.2f cm from the treads, deepest %.2f cm (frame %d, %s)\n",
              scene_name.c_str(), out.seat_x, out.seat_z, out.seat_y_min, out.seat_y_max, out.foot, out.depth,
              out.depth_frame, out.depth_joint.c_str());
  return out;
}

class Contact : public ::testing::TestWithParam<const char*> {};

TEST_P(Contact, SeatInSaddleFeetInStirrupsNothingInsideTheHorse) {
  const ClipContact c = measure(GetParam());
  EXPECT_LE(c.seat_x, kSeatHalfLengthCm);
  EXPECT_LE(c.seat_z, kSeatHalfWidthCm);
  EXPECT_GE(c.seat_y_min, 0.0f);
  EXPECT_LE(c.seat_y_max, kSeatMaxRiseCm);
  EXPECT_LE(c.foot, kFootOnTreadCm);
  EXPECT_LE(c.depth, kMaxDepthCm) << "frame " << c.depth_frame << ", rider joint " << c.depth_joint;
}

INSTANTIATE_TEST_SUITE_P(DefaultClips, Contact,
                         ::testing::Values("walk", "trot", "canter", "gallop", "stop", "jump", "rear", "buck"));

}  // namespace
}  // namespace stirrup::rig
