// Riders stirrup has never seen, seated by the rig and ridden (rig/characters/seating.h): every test
// character (tests/rig/user_riders.h) on the trot, the canter and the jump, at every frame, measured in
// world space against the saddle, the treads, the reins and the default rider on the same frame:
//   seat   the point on the seat under her hip joints (where her seat bones were put at rest), in the
//          saddle's frame, within 3 cm of the default rider's;
//   feet   the sole under the ball of each foot within 3 cm of its tread (rig::stirrupTarget);
//   hands  where each hand closes (the Hand role) within 3 cm of where the rig asks for it (the rein
//          grip at rest moved by the wrist channels, in the saddle's frame);
//   legs   no vertex of her legs more than 2 cm inside the skinned horse (rig/contact_depth.h);
//   bones  every bone of her file within 1% of its length (or 0.02 cm for the shortest);
//   trunk  her pelvis-to-neck line's world lean within 3° of the default rider's.
#include "rig/characters/seating.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/blender_fixture.h"

#include "rig/bake.h"
#include "rig/balance.h"
#include "rig/contact_depth.h"
#include "rig/io/gltf_character.h"
#include "rig/loose_tack.h"
#include "rig/pose.h"
#include "rig/skin.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/ridden_pair.h"
#include "scene/scene.h"
#include "tests/rig/default_characters.h"
#include "tests/rig/user_riders.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

glm::vec3 at(const std::vector<glm::mat4>& w, int j) { return glm::vec3(w[j][3]); }
glm::vec3 inSaddle(const glm::mat4& saddle, glm::vec3 p) { return glm::vec3(glm::inverse(saddle) * glm::vec4(p, 1.0f)); }

// The seat point: on the seat under the hip joints' midpoint at rest, carried by the pelvis.
glm::vec3 seatPoint(const Character& rider, const std::vector<glm::mat4>& world) {
  const Skeleton& s = rider.skeleton;
  const int pelvis = rider.role("pelvis");
  glm::vec3 rest = 0.5f * (s.restPosition(rider.role("lHip")) + s.restPosition(rider.role("rHip")));
  rest.y = 0.0f;  // the seat centre's height: the rider is in saddle space at rest
  return glm::vec3(world[pelvis] * s.joints[pelvis].inverse_bind * glm::vec4(rest, 1.0f));
}

// Vertices of her legs: bound mostly to a joint at or below a hip.
std::vector<bool> legVertices(const Character& rider) {
  const Skeleton& s = rider.skeleton;
  std::vector<bool> leg_joint(s.size(), false);
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int p = s.joints[j].parent;
    leg_joint[j] = static_cast<int>(j) == rider.role("lHip") || static_cast<int>(j) == rider.role("rHip") || (p >= 0 && leg_joint[p]);
  }
  std::vector<bool> out(rider.mesh.vertexCount(), false);
  for (std::size_t v = 0; v < out.size(); ++v) {
    int best = 0;
    for (int k = 1; k < 4; ++k)
      if (rider.mesh.weights[v][k] > rider.mesh.weights[v][best]) best = k;
    out[v] = leg_joint[rider.mesh.joints[v][best]];
  }
  return out;
}

struct Worst {
  double seat = 0, feet = 0, hands = 0, legs = 0, bones = 0, lean = 0;
  int frames = 0, out_of_reach = 0;  // hands the rig asked beyond her arms' reach
  std::string deepest;  // where the deepest leg vertex was: its joint, the frame and its place in the saddle's frame
};

class SeatedUserRider : public ::testing::TestWithParam<test::UserRiderSpec> {};

// The balance proportions the seating scales a rider's support lean by are the generated rider's.
TEST(SeatRider, TheReferenceBalanceProportionsAreTheGeneratedRidersOnTheGeneratedMount) {
  const Character& rider = test::defaultRider();
  const Character& horse = test::defaultHorse();
  EXPECT_NEAR(trunkComHeight(rider), kReferenceComHeightCm, 0.05);
  const glm::vec3 seat = horse.skeleton.restPosition(horse.role("saddle"));
  const float hips = 0.5f * (rider.skeleton.restPosition(rider.role("lHip")).y + rider.skeleton.restPosition(rider.role("rHip")).y);
  const float tread = horse.skeleton.restPosition(horse.role("lStirrup")).y - seat.y;
  EXPECT_NEAR(hips - tread, kReferenceHipsToTreadCm, 0.05);  // the rider is built in saddle space: hips above the seat centre
}

// Seats the rider in `glb` (through `mapping`, or mapped by itself when it is empty) on the default
// horse and checks every frame of the trot, the canter and the jump (the header comment).
void ridesSeated(const std::string& name, const fs::path& glb, const fs::path& mapping) {
  const Character& horse0 = test::defaultHorse();
  const Character& default_rider = test::defaultRider();
  const RigProfile profile = RigProfile::thesis();
  const scene::RiddenPair pair = scene::seatPair(horse0, resolveCharacter(CharacterKind::Rider, glb.string(), mapping.string()), profile);
  const Character& horse = pair.horse;
  const Character& rider = pair.rider;
  ASSERT_TRUE(pair.seat.seated_by_rig) << name;
  std::printf("%s: stature %.1f cm, leg %.1f, seat depth %.1f, tread %.1f below the seat (%+.1f cm against the horse's), "
              "knees out %.0f deg, treads out %.1f cm, hands short %.1f cm\n",
              name.c_str(), pair.seat.stature_cm, pair.seat.leg_cm, pair.seat.seat_depth_cm, pair.seat.tread_below_seat_cm,
              pair.seat.leather_change_cm, pair.seat.knee_turn_out_deg, pair.seat.tread_out_cm, pair.seat.hand_shortfall_cm);
  for (const std::string& n : pair.seat.notes) std::printf("  note: %s\n", n.c_str());
  std::printf("  trunk's centre of mass %.1f cm above her hips (the default rider's %.1f)\n", trunkComHeight(rider), trunkComHeight(default_rider));

  const Skeleton& s = rider.skeleton;
  const std::vector<bool> legs = legVertices(rider);
  const std::vector<bool> tack = horseLooseTack(horse);
  std::vector<glm::vec3> hp, hn, rp, rn;
  const std::vector<glm::vec3> rest_grip = {s.restPosition(rider.role("lHand")), s.restPosition(rider.role("rHand"))};
  const std::vector<glm::vec3> rest_wrist = {s.restPosition(rider.role("lWrist")), s.restPosition(rider.role("rWrist"))};
  const RiderPoseParams pose_params;
  for (const char* clip_name : {"trot", "canter", "jump"}) {
    const scene::SceneSpec scene = scene::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/" + clip_name + ".json");
    const auto clip = scene::makeClip(scene.clip);
    Worst w;
    for (int f : scene::parseFrameList(scene.frames, "frames")) {
      const BakedFrame b = bakeFrame(*clip, profile, f, scene::frameTime(scene, f));
      const MountedPose p = poseMounted(horse, rider, b.horse, b.rider, profile);
      const MountedPose d = poseMounted(horse0, default_rider, b.horse, b.rider, profile);
      const glm::mat4& saddle = p.horse[horse.role("saddle")];
      const glm::mat4& saddle_d = d.horse[horse0.role("saddle")];
      ++w.frames;
      // Seat.
      const double seat = glm::length(inSaddle(saddle, seatPoint(rider, p.rider)) - inSaddle(saddle_d, seatPoint(default_rider, d.rider)));
      w.seat = std::max(w.seat, seat);
      EXPECT_LE(seat, 3.0) << clip_name << " frame " << f << ": seat";
      // Feet and hands.
      const RiderChannels r = limitRiderChannels(b.rider, pose_params, profile.rider_unit_cm);
      for (int side = 0; side < 2; ++side) {
        const std::string n = side == 0 ? "l" : "r";
        const double foot = glm::length(at(p.rider, rider.role(n + "Ball")) - stirrupTarget(horse, p.horse, r, profile.rider_unit_cm, side));
        w.feet = std::max(w.feet, foot);
        EXPECT_LE(foot, 3.0) << clip_name << " frame " << f << ": " << n << " foot";
        const float u = float(profile.rider_unit_cm);
        const glm::vec3 offset(float(r[side == 0 ? RiderChannel::lWristTx : RiderChannel::rWristTx]) * u,
                               float(r[side == 0 ? RiderChannel::lWristTy : RiderChannel::rWristTy]) * u, 0.0f);
        const glm::vec3 asked = glm::vec3(saddle * glm::vec4(rest_grip[side] + offset, 1.0f));
        const double hand = glm::length(at(p.rider, rider.role(n + "Hand")) - asked);
        // Where the rig asks for a wrist her arm cannot reach (the default rider's hands fall 10.5 cm
        // short on the jump's landing), the arm reaches straight for it: the wrist on the line from the
        // shoulder to its target, the arm at its full length (less the IK's softening).
        const glm::vec3 shoulder = at(p.rider, rider.role(n + "Shoulder")), wrist = at(p.rider, rider.role(n + "Wrist"));
        const glm::vec3 wrist_asked = glm::vec3(saddle * glm::vec4(rest_wrist[side] + offset, 1.0f));
        const double arm = glm::length(s.restPosition(rider.role(n + "Elbow")) - s.restPosition(rider.role(n + "Shoulder"))) +
                           glm::length(s.restPosition(rider.role(n + "Wrist")) - s.restPosition(rider.role(n + "Elbow")));
        if (glm::length(wrist_asked - shoulder) > arm) {
          ++w.out_of_reach;
          const glm::vec3 toward = glm::normalize(wrist_asked - shoulder);
          const double off_line = glm::length((wrist - shoulder) - toward * glm::dot(wrist - shoulder, toward));
          EXPECT_LE(off_line, 1.5) << clip_name << " frame " << f << ": " << n << " arm not reaching straight for its target";
          EXPECT_GE(glm::length(wrist - shoulder), arm - pose_params.limb_soften - 0.5) << clip_name << " frame " << f << ": " << n << " arm";
        } else {
          w.hands = std::max(w.hands, hand);
          EXPECT_LE(hand, 3.0) << clip_name << " frame " << f << ": " << n << " hand";
        }
      }
      // Bones.
      for (std::size_t j = 0; j < s.size(); ++j) {
        const int parent = s.joints[j].parent;
        if (parent < 0 || s.joints[j].rig_point || s.joints[j].file_root) continue;
        const double rest = glm::length(s.restPosition(int(j)) - s.restPosition(parent));
        const double now = glm::length(at(p.rider, int(j)) - at(p.rider, parent));
        const double off = std::abs(now - rest);
        w.bones = std::max(w.bones, rest > 0 ? off / rest : 0.0);
        EXPECT_LE(off, std::max(0.01 * rest, 0.02)) << clip_name << " frame " << f << ": bone " << s.joints[j].name;
      }
      // Trunk.
      const glm::vec3 heading = saddleHeading(saddle);
      const double lean = leanDegrees(at(p.rider, rider.role("neck")) - at(p.rider, rider.role("pelvis")), heading);
      const double lean_d = leanDegrees(at(d.rider, default_rider.role("neck")) - at(d.rider, default_rider.role("pelvis")), heading);
      w.lean = std::max(w.lean, std::abs(lean - lean_d));
      EXPECT_LE(std::abs(lean - lean_d), 3.0) << clip_name << " frame " << f << ": trunk lean " << lean << " against the default rider's " << lean_d;
      // Legs in the horse.
      skinMesh(horse.mesh, horse.skeleton, p.horse, hp, hn);
      skinMesh(rider.mesh, rider.skeleton, p.rider, rp, rn);
      std::vector<glm::vec3> leg_points;
      std::vector<std::size_t> leg_vertex;
      for (std::size_t v = 0; v < rp.size(); ++v)
        if (legs[v]) leg_points.push_back(rp[v]), leg_vertex.push_back(v);
      const ContactDepth c = deepestRiderVertexInside(hp, hn, horse.mesh.indices, tack, leg_points);
      if (c.depth_cm > w.legs) {
        w.legs = c.depth_cm;
        const std::size_t v = leg_vertex[c.vertex];
        int best = 0;
        for (int k = 1; k < 4; ++k)
          if (rider.mesh.weights[v][k] > rider.mesh.weights[v][best]) best = k;
        const glm::vec3 q = inSaddle(saddle, rp[v]);
        std::size_t near = 0;
        for (std::size_t k = 1; k < hp.size(); ++k)
          if (glm::length(hp[k] - rp[v]) < glm::length(hp[near] - rp[v])) near = k;
        int hb = 0;
        for (int k = 1; k < 4; ++k)
          if (horse.mesh.weights[near][k] > horse.mesh.weights[near][hb]) hb = k;
        const glm::vec3 hq = inSaddle(saddle, hp[near]);
        char where[240];
        std::snprintf(where, sizeof where, "%s, frame %d, at (%.0f, %.0f, %.0f) in the saddle's frame; horse %s at (%.0f, %.0f, %.0f)",
                      s.joints[rider.mesh.joints[v][best]].name.c_str(), f, q.x, q.y, q.z,
                      horse.skeleton.joints[horse.mesh.joints[near][hb]].name.c_str(), hq.x, hq.y, hq.z);
        w.deepest = where;
      }
      EXPECT_LE(c.depth_cm, 2.0) << clip_name << " frame " << f << ": a leg vertex inside the horse";
    }
    std::printf("  %-6s %3d frames: seat %.2f cm, feet %.2f cm, hands %.2f cm (%d beyond reach), legs %.2f cm deep (%s), bones %.3f%%, "
                "lean %.2f deg\n", clip_name, w.frames, w.seat, w.feet, w.hands, w.out_of_reach, w.legs, w.deepest.c_str(), 100.0 * w.bones, w.lean);
    if (::testing::Test::HasFailure()) return;  // one clip's failures say enough
  }
}

TEST_P(SeatedUserRider, RidesTrotCanterAndJumpSeatedWithFeetInTheStirrupsAndHandsOnTheReins) {
  const test::UserRiderSpec& spec = GetParam();
  const test::UserRiderFiles files = test::writeUserRider(spec, fs::path(STIRRUP_BINARY_DIR) / "test_seating");
  ridesSeated(spec.name, files.glb, files.mapping);
}

// Blender's own Rigify human (tests/blender/rigify-rider: Rigify's meta-rig and the rig it generates,
// a skinned body, Blender's glTF exporter: 160 DEF- bones, limbs and face roots of their own), with no
// mapping: stirrup maps it by itself, seats it and rides it as the generated test characters.
TEST(SeatedBlenderRigifyRider, MappedByItselfRidesTrotCanterAndJumpSeated) {
  if (!stirrup::test::blenderInstalled())
    GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy): Blender's Rigify rider is not made";
  stirrup::test::BlenderMade made;
  const fs::path glb = stirrup::test::blenderRigifyRider(&made);
  ASSERT_TRUE(made.ok) << made.log;
  ridesSeated("blender_rigify", glb, "");
}

INSTANTIATE_TEST_SUITE_P(TestCharacters, SeatedUserRider, ::testing::ValuesIn(test::userRiderSpecs()),
                         [](const ::testing::TestParamInfo<test::UserRiderSpec>& i) { return i.param.name; });

}  // namespace
}  // namespace stirrup::rig
