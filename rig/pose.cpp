#include "rig/pose.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "rig/horse_body.h"
#include "rig/horse_leg.h"
#include "rig/ik.h"
#include "rig/rider_spine.h"
#include "rig/skeleton.h"

namespace stirrup::rig {
namespace {

constexpr glm::vec3 kX{1.0f, 0.0f, 0.0f}, kY{0.0f, 1.0f, 0.0f}, kZ{0.0f, 0.0f, 1.0f};
// A hoof lifted this little (cm) or less is down, for HorseReach::planted (the clips' stance lift is 0).
constexpr float kPlantedLiftCm = 1e-3f;
// Passes of the stance settle (poseHorse): each closes most of what is left.
constexpr int kStanceSettlePasses = 4;
// How far the neck turns back at most to counter the balance stage's turn: a choice, well inside the
// extension range of a neck, so the head never tips back past where a rider looking ahead holds it.
constexpr float kNeckCounterRangeDeg = 45.0f;
// The fold guard (Character::FoldGuard) finds the largest forward turn that keeps its room to this.
constexpr double kFoldGuardToleranceDeg = 0.1;

// Joints below the ones a solve placed (`solved`), which it did not place themselves, follow their
// parents by their local transforms (parents come before children in the skeleton).
void carryUnsolved(const Skeleton& s, std::span<const glm::mat4> local, const std::vector<char>& solved,
                   std::span<glm::mat4> world) {
  std::vector<char> moved = solved;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int p = s.joints[j].parent;
    if (solved[j] || p < 0 || !moved[p]) continue;
    world[j] = world[p] * local[j];
    moved[j] = 1;
  }
}

glm::mat4 rot(double degrees, glm::vec3 axis) {
  return glm::rotate(glm::mat4(1.0f), glm::radians(static_cast<float>(degrees)), axis);
}
glm::mat4 translate(glm::vec3 t) { return glm::translate(glm::mat4(1.0f), t); }
glm::vec3 position(const glm::mat4& m) { return glm::vec3(m[3]); }
glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

// Rest local with an extra translation (in the parent's frame) and rotation.
glm::mat4 offsetLocal(const Joint& j, glm::vec3 extra_translation, const glm::mat4& rotation) {
  return translate(extra_translation) * j.rest_local * rotation;
}

// The rigid motion a joint has made from its bind pose: world * inverse bind.
glm::mat4 motion(const Skeleton& s, std::span<const glm::mat4> world, int joint) {
  return world[joint] * s.joints[joint].inverse_bind;
}

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

void checkSize(const Character& c, std::span<const glm::mat4> world) {
  if (world.size() != c.skeleton.size())
    throw std::invalid_argument("pose: expected one world matrix per joint of " + c.name);
}

}  // namespace

std::array<glm::dvec2, 4> restHoofPlaces(const Character& horse) {
  std::array<glm::dvec2, 4> out{};
  static constexpr std::array<const char*, 4> kRoles = {"lfHoof", "rfHoof", "lbHoof", "rbHoof"};
  for (std::size_t i = 0; i < 4; ++i) {
    const glm::vec3 p = horse.skeleton.restPosition(horse.role(kRoles[i]));
    out[i] = {p.x, p.z};
  }
  return out;
}

glm::mat4 travelMatrix(const HorseFrame& frame) {
  // Heading + turns right: from +X toward +Z, a turn about -Y; then the ground's pitch, nose up.
  return translate({float(frame.travel_cm), float(frame.ground_y_cm), float(frame.travel_z_cm)}) *
         rot(-frame.heading_deg, kY) * rot(frame.ground_pitch_deg, kZ);
}

namespace {

// poseHorse with the body lowered `settle_cm` along the travel frame's up (see poseHorse).
std::vector<glm::mat4> poseHorseSettled(const Character& horse, const HorseFrame& frame, const HorsePoseParams& params,
                                        HorseReach* reach, float settle_cm) {
  const Skeleton& s = horse.skeleton;
  const HorseChannels& h = frame.controls;
  using C = HorseChannel;
  std::vector<glm::mat4> local = restLocals(s);

  // Body: the travel frame carries the rear pivot; rearPivot moves and turns it.
  const glm::mat4 travel = travelMatrix(frame);
  const int root = horse.role("root");
  local[root] = travel * translate({float(h[C::rearPivotTx]), float(h[C::rearPivotTy]) - settle_cm, float(h[C::rearPivotTz])}) *
                s.joints[root].rest_local * rot(-h[C::rearPivotRy], kY) * rot(h[C::rearPivotRz], kZ) *
                rot(h[C::rearPivotRx], kX);
  // A user's rig may hang the root from joints of its own (a ground root): they ride along rigidly with
  // the root, so no bone between them stretches. (The root's rest is translation-only: its rest world
  // is the inverse of its inverse bind.)
  int top = root;
  while (s.joints[top].parent >= 0) top = s.joints[top].parent;
  if (top != root) {
    const glm::mat4 root_world = local[root];
    local[root] = s.joints[root].rest_local;
    local[top] = root_world * s.joints[root].inverse_bind * s.joints[top].rest_local;
  }
  // The back, neck and tail as this horse's skeleton has them (rig/horse_body.h).
  const HorseBody body = horseBody(horse);
  // Back arch: the hips-to-mid-back segment tilts up by half, the front half pitches down by half,
  // so the middle of the back rises relative to both ends.
  if (body.back_turn >= 0) {
    const int back_mid = body.back_turn;
    const float half_arch = static_cast<float>(h[C::backMidRz]) * 0.5f;
    const glm::vec3 back_offset(s.joints[back_mid].rest_local[3]);
    const glm::vec3 arched = glm::vec3(rot(half_arch, kZ) * glm::vec4(back_offset, 0.0f));
    local[back_mid] = translate(arched) * rot(-h[C::backMidRy], kY) * rot(h[C::backMidRx], kX) * rot(-half_arch, kZ);
  }
  // Neck and head: + = up, spread over the neck's joints. Tail: + = up and to the right, spread over
  // the tail's longest line of joints.
  const double neck_share = frame.neck_rz / static_cast<double>(body.neck.size());
  for (int j : body.neck) local[j] = s.joints[j].rest_local * rot(neck_share, kZ);
  local[horse.role("head")] = s.joints[horse.role("head")].rest_local * rot(frame.head_rz, kZ);
  const double tail_parts = static_cast<double>(std::max(body.tail_length, 1));
  for (int j : body.tail) local[j] = s.joints[j].rest_local * rot(frame.tail_ry / tail_parts, kY) * rot(-frame.tail_rz / tail_parts, kZ);
  std::vector<glm::mat4> world(s.size());
  localToWorld(s, local, world);

  // Legs: hoof targets in the travel frame; the pastern folds back as the hoof lifts, the IK chain
  // reaches for the fetlock above the hoof.
  static constexpr std::array<const char*, 4> kLegs = {"lf", "rf", "lb", "rb"};
  static constexpr std::array<std::array<C, 3>, 4> kHoofChannels = {{{C::lfHoofTx, C::lfHoofTy, C::lfHoofTz},
                                                                     {C::rfHoofTx, C::rfHoofTy, C::rfHoofTz},
                                                                     {C::lbHoofTx, C::lbHoofTy, C::lbHoofTz},
                                                                     {C::rbHoofTx, C::rbHoofTy, C::rbHoofTz}}};
  std::vector<char> solved(s.size(), 0);  // joints the legs' IK places in world terms
  for (int leg = 0; leg < 4; ++leg) {
    const std::string n = kLegs[leg];
    const int upper = horse.role(n + "Upper"), middle = horse.role(n + "Middle");
    const int fetlock = horse.role(n + "Fetlock"), hoof = horse.role(n + "Hoof");
    for (int j : {upper, middle, fetlock, hoof}) solved[j] = 1;
    const glm::vec3 rest_upper = s.restPosition(upper), rest_middle = s.restPosition(middle);
    const glm::vec3 rest_fetlock = s.restPosition(fetlock), rest_hoof = s.restPosition(hoof);
    const auto& ch = kHoofChannels[leg];
    const glm::vec3 offset{static_cast<float>(h[ch[0]]), static_cast<float>(h[ch[1]]), static_cast<float>(h[ch[2]])};
    // The ground under the hoof lifts its target; the lift above it (the channel) folds the pastern.
    const glm::vec3 ground{0.0f, static_cast<float>(frame.hoof_ground_cm[leg]), 0.0f};
    const glm::vec3 hoof_target = transformPoint(travel, rest_hoof + offset + ground);
    const float lift = std::clamp(offset.y / params.hoof_flex_full_lift, 0.0f, 1.0f);
    const float flex = params.hoof_flex_deg * lift * lift * (3.0f - 2.0f * lift);
    // The hoof sole turns to face backward, about the travel frame's sideways axis.
    const glm::mat4 fold = glm::mat4(glm::mat3(travel)) * rot(-flex, kZ);
    if (reach) reach->planted[std::size_t(leg)] = offset.y <= kPlantedLiftCm;
    if (horse.roles.count(n + "Pivot")) {
      // The whole limb reaches (rig/horse_leg.h): the default horse names its scapula and hip pivots.
      HorseLegJoints joints;
      joints.fore = leg < 2;
      joints.pivot = horse.role(n + "Pivot");
      joints.shoulder = horseLegShoulder(s, joints.pivot, upper);
      joints.upper = upper;
      joints.middle = middle;
      joints.fetlock = fetlock;
      joints.hoof = hoof;
      for (int j : {joints.pivot, joints.shoulder})
        if (j >= 0) solved[j] = 1;
      const float short_cm = solveHorseLeg(s, joints, {hoof_target, fold}, params.leg, world);
      if (reach) reach->short_cm[std::size_t(leg)] = short_cm;
      continue;
    }
    const glm::vec3 fetlock_target = hoof_target + glm::vec3(fold * glm::vec4(rest_fetlock - rest_hoof, 0.0f));

    const glm::vec3 rest_pole = restPole(rest_upper, rest_middle, rest_fetlock, 40.0f);
    const int parent = s.joints[upper].parent;
    const glm::vec3 pole = transformPoint(motion(s, world, parent), rest_pole);
    const LimbPose limb = solveLimb(rest_upper, rest_middle, rest_fetlock, rest_pole, position(world[upper]),
                                    fetlock_target, pole, params.leg.soften_cm);
    world[upper] = limb.upper;
    world[middle] = limb.middle;
    world[fetlock] = translate(limb.end) * fold;
    world[hoof] = translate(limb.end + glm::vec3(fold * glm::vec4(rest_hoof - rest_fetlock, 0.0f))) * fold;
    if (reach) reach->short_cm[std::size_t(leg)] = glm::length(limb.end - fetlock_target);
  }
  // Joints hanging from the legs that no role names (a user's toes, dewclaws, twist joints) are
  // carried by their parents as they hang at rest.
  carryUnsolved(s, local, solved, world);
  return world;
}

}  // namespace

namespace {

// A horse keyed by its clip (HorseFrame::keyed_pose): its joints where the file keys them, the points the
// rig added hanging from their parents as at rest. A hoof is down within kKeyedContactCm of its rest
// height; nothing is solved, so nothing falls short.
std::vector<glm::mat4> poseKeyedHorse(const Character& horse, const HorseFrame& frame, HorseReach* reach) {
  const Skeleton& s = horse.skeleton;
  const KeyedHorsePose& keyed = *frame.keyed_pose;
  if (keyed.joint.size() != s.size() || keyed.keyed.size() != s.size())
    throw std::invalid_argument("poseHorse: the keyed pose was made for another horse (" + std::to_string(keyed.joint.size()) +
                                " joints, the horse has " + std::to_string(s.size()) + ")");
  const glm::mat4 travel = travelMatrix(frame);
  std::vector<glm::mat4> world(s.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int p = s.joints[j].parent;
    if (keyed.keyed[j]) world[j] = travel * keyed.joint[j];
    else world[j] = p < 0 ? travel * s.joints[j].rest_local : world[std::size_t(p)] * s.joints[j].rest_local;
  }
  if (reach) {
    *reach = {};
    static constexpr std::array<HorseChannel, 4> kLift = {HorseChannel::lfHoofTy, HorseChannel::rfHoofTy,
                                                          HorseChannel::lbHoofTy, HorseChannel::rbHoofTy};
    for (std::size_t leg = 0; leg < 4; ++leg) reach->planted[leg] = frame.controls[kLift[leg]] <= kKeyedContactCm;
  }
  return world;
}

}  // namespace

std::vector<glm::mat4> poseHorse(const Character& horse, const HorseFrame& frame, const HorsePoseParams& params,
                                 HorseReach* reach) {
  if (frame.keyed_pose) return poseKeyedHorse(horse, frame, reach);
  HorseReach r;
  std::vector<glm::mat4> world = poseHorseSettled(horse, frame, params, &r, 0.0f);
  // A planted leg short of its print: the body settles onto it, as far as max_stance_settle_cm. Each
  // pass lowers it by the worst shortfall left (a leg slanted from the vertical closes less than the
  // drop, so the passes approach the print from above); frames whose planted legs reach are untouched.
  const auto worstPlanted = [&r] {
    float worst = 0.0f;
    for (std::size_t leg = 0; leg < 4; ++leg)
      if (r.planted[leg]) worst = std::max(worst, r.short_cm[leg]);
    return worst;
  };
  if (worstPlanted() >= HorseReach::kOverReachCm) {
    float settle = 0.0f;
    for (int pass = 0; pass < kStanceSettlePasses && settle < params.max_stance_settle_cm; ++pass) {
      const float worst = worstPlanted();
      if (worst <= params.leg.soften_cm) break;
      settle = std::min(settle + worst, params.max_stance_settle_cm);
      world = poseHorseSettled(horse, frame, params, &r, settle);
    }
  }
  if (reach) *reach = r;
  return world;
}

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

glm::vec3 stirrupTarget(const Character& horse, std::span<const glm::mat4> horseWorld, const RiderChannels& r,
                        double rider_unit_cm, int side) {
  checkSize(horse, horseWorld);
  using C = RiderChannel;
  const Skeleton& s = horse.skeleton;
  const int saddle = horse.role("saddle");
  const int stirrup = horse.role(side == 0 ? "lStirrup" : "rStirrup");
  const float u = static_cast<float>(rider_unit_cm);
  const float tx = float(r[side == 0 ? C::lFootTx : C::rFootTx]) * u;
  const float away = float(r[side == 0 ? C::lFootTz : C::rFootTz]) * u * (side == 0 ? -1.0f : 1.0f);
  const glm::vec3 rest_in_saddle = s.restPosition(stirrup) - s.restPosition(saddle);
  return transformPoint(horseWorld[saddle], rest_in_saddle + glm::vec3(tx, 0.0f, away));
}

void placeStirrups(const Character& horse, std::span<glm::mat4> horseWorld, const RiderChannels& r,
                   double rider_unit_cm) {
  for (int side = 0; side < 2; ++side) {
    const glm::vec3 p = stirrupTarget(horse, horseWorld, r, rider_unit_cm, side);
    glm::mat4& m = horseWorld[horse.role(side == 0 ? "lStirrup" : "rStirrup")];
    m = horseWorld[horse.role("saddle")];
    m[3] = glm::vec4(p, 1.0f);
  }
}

void placeReins(const Character& horse, std::span<glm::mat4> horseWorld, const Character& rider,
                std::span<const glm::mat4> riderWorld) {
  checkSize(horse, horseWorld);
  checkSize(rider, riderWorld);
  for (const char* side : {"l", "r"}) {
    glm::mat4& m = horseWorld[horse.role(std::string(side) + "Rein")];
    m = horseWorld[horse.role("saddle")];
    m[3] = riderWorld[rider.role(std::string(side) + "Hand")][3];
  }
}

std::vector<glm::mat4> poseRider(const Character& rider, const Character& horse, std::span<const glm::mat4> horseWorld,
                                 const RiderChannels& r, double rider_unit_cm, const RiderPoseParams& params,
                                 const BalanceStage* balance, BalanceResult* balance_result) {
  checkSize(horse, horseWorld);
  using C = RiderChannel;
  const Skeleton& s = rider.skeleton;
  const float u = static_cast<float>(rider_unit_cm);
  // The rider is built in saddle space: the posed saddle is the rider's frame.
  const glm::mat4 saddle = horseWorld[horse.role("saddle")];

  std::vector<glm::mat4> local = restLocals(s);
  poseRiderSpine(rider, r, rider_unit_cm, params, local);
  // Braid and coat tail: "up" swings them back and up, "side" toward the right, spread along the chain.
  // Both are optional roles: a rider without a braid or a coat's skirt has nothing to swing.
  const float hair_up = float(r[C::hairUp]) * params.hair_deg_per_unit / 3.0f;
  const float hair_side = float(r[C::hairSide]) * params.hair_deg_per_unit / 3.0f;
  for (const char* n : {"braid1", "braid2", "braid3"})
    if (const auto it = rider.roles.find(n); it != rider.roles.end())
      local[it->second] = s.joints[it->second].rest_local * rot(-hair_side, kX) * rot(-hair_up, kZ);
  if (const auto it = rider.roles.find("coatTail"); it != rider.roles.end())
    local[it->second] = s.joints[it->second].rest_local * rot(-r[C::clothSide] * params.cloth_deg_per_unit, kX) *
                        rot(-r[C::clothUp] * params.cloth_deg_per_unit, kZ);
  const int pelvis = rider.role("pelvis");
  // The saddle carries her from the top of her pelvis's tree (a user's rig may hang the pelvis from a
  // root on the ground, which rides along).
  int top = pelvis;
  while (s.joints[top].parent >= 0) top = s.joints[top].parent;
  local[top] = saddle * local[top];
  std::vector<glm::mat4> world(s.size());
  localToWorld(s, local, world);

  if (balance) {
    // The balance stage (rig/balance.h): measure the trunk as the channels pose it, turn it about the
    // hips to the lean the stage decides, and turn the neck back so she keeps looking ahead.
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
    in.fold_scale = balance->fold_scale;
    in.seat_rise_cm = (glm::inverse(saddle) * glm::vec4(in.seat, 1.0f)).y - s.restPosition(pivot).y;
    in.accel_cm_s2 = balance->accel_cm_s2;
    in.ground_pitch_deg = balance->ground_pitch_deg;
    BalanceResult decided = balanceTrunk(in, balance->params);
    // Forward is a turn taking the vertical toward the heading: about up x heading. The seat rises
    // along the saddle's up.
    const glm::vec3 axis = glm::normalize(glm::cross(kY, saddleHeading(saddle)));
    const glm::vec3 lift = glm::normalize(glm::vec3(saddle[1])) * float(decided.seat_lift_cm);
    const auto turnBy = [&](double deg) {
      return translate(in.seat + lift) * glm::rotate(glm::mat4(1.0f), glm::radians(float(deg)), axis) * translate(-in.seat);
    };
    if (decided.turn_deg > 0.0 && !rider.fold_guard.empty()) {
      // Folding forward, she stops where her head or chest would come within the guard's room of the
      // horse's neck and head (a rider on a horse she was not built for; Character::FoldGuard).
      const Character::FoldGuard& g = rider.fold_guard;
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
      if (!clear(decided.turn_deg)) {
        // The largest turn that keeps the room, to a tenth of a degree (bisection: nearer the neck the
        // further she folds).
        double lo = 0.0, hi = decided.turn_deg;
        while (hi - lo > kFoldGuardToleranceDeg) {
          const double mid = 0.5 * (lo + hi);
          (clear(mid) ? lo : hi) = mid;
        }
        decided.turn_deg = lo;
        decided.lean_deg = decided.pose_lean_deg + lo;
        decided.limited = true;
      }
    }
    if (balance_result) *balance_result = decided;
    if (decided.turn_deg != 0.0 || decided.seat_lift_cm != 0.0) {
      const glm::mat4 turn = turnBy(decided.turn_deg);
      local[top] = turn * local[top];
      const float counter = std::clamp(float(decided.turn_deg * balance->params.head_counter), -kNeckCounterRangeDeg,
                                       kNeckCounterRangeDeg);
      const int neck = rider.role("neck");
      local[neck] = local[neck] * rot(counter, kZ);
      localToWorld(s, local, world);
    }
  }

  std::vector<char> solved(s.size(), 0);  // joints the limbs below place in world terms
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const float away = side == 0 ? -1.0f : 1.0f;  // +Z is the horse's right
    for (const char* part : {"Shoulder", "Elbow", "Wrist", "Hand", "Hip", "Knee", "Ankle", "Ball"}) solved[rider.role(n + part)] = 1;
    // Arm: the wrist reaches for the rein, moved by wrist tx (forward) and ty (up) in saddle space.
    {
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
    // Leg: the ball of the foot in the stirrup; the foot turns about the ball; the knee's pole moves
    // with the knee channels (away from the belly, up).
    {
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

MountedPose poseMounted(const Character& horse, const Character& rider, const HorseFrame& frame,
                        const RiderChannels& channels, const RigProfile& profile) {
  const double unit = profile.rider_unit_cm;
  const RiderPoseParams params;
  // In a turn her roll channels answer the horse's roll from the apparent vertical (rig/balance.h); on a
  // straight line, and for the rigid rider, the tilt is 0 and the channels are posed as they are.
  const double tilt = profile.rigid ? 0.0 : turnTiltDegrees(frame.travel_side_accel_cm_s2, profile.balance);
  const RiderChannels r = limitRiderChannels(answerTiltedVertical(channels, frame.controls, profile, tilt), params, unit);
  MountedPose p;
  p.horse = poseHorse(horse, frame, {}, &p.reach);
  placeStirrups(horse, p.horse, r, unit);
  if (profile.rigid) {
    p.rider = poseRider(rider, horse, p.horse, r, unit, params);
  } else {
    BalanceStage stage;
    stage.params = profile.balance;
    const double asked = std::abs(torsoFold(channels, params)), allowed = std::abs(torsoFold(r, params));
    stage.fold_scale = allowed > 1e-9 ? std::max(asked / allowed, 1.0) : 1.0;
    stage.accel_cm_s2 = frame.travel_accel_cm_s2;
    stage.ground_pitch_deg = frame.ground_pitch_deg;
    p.rider = poseRider(rider, horse, p.horse, r, unit, params, &stage, &p.balance);
    p.balance.turn_tilt_deg = tilt;
  }
  placeReins(horse, p.horse, rider, p.rider);
  return p;
}

}  // namespace stirrup::rig
