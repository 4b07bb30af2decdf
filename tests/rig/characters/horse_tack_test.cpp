// Tack for a horse without any (rig/characters/horse_tack.h):
//  * the generated horse built bare (HorseParams::tack = false) gets its saddle where the generator puts
//    its own: the seat centre 30% of the way from the withers to the hips, 6 cm over the barrel's top
//    there (worked from the generator's parameters: the barrel ellipsoid's top at x = 10), the treads
//    74 cm below it at the barrel's sides, the rein ends at the generated rider's grips, a bit at the
//    mouth; the leathers, irons and reins separate pieces a rider's legs and hands may touch;
//  * the Khronos Fox as a horse through a mapping that names no tack (scenes/fox/fox-horse-mapping.json)
//    rides the default rider's trot: every frame her seat within 3 cm of where it is on the generated
//    horse (in the saddle's frame), her feet on the treads, no leg vertex more than 2 cm inside the
//    horse, every bone of the Fox keeping its length.
#include "rig/characters/horse_tack.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rig/bake.h"
#include "rig/characters/seating.h"
#include "rig/contact_depth.h"
#include "rig/io/gltf_character.h"
#include "rig/loose_tack.h"
#include "rig/mapping/character_mapping.h"
#include "rig/pose.h"
#include "rig/skin.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/ridden_pair.h"
#include "scene/scene.h"
#include "tests/input_error.h"
#include "tests/rig/default_characters.h"
#include "tests/rig/tack_labels.h"
#include "tests/rig/user_riders.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;

glm::vec3 at(const std::vector<glm::mat4>& w, int j) { return glm::vec3(w[j][3]); }
glm::vec3 inSaddle(const glm::mat4& saddle, glm::vec3 p) { return glm::vec3(glm::inverse(saddle) * glm::vec4(p, 1.0f)); }

Character bareHorse() {
  HorseParams p;
  p.tack = false;
  return buildHorse(p);
}

TEST(HorseTack, ABareHorseGetsItsSaddleWhereTheGeneratorPutsIt) {
  Character horse = bareHorse();
  for (const char* role : kHorseTackRoles) ASSERT_EQ(horse.roles.count(role), 0u) << role;
  const std::size_t bare_vertices = horse.mesh.vertexCount(), bare_joints = horse.skeleton.size();
  const HorseTackReport r = addHorseTack(horse, "bare.glb");
  ASSERT_TRUE(r.added);
  const HorseParams p;
  // The generator's seat: x = saddle_x (10), on the barrel ellipsoid's top there, + saddle_seat_height.
  const float bx = (p.saddle_x - p.barrel_center.x) / p.barrel_radii.x;
  const glm::vec3 seat{p.saddle_x, p.barrel_center.y + p.barrel_radii.y * std::sqrt(1.0f - bx * bx) + p.saddle_seat_height, 0.0f};
  const Skeleton& s = horse.skeleton;
  const glm::vec3 got = s.restPosition(horse.role("saddle"));
  EXPECT_NEAR(got.x, seat.x, 0.5f);
  EXPECT_NEAR(got.z, 0.0f, 1e-4f);
  EXPECT_NEAR(got.y, seat.y, 2.0f);  // the mesh's top (smoothly blended shapes) against the ellipsoid's
  EXPECT_NEAR(r.back_top_y, seat.y - p.saddle_seat_height, 2.0f);
  // It hangs from the back joint carrying the barrel (the generator hangs its saddle there too).
  EXPECT_EQ(s.joints[s.joints[horse.role("saddle")].parent].name, "backMid");
  // Treads: 74 cm below the seat, out from the barrel (25 cm half-width) by 6 cm: the generator's 31.
  for (int side = 0; side < 2; ++side) {
    const glm::vec3 t = s.restPosition(horse.role(side == 0 ? "lStirrup" : "rStirrup")) - got;
    EXPECT_NEAR(t.x, p.mount.stirrup.x, 1e-4f);
    EXPECT_NEAR(t.y, p.mount.stirrup.y, 1e-4f);
    EXPECT_NEAR(t.z, side == 0 ? p.mount.stirrup.z : -p.mount.stirrup.z, 1.5f) << side;
    const glm::vec3 g = s.restPosition(horse.role(side == 0 ? "lRein" : "rRein")) - got;
    EXPECT_LT(glm::length(g - glm::vec3(p.mount.rein_grip.x, p.mount.rein_grip.y, side == 0 ? p.mount.rein_grip.z : -p.mount.rein_grip.z)), 1e-4f);
  }
  // The bit: the generator's, muzzle + (-7, -2, -(muzzle radius + 0.5)), within 5 cm.
  const glm::vec3 bit = p.muzzle + glm::vec3(-7.0f, -2.0f, -(p.muzzle_radius + 0.5f));
  EXPECT_LT(glm::length(r.bit - bit), 5.0f) << r.bit.x << " " << r.bit.y << " " << r.bit.z;
  // Five rig points, and tack in the mesh.
  EXPECT_EQ(s.size(), bare_joints + 5);
  for (const char* role : kHorseTackRoles) EXPECT_TRUE(s.joints[horse.role(role)].rig_point) << role;
  ASSERT_GT(horse.mesh.vertexCount(), bare_vertices + 1000);
  // Leathers, irons and reins are pieces of their own bound to the stirrup and rein points; the seat is not.
  const std::vector<bool> loose = horseLooseTack(horse);
  std::array<int, 4> bound{};
  std::size_t loose_count = 0;
  for (std::size_t v = 0; v < horse.mesh.vertexCount(); ++v) {
    loose_count += loose[v];
    for (int k = 0; k < kMaxInfluences; ++k) {
      if (!(horse.mesh.weights[v][k] > 0.0f)) continue;
      const int j = horse.mesh.joints[v][k];
      for (int i = 0; i < 4; ++i)
        if (j == horse.role(std::array<const char*, 4>{"lStirrup", "rStirrup", "lRein", "rRein"}[i])) {
          ++bound[i];
          EXPECT_TRUE(loose[v]) << "vertex " << v;
        }
    }
  }
  for (int i = 0; i < 4; ++i) EXPECT_GT(bound[i], 20) << i;
  std::size_t seat_vertices = 0;
  for (std::size_t v = bare_vertices; v < horse.mesh.vertexCount(); ++v) {
    const glm::vec3 q = horse.mesh.positions[v];
    if (std::abs(q.z) < 3.0f && q.y > got.y - 1.0f && std::abs(q.x - got.x) < 10.0f) {
      ++seat_vertices;
      EXPECT_FALSE(loose[v]) << "seat vertex " << v;
    }
  }
  EXPECT_GT(seat_vertices, 0u);
  // The reins reach the head: the vertices bound to the head joint among the rein pieces.
  std::size_t at_head = 0;
  for (std::size_t v = bare_vertices; v < horse.mesh.vertexCount(); ++v)
    at_head += loose[v] && horse.mesh.joints[v][0] == horse.role("head") && horse.mesh.weights[v][0] > 0.5f;
  EXPECT_GT(at_head, 0u);
  // Its parts are labelled (the horse's own vertices the body), each with its colours and joints.
  test::expectTackLabelsFit(horse);
  for (std::size_t v = 0; v < horse.mesh.vertexCount(); ++v)
    ASSERT_EQ(horse.mesh.tackPart(v) == TackPart::None, v < bare_vertices) << "vertex " << v;
  // Again: the horse has its tack now, nothing more is added.
  const std::size_t with_tack = horse.mesh.vertexCount();
  EXPECT_FALSE(addHorseTack(horse, "bare.glb").added);
  EXPECT_EQ(horse.mesh.vertexCount(), with_tack);
}

TEST(HorseTack, ErrorsNameTheFileTheRolesAndTheJoints) {
  // No surface over the saddle's place (a mesh of no triangles here).
  Character bare = bareHorse();
  bare.mesh.indices.clear();
  EXPECT_EQ(stirrup::test::errorOf([&] { addHorseTack(bare, "my-horse.json"); }),
            "my-horse.json: no back to put a saddle on: the mesh has no surface over the midline at x = 10 cm, a saddle's place "
            "behind the withers (check roles root \"root\", neck1 \"neck1\", lfUpper \"lfElbow\" and rfUpper \"rfElbow\", or map "
            "the tack roles to joints of the horse's own)");
}

TEST(HorseTack, TackNamedInPartIsAnError) {
  Character horse = bareHorse();
  horse.roles["saddle"] = horse.role("backMid");
  horse.roles["lRein"] = horse.role("head");
  EXPECT_EQ(stirrup::test::errorOf([&] { addHorseTack(horse, "my-horse.json"); }),
            "my-horse.json: roles.lStirrup: missing (the horse's saddle, lRein mapped: expected all five tack roles, saddle, "
            "lStirrup, rStirrup, lRein and rRein, or none, and the rig adds its own tack)");
}

// A horse modelled with its own saddle (here the generator's, its tack roles left unmapped, as a user's
// file whose saddle is a mesh of its own): the seat goes on that saddle, where the generator put its seat
// centre, within 2 cm, and no second saddle is added (only leathers, irons, bridle and reins: a few
// thousand vertices, against the generated saddle's tens of thousands).
TEST(HorseTack, AHorsesOwnSaddleIsSatOnNotSaddledAgain) {
  Character horse = buildHorse(HorseParams{});
  const glm::vec3 seat = horse.skeleton.restPosition(horse.role("saddle"));
  std::vector<char> own(horse.mesh.vertexCount(), 0);
  for (std::size_t v = 0; v < own.size(); ++v) {
    int best = 0;
    for (int k = 1; k < kMaxInfluences; ++k)
      if (horse.mesh.weights[v][k] > horse.mesh.weights[v][best]) best = k;
    own[v] = horse.mesh.joints[v][best] == horse.role("saddle");
  }
  for (const char* role : kHorseTackRoles) horse.roles.erase(role);
  horse.mesh.tack_parts.clear();  // a user's file labels no tack of stirrup's
  const std::size_t before = horse.mesh.vertexCount();
  const HorseTackReport r = addHorseTack(horse, "saddled.glb", HorseTackParams{}, &own);
  ASSERT_TRUE(r.added);
  EXPECT_TRUE(r.own_saddle);
  EXPECT_LT(glm::length(r.seat - seat), 2.0f) << "seat (" << r.seat.x << ", " << r.seat.y << ", " << r.seat.z << "), the generator's ("
                                              << seat.x << ", " << seat.y << ", " << seat.z << ")";
  EXPECT_LT(horse.mesh.vertexCount() - before, 8000u) << "vertices added";
  // Its own saddle is its own: only the parts the rig added are labelled, no saddle or pad among them.
  const std::map<TackPart, std::size_t> parts = test::tackPartCounts(horse.mesh);
  EXPECT_EQ(parts.count(TackPart::Saddle) + parts.count(TackPart::SaddlePad), 0u);
  EXPECT_EQ(parts.at(TackPart::None), before);
  for (TackPart part : {TackPart::Bridle, TackPart::Bit, TackPart::StirrupLeatherL, TackPart::StirrupIronR, TackPart::Reins})
    EXPECT_GT(parts.count(part), 0u) << tackPartName(part);
  Character bare = bareHorse();
  const std::size_t bare_before = bare.mesh.vertexCount();
  addHorseTack(bare, "bare.glb");
  EXPECT_GT(bare.mesh.vertexCount() - bare_before, 3 * (horse.mesh.vertexCount() - before)) << "the rig's own saddle is far more";
}

// The bit follows the head, whichever way the head points at rest: the generated horse built bare with
// its muzzle turned 30 degrees down about the poll (a head carried low, as a Rigify horse's head bone
// points), and 20 degrees up: the bit is where the level head's bit goes when turned the same way, within
// 3 cm.
TEST(HorseTack, TheBitFollowsTheHeadWhicheverWayItPoints) {
  Character level = bareHorse();
  const glm::vec3 level_bit = addHorseTack(level, "bare.glb").bit;
  for (const float turn : {-30.0f, 20.0f}) {
    HorseParams p;
    p.tack = false;
    const glm::mat3 r = glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(turn), glm::vec3(0.0f, 0.0f, 1.0f)));
    p.muzzle = p.poll + r * (p.muzzle - p.poll);
    Character horse = buildHorse(p);
    const glm::vec3 bit = addHorseTack(horse, "bare.glb").bit;
    const glm::vec3 expected = p.poll + r * (level_bit - p.poll);
    EXPECT_LT(glm::length(bit - expected), 3.0f) << turn << " degrees: bit (" << bit.x << ", " << bit.y << ", " << bit.z << "), expected ("
                                                 << expected.x << ", " << expected.y << ", " << expected.z << ")";
  }
}

// The reins clear a horse bulkier at the shoulders than a horse (the generated horse built bare with the
// base of its neck 60% thicker, 38 cm against 24): no rein vertex between the neck and the rider's hands
// inside the body. Reins drawn straight from the neck's side to the hands, as before, were 5.4 cm inside
// it on this horse.
TEST(HorseTack, TheReinsClearBulkyShoulders) {
  HorseParams p;
  p.tack = false;
  p.neck_base_radius *= 1.6f;
  Character horse = buildHorse(p);
  const std::size_t bare_vertices = horse.mesh.vertexCount();
  addHorseTack(horse, "bulky.glb");
  const std::vector<bool> loose = horseLooseTack(horse);
  std::vector<glm::vec3> hp, hn, reins;
  skinMesh(horse.mesh, horse.skeleton, restWorlds(horse.skeleton), hp, hn);
  const float neck_x = horse.skeleton.restPosition(horse.role("neck1")).x;
  for (std::size_t v = bare_vertices; v < hp.size(); ++v)
    if (loose[v] && hp[v].x < neck_x && hp[v].y > horse.skeleton.restPosition(horse.role("saddle")).y - 40.0f) reins.push_back(hp[v]);
  ASSERT_GT(reins.size(), 50u);
  std::vector<bool> body(loose.begin(), loose.end());
  const ContactDepth c = deepestRiderVertexInside(hp, hn, horse.mesh.indices, body, reins);
  EXPECT_LT(c.depth_cm, 0.2) << "a rein vertex inside the body";
}

// `rider` on `horse` through every frame of the trot (scenes/trot.json): her seat on the saddle (and,
// with `against_default_pair`, where the default rider's is on the generated horse, in the saddle's
// frame), her feet on the treads, no leg vertex more than 2 cm inside the horse, every bone of the
// horse's file its length.
void rideTheTrot(const Character& horse, const Character& rider, const std::string& who, bool against_default_pair,
                 const std::string& horse_name = "Fox") {
  const Character& horse0 = test::defaultHorse();
  const Character& rider0 = test::defaultRider();
  const RigProfile profile = RigProfile::thesis();
  const scene::SceneSpec scene = scene::loadScene(std::string(STIRRUP_SOURCE_DIR) + "/scenes/trot.json");
  const auto clip = scene::makeClip(scene.clip, horse);
  const auto clip0 = scene::makeClip(scene.clip);
  const std::vector<bool> tack = horseLooseTack(horse);
  const Skeleton& s = rider.skeleton;
  std::vector<bool> legs(rider.mesh.vertexCount(), false);
  {
    std::vector<bool> leg_joint(s.size(), false);
    for (std::size_t j = 0; j < s.size(); ++j) {
      const int p = s.joints[j].parent;
      leg_joint[j] = int(j) == rider.role("lHip") || int(j) == rider.role("rHip") || (p >= 0 && leg_joint[p]);
    }
    for (std::size_t v = 0; v < legs.size(); ++v) {
      int best = 0;
      for (int k = 1; k < 4; ++k)
        if (rider.mesh.weights[v][k] > rider.mesh.weights[v][best]) best = k;
      legs[v] = leg_joint[rider.mesh.joints[v][best]];
    }
  }
  const RiderPoseParams pose_params;
  double worst_seat = 0, worst_on_saddle = 0, worst_feet = 0, worst_legs = 0, worst_bone = 0;
  std::string deepest = "none inside";
  int frames = 0;
  std::vector<glm::vec3> hp, hn, rp, rn;
  for (int f : scene::parseFrameList(scene.frames, "frames")) {
    const BakedFrame b = bakeFrame(*clip, profile, f, scene::frameTime(scene, f));
    const BakedFrame b0 = bakeFrame(*clip0, profile, f, scene::frameTime(scene, f));
    const MountedPose p = poseMounted(horse, rider, b.horse, b.rider, profile);
    const MountedPose d = poseMounted(horse0, rider0, b0.horse, b0.rider, profile);
    ++frames;
    // Seat: her pelvis in the Fox's saddle frame where it is in the generated horse's.
    const glm::mat4& saddle = p.horse[horse.role("saddle")];
    const glm::mat4& saddle0 = d.horse[horse0.role("saddle")];
    if (against_default_pair) {
      const double seat_off = glm::length(inSaddle(saddle, at(p.rider, rider.role("pelvis"))) - inSaddle(saddle0, at(d.rider, rider0.role("pelvis"))));
      worst_seat = std::max(worst_seat, seat_off);
      EXPECT_LE(seat_off, 3.0) << who << ", frame " << f << ": seat";
    }
    // And on the generated saddle: the point of her seat under her hip joints (on the seat at rest) within
    // 6 cm of the saddle's seat centre: her hips sit 2 cm behind it (RiderParams::hip.x) and the trot's
    // cog channels move her up to 3 cm more (as on the generated horse).
    {
      glm::vec3 rest = 0.5f * (s.restPosition(rider.role("lHip")) + s.restPosition(rider.role("rHip")));
      rest.y = 0.0f;
      const int pelvis = rider.role("pelvis");
      const glm::vec3 seat_point = glm::vec3(p.rider[pelvis] * s.joints[pelvis].inverse_bind * glm::vec4(rest, 1.0f));
      const double on_saddle = glm::length(seat_point - at(p.horse, horse.role("saddle")));
      worst_on_saddle = std::max(worst_on_saddle, on_saddle);
      EXPECT_LE(on_saddle, 6.0) << who << ", frame " << f << ": seat off the saddle";
    }
    // Feet on the treads.
    const RiderChannels r = limitRiderChannels(b.rider, pose_params, profile.rider_unit_cm);
    for (int side = 0; side < 2; ++side) {
      const double foot = glm::length(at(p.rider, rider.role(side == 0 ? "lBall" : "rBall")) - stirrupTarget(horse, p.horse, r, profile.rider_unit_cm, side));
      worst_feet = std::max(worst_feet, foot);
      EXPECT_LE(foot, 3.0) << who << ", frame " << f << ": foot " << side;
    }
    // The Fox's bones keep their length (the rig's points are not bones).
    for (std::size_t j = 0; j < horse.skeleton.size(); ++j) {
      const int parent = horse.skeleton.joints[j].parent;
      if (parent < 0 || horse.skeleton.joints[j].rig_point) continue;
      const double rest = glm::length(horse.skeleton.restPosition(int(j)) - horse.skeleton.restPosition(parent));
      const double off = std::abs(glm::length(at(p.horse, int(j)) - at(p.horse, parent)) - rest);
      worst_bone = std::max(worst_bone, off);
      EXPECT_LE(off, std::max(0.01 * rest, 0.02)) << who << ", frame " << f << ": bone " << horse.skeleton.joints[j].name;
    }
    // Legs in the horse.
    skinMesh(horse.mesh, horse.skeleton, p.horse, hp, hn);
    skinMesh(rider.mesh, rider.skeleton, p.rider, rp, rn);
    std::vector<glm::vec3> leg_points;
    std::vector<std::size_t> leg_vertex;
    for (std::size_t v = 0; v < rp.size(); ++v)
      if (legs[v]) leg_points.push_back(rp[v]), leg_vertex.push_back(v);
    const ContactDepth c = deepestRiderVertexInside(hp, hn, horse.mesh.indices, tack, leg_points);
    if (c.depth_cm > worst_legs) {
      worst_legs = c.depth_cm;
      const glm::vec3 q = inSaddle(saddle, rp[leg_vertex[c.vertex]]);
      char where[160];
      std::snprintf(where, sizeof where, "frame %d, at (%.1f, %.1f, %.1f) in the saddle's frame", f, q.x, q.y, q.z);
      deepest = where;
    }
    EXPECT_LE(c.depth_cm, 2.0) << who << ", frame " << f << ": a leg vertex inside the horse";
  }
  std::printf("%s at the trot, %s, %d frames: seat %.2f cm from the default pair's, %.2f cm from the seat centre, feet %.2f cm, legs %.2f cm deep (%s), bones %.3f cm\n", horse_name.c_str(), who.c_str(), frames, worst_seat,
              worst_on_saddle, worst_feet, worst_legs, deepest.c_str(), worst_bone);
  EXPECT_EQ(frames, 72);
}

TEST(HorseTack, TheFoxWithoutTackRidesTheDefaultRidersTrot) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  const fs::path mapping = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "fox" / "fox-horse-mapping.json";
  const RigProfile profile = RigProfile::thesis();
  const scene::RiddenPair pair = scene::resolveRiddenPair(fox.string(), mapping.string(), "default", "", profile);
  const Character& horse = pair.horse;
  const Character& rider = pair.rider;
  const Character& horse0 = test::defaultHorse();
  for (const char* role : kHorseTackRoles) EXPECT_TRUE(horse.skeleton.joints[horse.role(role)].rig_point) << role;
  const glm::vec3 seat = horse.skeleton.restPosition(horse.role("saddle"));
  std::printf("Fox: saddle (%.1f, %.1f, %.1f) on %s; treads %.1f, %.1f cm out; %zu vertices, %zu triangles\n", seat.x, seat.y, seat.z,
              horse.skeleton.joints[horse.skeleton.joints[horse.role("saddle")].parent].name.c_str(),
              horse.skeleton.restPosition(horse.role("lStirrup")).z, horse.skeleton.restPosition(horse.role("rStirrup")).z,
              horse.mesh.vertexCount(), horse.mesh.triangleCount());
  // A horse's size: the seat about where the generated horse's is (157 cm), the mesh textured still.
  EXPECT_NEAR(seat.y, horse0.skeleton.restPosition(horse0.role("saddle")).y, 12.0f);
  EXPECT_TRUE(horse.mesh.textured());

  rideTheTrot(horse, rider, "default rider", true);
}

// A user's rider standing in her file's T-pose (tests/rig/user_riders.h, the Mixamo-named one) seated by
// the rig on the Fox's rig-made tack: the leathers set to her legs, her legs fitted against the Fox's
// barrel and saddle (seating reads the tack as any horse's: horseLooseTack leaves the irons, leathers and
// reins out of the surface her legs keep clear of).
TEST(HorseTack, AStandingUserRiderIsSeatedOnTheFoxsTackAndRidesTheTrot) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  const fs::path mapping = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "fox" / "fox-horse-mapping.json";
  const test::UserRiderSpec spec = test::userRiderSpecs().front();
  const test::UserRiderFiles files = test::writeUserRider(spec, fs::path(STIRRUP_BINARY_DIR) / "test_horse_tack");
  const scene::RiddenPair pair = scene::resolveRiddenPair(fox.string(), mapping.string(), files.glb.string(), files.mapping.string(), RigProfile::thesis());
  ASSERT_TRUE(pair.seat.seated_by_rig) << spec.name;
  std::printf("%s on the Fox: tread %.1f cm below the seat, knees out %.0f deg, treads out %.1f cm, hands short %.1f cm\n",
              spec.name.c_str(), pair.seat.tread_below_seat_cm, pair.seat.knee_turn_out_deg, pair.seat.tread_out_cm,
              pair.seat.hand_shortfall_cm);
  rideTheTrot(pair.horse, pair.rider, spec.name, false);
}

// The default rider, built seated for the generated horse, on a horse 22 cm wider in the barrel (a
// draught horse's 72 cm, barrel_radii.z 36 against 25) that has no tack of its own: the rig's treads hang out
// from its barrel, her feet are off them as built, so the rig fits her legs and arms to it as it seats a
// standing rider (her trunk kept), and she rides the trot with no leg vertex inside the horse. As built
// (not fitted) her knees and calves would be inside it: the check can fail.
TEST(HorseTack, TheDefaultRiderIsFittedToAWideHorse) {
  HorseParams params;
  params.tack = false;
  params.barrel_radii.z = 36.0f;
  Character horse = buildHorse(params);
  horse.source.file = "wide-horse.glb";  // a user's horse, as a file would give it
  addHorseTack(horse, "wide-horse.glb");
  const Character& rider = test::defaultRider();
  EXPECT_NE(seatedMisfit(rider, horse), "");
  EXPECT_EQ(seatedMisfit(rider, test::defaultHorse()), "") << "on the horse she was built for she fits as she is";
  const scene::RiddenPair pair = scene::seatPair(horse, rider, RigProfile::thesis());
  ASSERT_TRUE(pair.seat.fitted_to_horse);
  EXPECT_FALSE(pair.seat.seated_by_rig);
  // Her trunk as built: the pelvis and neck where the generated rider has them.
  for (const char* role : {"pelvis", "neck", "head"})
    EXPECT_LT(glm::length(pair.rider.skeleton.restPosition(pair.rider.role(role)) - rider.skeleton.restPosition(rider.role(role))), 1e-3f)
        << role;
  std::printf("default rider on a wide horse: tread %.1f cm below the seat, knees out %.0f deg, treads out %.1f cm\n",
              pair.seat.tread_below_seat_cm, pair.seat.knee_turn_out_deg, pair.seat.tread_out_cm);
  rideTheTrot(pair.horse, pair.rider, "default rider, fitted", true, "wide horse");
  // As built, on the same horse (the treads where the rig hung them): her legs inside it.
  const std::vector<glm::mat4> rider_rest = restWorlds(rider.skeleton), horse_rest = restWorlds(horse.skeleton);
  std::vector<glm::vec3> hp, hn, rp, rn;
  skinMesh(horse.mesh, horse.skeleton, horse_rest, hp, hn);
  skinMesh(rider.mesh, rider.skeleton, rider_rest, rp, rn);
  const glm::vec3 seat = horse.skeleton.restPosition(horse.role("saddle"));
  for (glm::vec3& q : rp) q += seat;  // she is built in saddle space
  const ContactDepth as_built = deepestRiderVertexInside(hp, hn, horse.mesh.indices, horseLooseTack(horse), rp);
  EXPECT_GT(as_built.depth_cm, 4.0) << "the unfitted rider's deepest vertex inside the wide horse";
}

}  // namespace
}  // namespace stirrup::rig
