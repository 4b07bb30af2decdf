#include "rig/rider_pose.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "rig/ik.h"
#include "rig/pose_transforms.h"
#include "rig/rider_spine.h"
#include "rig/skeleton.h"
#include "rig/tack_pose.h"

namespace stirrup::rig {
namespace {

using namespace pose_transforms;

// How far the neck turns back at most to counter the balance stage's turn: a choice, well inside the
// extension range of a neck, so the head never tips back past where a rider looking ahead holds it.
constexpr float kNeckCounterRangeDeg = 45.0f;
// The fold guard (Character::FoldGuard) finds the largest forward turn that keeps its room to this.
constexpr double kFoldGuardToleranceDeg = 0.1;

// A seated user rider's knee turned out about its hip-ankle line, the least that keeps the knee and two
// points of the calf (a quarter and half way down the shin) their radius and some room outside the
// horse's side (Character::LegGuard); where no turn is enough (the foot swung back and in against the
// flap), the foot also moves out in the iron, by at most kGuardFootOutCm. `away` is -1 on the left, +1
// on the right; `resolve(pole, foot_out)` solves the limb again toward a pole point (world) with the
// ankle's target moved out by foot_out (cm, saddle space).
constexpr float kGuardFootOutCm = 2.4f;  // within the iron's tread (11 cm wide)
// With it, the foot rises as much as two thirds of that in the iron (the leg bends a little more, so its
// knee can turn out): the sole stays within 3 cm of the tread's centre.
constexpr float kGuardFootUpPerOut = 2.0f / 3.0f;
template <class Resolve>
LimbPose guardLeg(const Character::LegGuard& g, const glm::mat4& saddle, float away, LimbPose limb, Resolve&& resolve) {
  const glm::mat4 to_saddle = glm::inverse(saddle);
  float foot_out = 0.0f;
  for (int pass = 0; pass < 4; ++pass) {
    const glm::vec3 hip = transformPoint(to_saddle, position(limb.upper)), knee = transformPoint(to_saddle, position(limb.middle));
    const glm::vec3 ankle = transformPoint(to_saddle, limb.end);
    // The knee's |z| each point needs: the knee itself, and the calf's points, which lie between the
    // knee and the ankle (whose place the tread fixes).
    float need = g.widthNear(knee.x, knee.y) + g.knee_radius_cm + g.room_cm;
    float worst_t = 0.0f;
    for (float t : {0.25f, 0.5f}) {
      const glm::vec3 c = glm::mix(knee, ankle, t);
      const float n = (g.widthNear(c.x, c.y) + g.calf_radius_cm + g.room_cm - t * ankle.z * away) / (1.0f - t);
      if (n > need) need = n, worst_t = t;
    }
    if (!(knee.z * away < need - 1e-3f)) break;
    const glm::vec3 axis = glm::normalize(ankle - hip);
    const glm::vec3 centre = hip + axis * glm::dot(knee - hip, axis);
    const float radius = glm::length(knee - centre);
    if (radius < 1e-3f) break;
    const glm::vec3 e1 = (knee - centre) / radius, e2 = glm::cross(axis, e1);
    // Out from the midline along the circle: (centre + radius (cos t e1 + sin t e2)).z * away; the
    // turn nearest t = 0 that reaches `need`, or the farthest out where none does.
    const float A = radius * e1.z * away, B = radius * e2.z * away, C = centre.z * away;
    const float R = std::sqrt(A * A + B * B);
    if (R < 1e-6f) break;
    const float phase = std::atan2(B, A);
    float t = phase;  // the farthest out
    if (need - C <= R) {
      const float d = std::acos(std::clamp((need - C) / R, -1.0f, 1.0f));
      const float t1 = std::remainder(phase - d, 2.0f * glm::pi<float>()), t2 = std::remainder(phase + d, 2.0f * glm::pi<float>());
      t = std::abs(t1) < std::abs(t2) ? t1 : t2;
    } else if (foot_out < kGuardFootOutCm) {
      // The calf's point t of the way down moves out t of what the ankle does; the knee needs the leg bent.
      foot_out = std::min(kGuardFootOutCm, foot_out + (need - C - R) * (worst_t > 0.0f ? (1.0f - worst_t) / worst_t : 1.0f));
    }
    const glm::vec3 k = centre + radius * (std::cos(t) * e1 + std::sin(t) * e2);
    limb = resolve(transformPoint(saddle, centre + (k - centre) * 10.0f), foot_out);
  }
  return limb;
}

}  // namespace

SpineControllers riderSpineControllers(const RiderChannels& r, const RiderPoseParams& params) {
  using C = RiderChannel;
  SpineControllers c;
  // Contract: lowerBack.rz + leans forward = the spine's +rz (toward +X); lowerBack.ry + leans to her
  // right = +ry (toward +Z); lowerBack.rx + twists the chest to her right = −rx about the bone's up.
  c.lower = {0.0, r[C::lowerBackRy], r[C::lowerBackRz]};
  c.middle = {0.0, 0.0, r[C::waistRz]};
  c.top = {-r[C::lowerBackRx], 0.0, r[C::waistRz] * params.chest_follow};
  return c;
}

double riderSpineStretch(const CurveSpine& spine, const RiderChannels& r, double rider_unit_cm) {
  using C = RiderChannel;
  const double offset = (r[C::spineCTy] + r[C::spineDTy] + r[C::spineFTy]) * rider_unit_cm;
  return std::max(spine.stretchForOffset(offset), kMinRiderSpineStretch);
}

void poseRiderSpine(const Character& rider, const RiderChannels& r, double rider_unit_cm,
                    const RiderPoseParams& params, std::span<glm::mat4> local) {
  const Skeleton& s = rider.skeleton;
  if (local.size() != s.size()) throw std::invalid_argument("poseRiderSpine: expected one matrix per joint");
  using C = RiderChannel;
  const float u = static_cast<float>(rider_unit_cm);
  auto up = [&](C c) { return glm::vec3(0.0f, float(r[c]) * u, 0.0f); };
  auto joint = [&](const char* n) -> const Joint& { return s.joints[rider.role(n)]; };
  // Pelvis: lifted by cog.ty and slid by cog.tx; tips forward (hip.rz) and rolls (hip.ry). The lift and
  // slide move the top of the pelvis's tree (the pelvis itself, or a user's root joint above it), so no
  // bone between them stretches.
  const glm::vec3 cog = glm::vec3(static_cast<float>(r[C::cogTx]) * u, static_cast<float>(r[C::cogTy]) * u, 0.0f);
  const int pelvis_joint = rider.role("pelvis");
  int top = pelvis_joint;
  while (s.joints[top].parent >= 0) top = s.joints[top].parent;
  if (top == pelvis_joint) {
    local[pelvis_joint] = offsetLocal(joint("pelvis"), cog, rot(-r[C::hipRz], kZ) * rot(r[C::hipRy], kX));
  } else {
    local[top] = translate(cog) * s.joints[top].rest_local;
    local[pelvis_joint] = s.joints[pelvis_joint].rest_local * rot(-r[C::hipRz], kZ) * rot(r[C::hipRy], kX);
  }

  // The curve spine, in the pelvis's frame with its root at the lower back. Constructing it only
  // stores the lengths; solve() is the work (71 us a call, BM_PoseRiderSpine in tests/bench/pose_bench.cpp).
  const RiderSpine layout = riderSpine(rider);
  const int segments = layout.laid_on_curve ? CurveSpine::kRiderSegments : CurveSpine::kMinSegments;
  const CurveSpine spine(layout.fk_lengths, segments);
  SpineControllers controllers = riderSpineControllers(r, params);
  if (!layout.laid_on_curve && rider.spine_bend_gain != 1.0f)
    for (glm::dvec3* c : {&controllers.lower, &controllers.middle, &controllers.top}) {
      c->y *= rider.spine_bend_gain;
      c->z *= rider.spine_bend_gain;
    }
  // Eq 9's squash and stretch lengthens the generated rider's spine, neck and head bones; a user's
  // rider keeps every bone's length (her chain only bends), so it is left out for her.
  const double stretch = layout.laid_on_curve ? riderSpineStretch(spine, r, rider_unit_cm) : 1.0;
  const glm::dvec3 root(layout.root);
  const glm::dquat unrest = glm::inverse(restBoneFrame());
  // A spine joint's transform relative to the pelvis: at its place, turned by its frame's change
  // from the rest frame (joints are translation-only at rest).
  const auto place = [&](const glm::dvec3& p, const glm::dquat& frame) {
    return glm::translate(glm::dmat4(1.0), root + p) * glm::mat4_cast(frame * unrest);
  };
  const std::array<glm::dquat, 3> frames = spine.controllerFrames(controllers);
  if (layout.laid_on_curve) {
    const SpineResult solved = spine.solve(controllers, stretch, SpineDetail::Joints);  // no samples: a pose reads the joints
    glm::dmat4 parent(1.0);  // the pelvis
    for (int k = 0; k < 3; ++k) {
      const glm::dmat4 world = place(solved.fk[k], frames[k]);
      local[layout.controllers[k]] = glm::mat4(glm::inverse(parent) * world);
      parent = world;
    }
    parent = glm::dmat4(1.0);
    for (int i = 0; i <= CurveSpine::kRiderSegments; ++i) {
      const glm::dmat4 world = place(solved.joints[i].position, solved.joints[i].rotation);
      local[layout.chain[i]] = glm::mat4(glm::inverse(parent) * world);
      parent = world;
    }
  } else {
    // Each bone turns with the curve's frame at its middle and keeps its length (times the stretch);
    // a chain ending at upperChest gives its top joint the curve's end frame.
    const std::size_t bones = layout.points.size() - 1;
    std::vector<double> at;
    for (std::size_t i = 0; i < bones; ++i) at.push_back(0.5 * (layout.arc[i] + layout.arc[i + 1]) / layout.arc.back());
    if (!layout.ends_at_neck) at.push_back(1.0);
    const std::vector<glm::dquat> turn = spine.framesAt(controllers, stretch, at);
    glm::dvec3 p = layout.points[0];
    glm::dmat4 parent(1.0);  // the pelvis
    for (std::size_t i = 0; i < layout.chain.size(); ++i) {
      const glm::dquat q = glm::normalize(turn[i] * unrest);
      const glm::dmat4 world = glm::translate(glm::dmat4(1.0), p) * glm::mat4_cast(q);
      local[layout.chain[i]] = glm::mat4(glm::inverse(parent) * world);
      parent = world;
      if (i < bones) p += q * ((layout.points[i + 1] - layout.points[i]) * stretch);
    }
    // Controller joints of their own (unskinned handles) at the FK places, when they hang from the pelvis.
    const std::array<glm::dvec3, 4> fk = spine.fkJoints(controllers, stretch);
    glm::dmat4 handle(1.0);
    int handle_joint = layout.pelvis;
    for (int k = 0; k < 3; ++k) {
      const int j = layout.controllers[k];
      if (j < 0 || s.joints[j].parent != handle_joint) break;
      const glm::dmat4 world = place(fk[k], frames[k]);
      local[j] = glm::mat4(glm::inverse(handle) * world);
      handle = world;
      handle_joint = j;
    }
  }
  // Neck and head ride on the chain's tip (a chain ending at the neck stretches its last bone too).
  const glm::vec3 neck_lift = layout.laid_on_curve ? up(C::neckTy) : glm::vec3(0.0f);
  const glm::vec3 head_lift = layout.laid_on_curve ? up(C::headATy) : glm::vec3(0.0f);
  local[rider.role("neck")] = translate(neck_lift) * joint("neck").rest_local;
  local[rider.role("head")] = offsetLocal(joint("head"), head_lift, rot(r[C::headRy], kX) * rot(-r[C::headRz], kZ));
}

namespace {

// Braid and coat tail: "up" swings them back and up, "side" toward the right, spread along the chain.
// Both are optional roles: a rider without a braid or a coat's skirt has nothing to swing.
void swingHairAndCloth(const Character& rider, const RiderChannels& r, const RiderPoseParams& params, std::span<glm::mat4> local) {
  using C = RiderChannel;
  const Skeleton& s = rider.skeleton;
  const float hair_up = float(r[C::hairUp]) * params.hair_deg_per_unit / 3.0f;
  const float hair_side = float(r[C::hairSide]) * params.hair_deg_per_unit / 3.0f;
  for (const char* n : {"braid1", "braid2", "braid3"})
    if (const auto it = rider.roles.find(n); it != rider.roles.end())
      local[it->second] = s.joints[it->second].rest_local * rot(-hair_side, kX) * rot(-hair_up, kZ);
  if (const auto it = rider.roles.find("coatTail"); it != rider.roles.end())
    local[it->second] = s.joints[it->second].rest_local * rot(-r[C::clothSide] * params.cloth_deg_per_unit, kX) *
                        rot(-r[C::clothUp] * params.cloth_deg_per_unit, kZ);
}

// Folding forward, she stops where her head or chest would come within the guard's room of the horse's
// neck and head (a rider on a horse she was not built for; Character::FoldGuard): `decided` limited to
// the largest turn (by `turnBy`) that keeps the room.
template <typename TurnBy>
void guardFold(const Character::FoldGuard& g, std::span<const glm::mat4> horseWorld, std::span<const glm::mat4> world,
               TurnBy&& turnBy, BalanceResult& decided) {
  std::vector<glm::vec3> neck(g.horse_joint.size()), upper(g.rider_joint.size());
  for (std::size_t k = 0; k < neck.size(); ++k) neck[k] = glm::vec3(horseWorld[g.horse_joint[k]] * glm::vec4(g.horse_local[k], 1.0f));
  for (std::size_t k = 0; k < upper.size(); ++k) upper[k] = glm::vec3(world[g.rider_joint[k]] * glm::vec4(g.rider_local[k], 1.0f));
  const float room2 = g.room_cm * g.room_cm;
  // The neck's box grown by the room: a point outside it is clear of every neck point (most of her,
  // most frames), so only the few inside are measured one by one.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& h : neck) lo = glm::min(lo, h), hi = glm::max(hi, h);
  lo -= glm::vec3(g.room_cm);
  hi += glm::vec3(g.room_cm);
  const auto clear = [&](double deg) {
    const glm::mat4 t = turnBy(deg);
    for (const glm::vec3& p : upper) {
      const glm::vec3 q(t * glm::vec4(p, 1.0f));
      if (glm::any(glm::lessThan(q, lo)) || glm::any(glm::greaterThan(q, hi))) continue;
      for (const glm::vec3& h : neck)
        if (glm::dot(q - h, q - h) < room2) return false;
    }
    return true;
  };
  if (clear(decided.turn_deg)) return;
  // The largest turn that keeps the room, to a tenth of a degree (bisection: nearer the neck the
  // further she folds).
  double low = 0.0, high = decided.turn_deg;
  while (high - low > kFoldGuardToleranceDeg) {
    const double mid = 0.5 * (low + high);
    (clear(mid) ? low : high) = mid;
  }
  decided.turn_deg = low;
  decided.lean_deg = decided.pose_lean_deg + low;
  decided.limited = true;
}

// The balance stage (rig/balance.h): measure the trunk as the channels pose it, turn it about the hips
// to the lean the stage decides, and turn the neck back so she keeps looking ahead. `top` is the top of
// her pelvis's tree; `local` and `world` are updated together.
BalanceResult balanceRider(const Character& rider, const Character& horse, std::span<const glm::mat4> horseWorld,
                           const RiderChannels& r, double rider_unit_cm, const BalanceStage& balance, int top,
                           std::span<glm::mat4> local, std::vector<glm::mat4>& world) {
  const Skeleton& s = rider.skeleton;
  const glm::mat4 saddle = horseWorld[horse.role("saddle")];
  const int pelvis = rider.role("pelvis");
  BalanceInput in;
  in.saddle = saddle;
  // Her trunk folds at her hips: the pelvis joint of the generated rider (at her hip joints' height),
  // or where the seating marked a user's hip joints ("hipCentre": a pelvis joint sits where its rig
  // put it, often well above the hips).
  const auto hip_centre = rider.roles.find("hipCentre");
  const int pivot = hip_centre == rider.roles.end() ? pelvis : hip_centre->second;
  in.seat = position(world[pivot]);
  in.stirrups = 0.5f * (stirrupTarget(horse, horseWorld, r, rider_unit_cm, 0) + stirrupTarget(horse, horseWorld, r, rider_unit_cm, 1));
  in.trunk = position(world[rider.role("neck")]) - position(world[pelvis]);
  in.com_height_cm = rider.balance_com_height_cm > 0.0f ? rider.balance_com_height_cm : trunkComHeight(rider);
  in.fold_scale = balance.fold_scale;
  in.seat_rise_cm = (glm::inverse(saddle) * glm::vec4(in.seat, 1.0f)).y - s.restPosition(pivot).y;
  in.accel_cm_s2 = balance.accel_cm_s2;
  in.ground_pitch_deg = balance.ground_pitch_deg;
  BalanceResult decided = balanceTrunk(in, balance.params);
  // Forward is a turn taking the vertical toward the heading: about up x heading. The seat rises
  // along the saddle's up.
  const glm::vec3 axis = glm::normalize(glm::cross(kY, saddleHeading(saddle)));
  const glm::vec3 lift = glm::normalize(glm::vec3(saddle[1])) * float(decided.seat_lift_cm);
  const auto turnBy = [&](double deg) {
    return translate(in.seat + lift) * glm::rotate(glm::mat4(1.0f), glm::radians(float(deg)), axis) * translate(-in.seat);
  };
  if (decided.turn_deg > 0.0 && !rider.fold_guard.empty()) guardFold(rider.fold_guard, horseWorld, world, turnBy, decided);
  if (decided.turn_deg != 0.0 || decided.seat_lift_cm != 0.0) {
    const glm::mat4 turn = turnBy(decided.turn_deg);
    local[top] = turn * local[top];
    const float counter = std::clamp(float(decided.turn_deg * balance.params.head_counter), -kNeckCounterRangeDeg,
                                     kNeckCounterRangeDeg);
    const int neck = rider.role("neck");
    local[neck] = local[neck] * rot(counter, kZ);
    localToWorld(s, local, world);
  }
  return decided;
}

// Arm: the wrist reaches for the rein, moved by wrist tx (forward) and ty (up) in saddle space.
void reachForRein(const Character& rider, const glm::mat4& saddle, const RiderChannels& r, float u, int side,
                  const RiderPoseParams& params, std::vector<glm::mat4>& world) {
  using C = RiderChannel;
  const Skeleton& s = rider.skeleton;
  const std::string n = side == 0 ? "l" : "r";
  const int shoulder = rider.role(n + "Shoulder"), elbow = rider.role(n + "Elbow"), wrist = rider.role(n + "Wrist");
  const glm::vec3 rs = s.restPosition(shoulder), re = s.restPosition(elbow), rw = s.restPosition(wrist);
  const glm::vec3 offset(float(r[side == 0 ? C::lWristTx : C::rWristTx]) * u,
                         float(r[side == 0 ? C::lWristTy : C::rWristTy]) * u, 0.0f);
  const glm::vec3 target = transformPoint(saddle, rw + offset);
  const glm::vec3 rest_pole = restPole(rs, re, rw, 40.0f);
  const glm::vec3 pole = transformPoint(motion(s, world, s.joints[shoulder].parent), rest_pole);
  const LimbPose limb = solveLimb(rs, re, rw, rest_pole, position(world[shoulder]), target, pole, params.limb_soften);
  world[shoulder] = limb.upper;
  world[elbow] = limb.middle;
  world[wrist] = translate(limb.end) * glm::mat4(glm::mat3(saddle));  // the hand keeps its grip angle
  const int hand = rider.role(n + "Hand");
  world[hand] = world[wrist] * s.joints[hand].rest_local;
}

// Leg: the ball of the foot in the stirrup; the foot turns about the ball; the knee's pole moves with
// the knee channels (away from the belly, up).
void footInStirrup(const Character& rider, const Character& horse, std::span<const glm::mat4> horseWorld,
                   const RiderChannels& r, double rider_unit_cm, int side, const RiderPoseParams& params,
                   std::vector<glm::mat4>& world) {
  using C = RiderChannel;
  const Skeleton& s = rider.skeleton;
  const glm::mat4 saddle = horseWorld[horse.role("saddle")];
  const float u = static_cast<float>(rider_unit_cm);
  const std::string n = side == 0 ? "l" : "r";
  const float away = side == 0 ? -1.0f : 1.0f;  // +Z is the horse's right
  const int hip = rider.role(n + "Hip"), knee = rider.role(n + "Knee");
  const int ankle = rider.role(n + "Ankle"), ball = rider.role(n + "Ball");
  const glm::vec3 rh = s.restPosition(hip), rk = s.restPosition(knee), ra = s.restPosition(ankle),
                  rb = s.restPosition(ball);
  const glm::mat4 foot_rot = rot(-r[side == 0 ? C::lFootRy : C::rFootRy], kY) *
                             rot(r[side == 0 ? C::lFootRx : C::rFootRx], kX) *
                             rot(r[side == 0 ? C::lFootRz : C::rFootRz], kZ);
  const glm::mat4 foot_world_rot = glm::mat4(glm::mat3(saddle)) * foot_rot;
  const glm::vec3 ball_target = stirrupTarget(horse, horseWorld, r, rider_unit_cm, side);
  const glm::vec3 ankle_target = ball_target + glm::vec3(foot_world_rot * glm::vec4(ra - rb, 0.0f));
  const glm::vec3 rest_pole = restPole(rh, rk, ra, 50.0f);
  const glm::vec3 knee_offset(0.0f, float(r[side == 0 ? C::lKneeTy : C::rKneeTy]) * u,
                              float(r[side == 0 ? C::lKneeTz : C::rKneeTz]) * u * away);
  const glm::vec3 pole = transformPoint(saddle, rest_pole + knee_offset * params.knee_pole_gain);
  LimbPose limb = solveLimb(rh, rk, ra, rest_pole, position(world[hip]), ankle_target, pole, params.limb_soften);
  if (!rider.leg_guard.empty())
    limb = guardLeg(rider.leg_guard, saddle, away, limb, [&](glm::vec3 pole_point, float foot_out) {
      const glm::vec3 out = glm::vec3(saddle * glm::vec4(0.0f, kGuardFootUpPerOut * foot_out, away * foot_out, 0.0f));
      return solveLimb(rh, rk, ra, rest_pole, position(world[hip]), ankle_target + out, pole_point, params.limb_soften);
    });
  world[hip] = limb.upper;
  world[knee] = limb.middle;
  world[ankle] = translate(limb.end) * foot_world_rot;
  world[ball] = translate(limb.end + glm::vec3(foot_world_rot * glm::vec4(rb - ra, 0.0f))) * foot_world_rot;
}

}  // namespace

std::vector<glm::mat4> poseRider(const Character& rider, const Character& horse, std::span<const glm::mat4> horseWorld,
                                 const RiderChannels& r, double rider_unit_cm, const RiderPoseParams& params,
                                 const BalanceStage* balance, BalanceResult* balance_result) {
  checkSize(horse, horseWorld);
  const Skeleton& s = rider.skeleton;
  // The rider is built in saddle space: the posed saddle is the rider's frame.
  const glm::mat4 saddle = horseWorld[horse.role("saddle")];

  std::vector<glm::mat4> local = restLocals(s);
  poseRiderSpine(rider, r, rider_unit_cm, params, local);
  swingHairAndCloth(rider, r, params, local);
  // The saddle carries her from the top of her pelvis's tree (a user's rig may hang the pelvis from a
  // root on the ground, which rides along).
  int top = rider.role("pelvis");
  while (s.joints[top].parent >= 0) top = s.joints[top].parent;
  local[top] = saddle * local[top];
  std::vector<glm::mat4> world(s.size());
  localToWorld(s, local, world);

  if (balance) {
    const BalanceResult decided = balanceRider(rider, horse, horseWorld, r, rider_unit_cm, *balance, top, local, world);
    if (balance_result) *balance_result = decided;
  }

  std::vector<char> solved(s.size(), 0);  // joints the limbs below place in world terms
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    for (const char* part : {"Shoulder", "Elbow", "Wrist", "Hand", "Hip", "Knee", "Ankle", "Ball"}) solved[rider.role(n + part)] = 1;
    reachForRein(rider, saddle, r, static_cast<float>(rider_unit_cm), side, params, world);
    footInStirrup(rider, horse, horseWorld, r, rider_unit_cm, side, params, world);
  }
  // Joints hanging from the limbs that no role names (fingers, toes, twist and split-segment joints
  // of a user's rig) are carried by their parents as they hang at rest.
  carryUnsolved(s, local, solved, world);
  return world;
}

double torsoFold(const RiderChannels& r, const RiderPoseParams& params) {
  using C = RiderChannel;
  return r[C::hipRz] + r[C::lowerBackRz] + r[C::waistRz] * (1.0 + params.chest_follow);
}

RiderChannels limitRiderChannels(RiderChannels r, const RiderPoseParams& params, double rider_unit_cm) {
  using C = RiderChannel;
  const double lean = torsoFold(r, params);
  if (std::abs(lean) > params.max_lean_deg) {
    const double s = params.max_lean_deg / std::abs(lean);
    for (C c : {C::hipRz, C::lowerBackRz, C::waistRz}) r[c] *= s;
  }
  const double swing = params.max_foot_swing_cm / std::max(rider_unit_cm, 1e-9);
  for (C c : {C::lFootTx, C::rFootTx}) r[c] = std::clamp(r[c], -swing, swing);
  for (C c : {C::lFootRz, C::rFootRz})
    r[c] = std::clamp(r[c], -double(params.max_foot_turn_deg), double(params.max_foot_turn_deg));
  const double unit = std::max(rider_unit_cm, 1e-9);
  for (C c : {C::lFootTz, C::rFootTz}) r[c] = std::max(r[c], -params.max_foot_in_cm / unit);  // − is in
  for (C c : {C::lFootRy, C::rFootRy})
    r[c] = std::clamp(r[c], -double(params.max_foot_twist_deg), double(params.max_foot_twist_deg));
  r[C::cogTx] = std::max(r[C::cogTx], -params.max_seat_back_cm / unit);  // − is back
  return r;
}

}  // namespace stirrup::rig
