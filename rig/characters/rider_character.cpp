#include "rig/characters/rider_character.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "rig/characters/implicit_body.h"
#include "rig/characters/joint_placement.h"
#include "rig/characters/torso_weights.h"
#include "rig/ik.h"

namespace stirrup::rig {
namespace {

// The middle joint of a limb at rest: the same IK the posing job runs, so rest is reproduced exactly.
glm::vec3 restMiddle(glm::vec3 root, glm::vec3 end, float upper, float lower, glm::vec3 pole_dir) {
  TwoBoneIkInput in;
  in.root = root;
  in.target = end;
  in.upper_length = upper;
  in.lower_length = lower;
  in.pole = 0.5f * (root + end) + glm::normalize(pole_dir) * 50.0f;
  return solveTwoBoneIk(in).middle;
}

// The chain of equal bones buildRiderTrunk lays up from the lower back, which the torso is skinned to.
struct RiderChain {
  std::array<int, kRiderSpineSegments + 1> joints{};
  float y0 = 0.0f, bone = 0.0f;
  // The chain joint nearest a height: where a primitive or a child at that height hangs.
  int at(float y) const {
    const int i = static_cast<int>(std::lround((y - y0) / bone));
    return joints[std::clamp(i, 0, kRiderSpineSegments)];
  }
};

RiderChain riderChain(const Character& c, const RiderParams& p) {
  constexpr int kN = kRiderSpineSegments;
  RiderChain chain;
  chain.y0 = p.lower_back.y;
  chain.bone = (p.upper_chest.y - p.lower_back.y) / kN;
  for (int i = 0; i <= kN; ++i) chain.joints[i] = c.role("spine" + std::to_string(i));
  return chain;
}

// The joints the hair channels swing (the braid down the back of the head) and the coat's tail.
struct RiderHangingJoints {
  int braid1 = -1, braid2 = -1, braid3 = -1, coat_tail = -1;
  glm::vec3 braid_root{0.0f}, braid_dir{0.0f};
};

RiderHangingJoints addRiderHangingJoints(Character& c, const RiderParams& p, const RiderChain& chain, int head,
                                         glm::vec3 skull) {
  Skeleton& s = c.skeleton;
  RiderHangingJoints h;
  h.braid_root = skull + glm::vec3(-8.5f, -2.0f, 0.0f);
  h.braid_dir = glm::normalize(glm::vec3(-0.15f, -1.0f, 0.0f));
  h.braid1 = addJointAt(s, "braid1", head, h.braid_root);
  h.braid2 = addJointAt(s, "braid2", h.braid1, h.braid_root + h.braid_dir * (p.braid_length / 3.0f));
  h.braid3 = addJointAt(s, "braid3", h.braid2, h.braid_root + h.braid_dir * (2.0f * p.braid_length / 3.0f));
  h.coat_tail = addJointAt(s, "coatTail", chain.at(p.waist.y), p.waist + glm::vec3(-10.0f, -4.0f, 0.0f));
  for (const auto& [role, j] : {std::pair{"braid1", h.braid1}, {"braid2", h.braid2}, {"braid3", h.braid3}, {"coatTail", h.coat_tail}})
    c.roles[role] = j;
  return h;
}

// Torso: coat over the chest and waist, breeches over the hips.
void addRiderTorso(ImplicitBody& body, const RiderParams& p, int pelvis, const RiderChain& chain) {
  body.add(ellipsoid(p.pelvis + glm::vec3(-0.5f, 0.0f, 0.0f), p.hips_radii, pelvis, p.breeches, 4.0f));
  // (Each is attached to the chain joint at its height; spreadTorsoWeights then spreads the torso's
  // share of every vertex's weight along the chain.)
  body.add(ellipsoid(p.lower_back + glm::vec3(1.0f, 3.0f, 0.0f), {10.5f, 9.0f, p.waist_radius + 1.0f},
                     chain.at(p.lower_back.y + 3.0f), p.coat, 6.0f));
  body.add(ellipsoid(p.waist + glm::vec3(1.0f, 2.0f, 0.0f), {9.5f, 9.0f, p.waist_radius}, chain.at(p.waist.y + 2.0f),
                     p.coat, 6.0f));
  body.add(ellipsoid(p.chest + glm::vec3(1.0f, 3.0f, 0.0f), p.chest_radii, chain.at(p.chest.y + 3.0f), p.coat, 6.0f));
  body.add(ellipsoid(p.upper_chest + glm::vec3(-0.5f, 1.0f, 0.0f), {9.0f, 6.5f, 18.5f}, chain.joints[kRiderSpineSegments],
                     p.coat, 5.0f));
}

// Neck and head: skull, jaw, nose, eyes and ears, the hair's cap and back.
void addRiderHead(ImplicitBody& body, const RiderParams& p, int neck, int head, glm::vec3 skull) {
  body.add(taperedCapsule(p.neck + glm::vec3(0.0f, -2.0f, 0.0f), p.head + glm::vec3(0.5f, 3.0f, 0.0f), 5.6f, 5.0f,
                          neck, p.skin, 3.0f));
  body.add(ellipsoid(skull, {10.0f, 11.5f, 8.6f}, head, p.skin, 3.0f));
  body.add(ellipsoid(p.head + glm::vec3(4.0f, 4.0f, 0.0f), {6.5f, 5.5f, 6.0f}, head, p.skin, 4.0f));
  body.add(taperedCapsule(skull + glm::vec3(8.5f, 1.0f, 0.0f), skull + glm::vec3(10.8f, -2.5f, 0.0f), 1.3f, 1.7f, head,
                          p.skin, 1.5f));
  for (float side : {-1.0f, 1.0f}) {
    body.add(ellipsoid(skull + glm::vec3(8.6f, 2.5f, 3.3f * side), glm::vec3(1.1f), head, p.eyes, 0.3f));
    body.add(ellipsoid(skull + glm::vec3(-0.5f, 0.0f, 8.4f * side), {2.0f, 3.0f, 1.2f}, head, p.skin, 1.0f));
  }
  ImplicitPrimitive cap = ellipsoid(skull + glm::vec3(-1.2f, 1.2f, 0.0f), {10.6f, 11.8f, 9.3f}, head, p.hair, 0.6f);
  cap.clip_min.y = skull.y + 3.0f;
  body.add(cap);
  ImplicitPrimitive back_hair = ellipsoid(skull + glm::vec3(-3.0f, -1.0f, 0.0f), {8.5f, 10.5f, 9.2f}, head, p.hair, 0.6f);
  back_hair.clip_max.x = skull.x - 3.0f;
  body.add(back_hair);
}

// The braid (three tapering segments that the hair channels swing) and the coat's tail, draped over the
// cantle behind the seat.
void addRiderBraidAndSkirt(ImplicitBody& body, const Skeleton& s, const RiderParams& p, const RiderHangingJoints& h) {
  const glm::vec3 b1 = s.restPosition(h.braid1), b2 = s.restPosition(h.braid2), b3 = s.restPosition(h.braid3);
  const glm::vec3 btip = h.braid_root + h.braid_dir * p.braid_length;
  body.add(taperedCapsule(b1, b2, p.braid_radius, p.braid_radius * 0.9f, h.braid1, p.hair, 1.5f));
  body.add(taperedCapsule(b2, b3, p.braid_radius * 0.9f, p.braid_radius * 0.75f, h.braid2, p.hair, 1.0f));
  body.add(taperedCapsule(b3, btip, p.braid_radius * 0.75f, p.braid_radius * 0.5f, h.braid3, p.hair, 1.0f));
  const glm::vec3 ct = s.restPosition(h.coat_tail);
  // A shell around the hips cut to its back half: the coat's skirt, lying over the seat's back.
  ImplicitPrimitive skirt = ellipsoid(p.pelvis + glm::vec3(-0.5f, 4.0f, 0.0f), p.hips_radii + glm::vec3(1.5f, 4.0f, 1.5f),
                                      h.coat_tail, p.coat, 1.0f);
  skirt.clip_max = glm::vec3(p.pelvis.x - 4.0f, ct.y + 2.0f, 1e3f);
  skirt.clip_min.y = ct.y - p.coat_tail_length;
  body.add(skirt);
}

// One side's arm and leg, joints and body: the wrist at the rein, the ball of the foot on the stirrup.
// The parameters describe the left side (z < 0); `side` -1 is the left, +1 the right.
void addRiderLimbs(Character& c, ImplicitBody& body, const RiderParams& p, const MountParams& mount, float side, int pelvis,
                   int upper_chest) {
  Skeleton& s = c.skeleton;
  const std::string n = side < 0 ? "l" : "r";
  const float m = -side;  // mirror factor applied to left-side parameters
  // Arm: shoulder -> elbow -> wrist, the wrist at the rein.
  const glm::vec3 shoulder = mirrorZ(p.shoulder, m);
  const glm::vec3 wrist = mirrorZ(mount.rein_grip + p.wrist_from_grip, m);
  const glm::vec3 elbow = restMiddle(shoulder, wrist, p.upper_arm, p.forearm, mirrorZ(p.elbow_pole_dir, m));
  const int j_shoulder = addJointAt(s, n + "Shoulder", upper_chest, shoulder);
  const int j_elbow = addJointAt(s, n + "Elbow", j_shoulder, elbow);
  const int j_wrist = addJointAt(s, n + "Wrist", j_elbow, wrist);
  const int j_hand = addJointAt(s, n + "Hand", j_wrist, mirrorZ(mount.rein_grip, m));
  // Leg: hip -> knee -> ankle, the ball of the foot on the stirrup tread.
  const glm::vec3 hip = mirrorZ(p.hip, m);
  const glm::vec3 ball = mirrorZ(mount.stirrup, m);
  const glm::vec3 ankle = ball + mirrorZ(p.ankle_from_ball, m);
  const glm::vec3 knee = restMiddle(hip, ankle, p.thigh, p.shin, mirrorZ(p.knee_pole_dir, m));
  const int j_hip = addJointAt(s, n + "Hip", pelvis, hip);
  const int j_knee = addJointAt(s, n + "Knee", j_hip, knee);
  const int j_ankle = addJointAt(s, n + "Ankle", j_knee, ankle);
  const int j_ball = addJointAt(s, n + "Ball", j_ankle, ball);
  for (const auto& [role, j] : {std::pair{"Shoulder", j_shoulder}, {"Elbow", j_elbow}, {"Wrist", j_wrist}, {"Hand", j_hand},
                                {"Hip", j_hip}, {"Knee", j_knee}, {"Ankle", j_ankle}, {"Ball", j_ball}})
    c.roles[n + role] = j;

  const glm::vec3 out(0.0f, 0.0f, side);
  body.add(ellipsoid(shoulder + glm::vec3(0.0f, 0.5f, -1.5f * side), {6.0f, 5.5f, 6.0f}, j_shoulder, p.coat, 4.0f));
  body.add(taperedCapsule(shoulder, elbow, p.shoulder_radius, 4.2f, j_shoulder, p.coat, 3.0f));
  body.add(taperedCapsule(elbow, wrist, 4.2f, p.wrist_radius, j_elbow, p.coat, 2.0f));
  const glm::vec3 fwd = glm::normalize(wrist - elbow);
  body.add(ellipsoid(wrist + fwd * 4.5f + glm::vec3(0.0f, -0.5f, 0.0f), {5.0f, 3.8f, 2.8f}, j_wrist, p.skin, 2.0f,
                     fwd));
  body.add(taperedCapsule(wrist + fwd * 5.0f + out * 1.5f, wrist + fwd * 5.0f + glm::vec3(0.0f, 3.0f, 0.0f) + out * 1.5f,
                          1.2f, 1.1f, j_wrist, p.skin, 1.5f));  // thumb on top of the rein

  body.add(taperedCapsule(hip + glm::vec3(0.0f, 0.0f, 1.0f * side), knee, p.thigh_radius, p.knee_radius, j_hip,
                          p.breeches, 4.0f));
  const glm::vec3 boot_top = knee + (ankle - knee) * 0.12f;
  body.add(taperedCapsule(knee, boot_top, p.knee_radius, p.knee_radius, j_knee, p.breeches, 2.0f));
  body.add(taperedCapsule(boot_top, ankle, p.calf_radius + 0.4f, p.ankle_radius + 0.4f, j_knee, p.boots, 1.0f));
  const glm::vec3 heel = ankle + glm::vec3(-3.0f, -4.0f, 0.0f);
  const glm::vec3 toe = ball + glm::vec3(7.0f, 3.3f, 0.0f);
  ImplicitPrimitive foot = taperedCapsule(heel, toe, 4.2f, 3.4f, j_ankle, p.boots, 2.0f);
  body.add(foot);
}

}  // namespace

Character buildRiderTrunk(const RiderParams& p) {
  Character c;
  c.name = "rider";
  Skeleton& s = c.skeleton;
  const int pelvis = addJointAt(s, "pelvis", -1, p.pelvis);
  // The curve spine's FK controllers, straight up from the lower back (the curve spine's rest pose),
  // then the chain of equal bones the torso is skinned to, over the same length.
  const auto above_lower_back = [&](float y) { return glm::vec3(p.lower_back.x, y, p.lower_back.z); };
  const int lower_back = addJointAt(s, "lowerBack", pelvis, p.lower_back);
  const int waist = addJointAt(s, "waist", lower_back, above_lower_back(p.waist.y));
  const int chest = addJointAt(s, "chest", waist, above_lower_back(p.chest.y));
  constexpr int kN = kRiderSpineSegments;
  const float chain_bone = (p.upper_chest.y - p.lower_back.y) / kN;
  std::array<int, kN + 1> chain{};
  for (int i = 0; i <= kN; ++i)
    chain[i] = addJointAt(s, i == kN ? std::string("upperChest") : "spine" + std::to_string(i), i == 0 ? pelvis : chain[i - 1],
                          above_lower_back(p.lower_back.y + chain_bone * static_cast<float>(i)));
  const int neck = addJointAt(s, "neck", chain[kN], p.neck);
  const int head = addJointAt(s, "head", neck, p.head);
  c.roles = {{"pelvis", pelvis}, {"lowerBack", lower_back}, {"waist", waist}, {"chest", chest},
             {"upperChest", chain[kN]}, {"neck", neck}, {"head", head}};
  for (int i = 0; i <= kN; ++i) c.roles["spine" + std::to_string(i)] = chain[i];
  return c;
}

Character buildRider(const RiderParams& p, const MountParams& mount) {
  Character c = buildRiderTrunk(p);
  ImplicitBody body;

  const int pelvis = c.role("pelvis");
  const RiderChain chain = riderChain(c, p);
  const int upper_chest = chain.joints[kRiderSpineSegments];
  const int neck = c.role("neck"), head = c.role("head");
  const glm::vec3 skull = p.head + glm::vec3(1.5f, p.head_height * 0.45f, 0.0f);  // cranium centre
  const RiderHangingJoints hanging = addRiderHangingJoints(c, p, chain, head, skull);

  addRiderTorso(body, p, pelvis, chain);
  addRiderHead(body, p, neck, head, skull);
  addRiderBraidAndSkirt(body, c.skeleton, p, hanging);
  for (float side : {-1.0f, 1.0f}) addRiderLimbs(c, body, p, mount, side, pelvis, upper_chest);

  PolygonizeParams poly;
  poly.cell = p.cell;
  poly.skin_falloff = 2.0f;
  c.mesh = polygonize(body, poly);
  TorsoChain torso;  // bones evenly spaced up from the lower back
  torso.joints = chain.joints;
  torso.y0 = p.lower_back.y;
  torso.bone = chain.bone;
  spreadTorsoWeights(c.mesh, torso);
  groupTrianglesByColor(c.mesh);
  return c;
}

Character buildDefaultRider() { return buildRider(RiderParams{}, HorseParams{}.mount); }

}  // namespace stirrup::rig
