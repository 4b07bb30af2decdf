#include "rig/horse_pose.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "rig/horse_body.h"
#include "rig/horse_leg.h"
#include "rig/ik.h"
#include "rig/pose_transforms.h"
#include "rig/skeleton.h"

namespace stirrup::rig {
namespace {

using namespace pose_transforms;

// A hoof lifted this little (cm) or less is down, for HorseReach::planted (the clips' stance lift is 0).
constexpr float kPlantedLiftCm = 1e-3f;
// Passes of the stance settle (poseHorse): each closes most of what is left.
constexpr int kStanceSettlePasses = 4;

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

// The body's local transforms at `settle_cm` lowered: the travel frame carrying the rear pivot, the
// back, neck, head and tail turned by their channels; the legs are left at rest for the IK to place.
std::vector<glm::mat4> horseBodyLocals(const Character& horse, const HorseFrame& frame, const glm::mat4& travel,
                                       float settle_cm) {
  const Skeleton& s = horse.skeleton;
  const HorseChannels& h = frame.controls;
  using C = HorseChannel;
  std::vector<glm::mat4> local = restLocals(s);

  // Body: the travel frame carries the rear pivot; rearPivot moves and turns it.
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
  return local;
}

// One leg reaching for its hoof target in the travel frame: the pastern folds back as the hoof lifts,
// the IK chain reaches for the fetlock above the hoof. Marks the joints it places in `solved`.
void reachHorseLeg(const Character& horse, const HorseFrame& frame, const HorsePoseParams& params, const glm::mat4& travel,
                   int leg, std::vector<glm::mat4>& world, std::vector<char>& solved, HorseReach* reach) {
  using C = HorseChannel;
  static constexpr std::array<const char*, 4> kLegs = {"lf", "rf", "lb", "rb"};
  static constexpr std::array<std::array<C, 3>, 4> kHoofChannels = {{{C::lfHoofTx, C::lfHoofTy, C::lfHoofTz},
                                                                     {C::rfHoofTx, C::rfHoofTy, C::rfHoofTz},
                                                                     {C::lbHoofTx, C::lbHoofTy, C::lbHoofTz},
                                                                     {C::rbHoofTx, C::rbHoofTy, C::rbHoofTz}}};
  const Skeleton& s = horse.skeleton;
  const HorseChannels& h = frame.controls;
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
    return;
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

// poseHorse with the body lowered `settle_cm` along the travel frame's up (see poseHorse).
std::vector<glm::mat4> poseHorseSettled(const Character& horse, const HorseFrame& frame, const HorsePoseParams& params,
                                        HorseReach* reach, float settle_cm) {
  const Skeleton& s = horse.skeleton;
  const glm::mat4 travel = travelMatrix(frame);
  const std::vector<glm::mat4> local = horseBodyLocals(horse, frame, travel, settle_cm);
  std::vector<glm::mat4> world(s.size());
  localToWorld(s, local, world);

  std::vector<char> solved(s.size(), 0);  // joints the legs' IK places in world terms
  for (int leg = 0; leg < 4; ++leg) reachHorseLeg(horse, frame, params, travel, leg, world, solved, reach);
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

}  // namespace stirrup::rig
