#include "rig/characters/seating.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <cstdint>
#include <unordered_map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "rig/characters/rider_character.h"
#include "rig/error.h"
#include "rig/ik.h"
#include "rig/loose_tack.h"
#include "rig/pose.h"
#include "rig/pose_transforms.h"
#include "rig/skin.h"
#include "rig/units.h"

namespace stirrup::rig {
namespace {

float toRadians(float degrees) { return degrees * kPiF / 180.0f; }
float toDegrees(float radians) { return radians * 180.0f / kPiF; }

// Segment lengths as fractions of stature (Drillis and Contini 1966, "Body segment parameters",
// Report 1166-03, New York University; the figure in Winter, Biomechanics and Motor Control of Human
// Movement): the hand 0.108 H, the foot 0.152 H. Used only where the file's mesh does not say.
constexpr float kHandPerStature = 0.108f;
constexpr float kFootPerStature = 0.152f;
// The ball of the foot (the first metatarsal head) lies about 73% of the foot's length from the heel:
// the heel-to-ball ("arch") length a Brannock device measures against the heel-to-toe length (an
// estimate from shoe-fitting practice, not a measured constant).
constexpr float kBallFromHeel = 0.73f;
// Where the hand closes on the rein, from the wrist along the hand: the generated rider's grip is
// 6.2 cm ahead of her wrist on a hand of about 10 cm (RiderParams::wrist_from_grip).
constexpr float kGripAlongHand = 0.6f;
// The seat: hip joints above the seat bones, as a fraction of stature where the mesh does not tell
// (the generated rider: 10 cm of 170), and the range a measurement from a mesh is trusted in.
constexpr float kSeatDepthPerStature = 10.0f / 170.0f;
constexpr float kSeatDepthMin = 0.045f, kSeatDepthMax = 0.075f;
// A thigh hanging within this angle of straight down is a standing rest.
constexpr float kStandingThighDeg = 30.0f;
// How far the knee's bend may turn out beyond the pole direction to clear the barrel, and in what
// steps: a little, so the knee still points forward; past that the treads move out instead.
constexpr float kMaxKneeTurnDeg = 20.0f, kKneeTurnStepDeg = 1.0f;
// The spine's bend gain stays within these (a chain far from the thesis rig's bends at most twice as
// much, or half).
constexpr double kMinSpineBendGain = 0.5, kMaxSpineBendGain = 2.0;
// The horse's side kept for posing (Character::LegGuard): where a rider's legs can be, saddle space, in
// 2 cm cells; the room kept between her legs' surface and the horse's as she rides.
constexpr glm::vec2 kGuardMin{-45.0f, -80.0f}, kGuardMax{55.0f, 10.0f};
constexpr float kGuardCellCm = 2.0f, kGuardRoomCm = 0.5f;
// How far the treads may move out from where the horse hangs them, in a few steps: the leathers hang a
// little wider, no more.
constexpr float kMaxTreadOutCm = 10.0f;
constexpr int kMaxTreadOutSteps = 6;
// The arm reaches at most this share of its length at rest: elbows bent about 110°, a rider's hands
// "in a straight line elbow-hand-bit" with the elbow bent and soft, so the wrist channels (forward over
// the jump, back on landing as the trunk leans back) stay within the arm's reach. (The generated
// rider's arms reach 88% at rest, her shoulders 10 cm nearer the saddle than most riders'.)
constexpr float kArmReach = 0.82f;
// The head is turned upright by at most this (a neck's comfortable range is far larger).
constexpr float kMaxHeadTurnDeg = 20.0f;

using pose_transforms::translate;
glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }
glm::vec3 mirror(glm::vec3 v, float side) { return {v.x, v.y, v.z * side}; }  // side -1 left, +1 right

std::optional<int> roleIfMapped(const Character& c, const std::string& role) {
  const auto it = c.roles.find(role);
  if (it == c.roles.end()) return std::nullopt;
  return it->second;
}

// The rotation taking unit a onto unit b by the smallest angle.
glm::mat3 arc(glm::vec3 a, glm::vec3 b) {
  a = glm::normalize(a), b = glm::normalize(b);
  const float c = glm::dot(a, b);
  if (c > 1.0f - 1e-7f) return glm::mat3(1.0f);
  glm::vec3 axis = glm::cross(a, b);
  if (glm::length(axis) < 1e-6f) axis = std::abs(a.x) < 0.9f ? glm::cross(a, glm::vec3(1, 0, 0)) : glm::cross(a, glm::vec3(0, 1, 0));
  return glm::mat3(glm::rotate(glm::mat4(1.0f), std::acos(std::clamp(c, -1.0f, 1.0f)), glm::normalize(axis)));
}

// An orthonormal frame from a direction and a second direction across it.
glm::mat3 frame(glm::vec3 x, glm::vec3 n) {
  x = glm::normalize(x);
  n = glm::normalize(n - x * glm::dot(n, x));
  return glm::mat3(x, n, glm::cross(x, n));
}

// Every joint below `joint` (and itself).
std::vector<char> subtree(const Skeleton& s, int joint) {
  std::vector<char> in(s.size(), 0);
  in[joint] = 1;
  for (std::size_t j = 0; j < s.size(); ++j)
    if (s.joints[j].parent >= 0 && in[s.joints[j].parent]) in[j] = 1;
  return in;
}

int dominantJoint(const SkinnedMesh& m, std::size_t v) {
  int best = 0;
  for (int k = 1; k < kMaxInfluences; ++k)
    if (m.weights[v][k] > m.weights[v][best]) best = k;
  return m.joints[v][best];
}

// The mesh at rest (bind offsets applied), in the character's space.
std::vector<glm::vec3> restMesh(const Character& c) {
  std::vector<glm::vec3> p, n;
  skinMesh(c.mesh, c.skeleton, restWorlds(c.skeleton), p, n);
  return p;
}

int addRigPoint(Character& c, const std::string& role, int parent, glm::vec3 at, SeatReport& report) {
  std::string name = "stirrup_" + role;
  while (c.skeleton.find(name) >= 0) name += "_";
  const int j = c.skeleton.addJoint(name, parent, translate(at - c.skeleton.restPosition(parent)));
  c.skeleton.joints[j].rig_point = true;
  c.roles[role] = j;
  report.added_points.push_back(role + " (" + name + ", under " + c.skeleton.joints[parent].name + ")");
  return j;
}

float statureOf(const std::vector<glm::vec3>& mesh) {
  float lo = 1e30f, hi = -1e30f;
  for (const glm::vec3& p : mesh) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
  return mesh.empty() ? 0.0f : hi - lo;
}

// The hand's grip and the sole's contact with the tread, where the file names no joint for them (or
// names the wrist or ankle itself): points the rig adds, from the mesh of the hand and the foot.
void addMissingPoints(Character& c, const std::vector<glm::vec3>& mesh, float stature, bool sole_under_ball,
                      SeatReport& report) {
  const Skeleton& s = c.skeleton;
  for (const char* side : {"l", "r"}) {
    const std::string n = side;
    const int wrist = c.role(n + "Wrist"), ankle = c.role(n + "Ankle");
    // Grip.
    const auto hand = roleIfMapped(c, n + "Hand");
    if (!hand || *hand == wrist) {
      if (hand) c.roles.erase(n + "Hand");
      const std::vector<char> below = subtree(s, wrist);
      const glm::vec3 w = s.restPosition(wrist);
      glm::vec3 centroid(0.0f);
      int count = 0;
      for (std::size_t v = 0; v < mesh.size(); ++v)
        if (below[dominantJoint(c.mesh, v)]) centroid += mesh[v], ++count;
      const glm::vec3 forearm = glm::normalize(w - s.restPosition(c.role(n + "Elbow")));
      glm::vec3 dir = forearm;
      float length = kHandPerStature * stature;
      if (count > 0 && glm::length(centroid / float(count) - w) > 1.0f) {
        dir = glm::normalize(centroid / float(count) - w);
        float reach = 0.0f;
        for (std::size_t v = 0; v < mesh.size(); ++v)
          if (below[dominantJoint(c.mesh, v)]) reach = std::max(reach, glm::dot(mesh[v] - w, dir));
        if (reach > 1.0f) length = reach;
      }
      addRigPoint(c, n + "Hand", wrist, w + dir * (kGripAlongHand * length), report);
    }
    // Sole: under the ball of the foot, on the sole's surface (the tread carries the sole, not a joint
    // inside the foot).
    const auto ball = roleIfMapped(c, n + "Ball");
    const bool named_ball = ball && *ball != ankle;
    if (named_ball && !sole_under_ball) continue;
    if (ball && !named_ball) c.roles.erase(n + "Ball");
    const std::vector<char> below = subtree(s, ankle);
    float heel = 1e30f, toe = -1e30f, sole = 1e30f, zsum = 0.0f;
    int count = 0;
    for (std::size_t v = 0; v < mesh.size(); ++v)
      if (below[dominantJoint(c.mesh, v)]) {
        heel = std::min(heel, mesh[v].x), toe = std::max(toe, mesh[v].x), sole = std::min(sole, mesh[v].y);
        zsum += mesh[v].z, ++count;
      }
    const glm::vec3 a = s.restPosition(ankle);
    glm::vec3 at;
    if (count == 0) {
      // No foot in the mesh: a foot of the usual length, the ankle a third of it behind the ball.
      const float foot = kFootPerStature * stature;
      at = named_ball ? s.restPosition(*ball) : a + glm::vec3(foot * (kBallFromHeel - 0.2f), 0.0f, 0.0f);
      at.y = std::min(at.y, a.y - 0.045f * stature);
    } else {
      at = named_ball ? s.restPosition(*ball) : glm::vec3(heel + kBallFromHeel * (toe - heel), 0.0f, zsum / float(count));
      at.y = sole;
    }
    addRigPoint(c, n + "Ball", named_ball ? *ball : ankle, at, report);
  }
}

// The horse's half-width at the saddle on one side, where the rider's leg lies: the farthest horse
// surface point from the midline near a point (within `slab` cm fore-aft and up-down), leaving out the
// tack that hangs free or is held (horseLooseTack). Saddle space.
struct HorseWidth {
  std::vector<glm::vec3> points;  // the horse's surface, saddle space, tack left out
  float near(glm::vec3 at, float side, float slab) const {
    float w = -1e30f;
    for (const glm::vec3& p : points)
      if (std::abs(p.x - at.x) < slab && std::abs(p.y - at.y) < slab && p.z * side > 0.0f) w = std::max(w, p.z * side);
    return w;
  }
};

HorseWidth horseWidth(const Character& horse, glm::vec3 saddle) {
  HorseWidth out;
  const std::vector<bool> loose = horseLooseTack(horse);
  const std::vector<glm::vec3> mesh = restMesh(horse);
  for (std::size_t v = 0; v < mesh.size(); ++v)
    if (!loose[v]) out.points.push_back(mesh[v] - saddle);
  return out;
}

// How far a limb's surface reaches toward the body's midline (where the horse will be) from the bone's
// axis (from -> to), standing: the 95th percentile, over the vertices bound mostly to one of `joints`
// within `span` cm along the axis of the point `along` of the way down the bone, of their offset toward
// the midline (a calf is not round: its inner side is what meets the saddle flap).
float limbRadius(const Character& c, const std::vector<glm::vec3>& mesh, const std::vector<int>& joints, glm::vec3 from,
                 glm::vec3 to, float along, float span, float fallback) {
  const glm::vec3 axis = glm::normalize(to - from);
  const glm::vec3 at = from + (to - from) * along;
  glm::vec3 medial(0.0f, 0.0f, from.z < c.skeleton.restPosition(c.role("pelvis")).z ? 1.0f : -1.0f);
  medial = glm::normalize(medial - axis * glm::dot(medial, axis));
  std::vector<float> d;
  for (std::size_t v = 0; v < mesh.size(); ++v) {
    if (std::find(joints.begin(), joints.end(), dominantJoint(c.mesh, v)) == joints.end()) continue;
    const glm::vec3 r = mesh[v] - at;
    const float t = glm::dot(r, axis);
    if (std::abs(t) > span) continue;
    d.push_back(glm::dot(r - axis * t, medial));
  }
  if (d.size() < 8) return fallback;
  std::sort(d.begin(), d.end());
  return std::max(d[d.size() * 95 / 100], 0.0f);
}

// The joints of a limb segment: `from` and any joints between it and `to` (a bone split in two halves,
// Rigify's ".001"), not `to`.
std::vector<int> segmentJoints(const Skeleton& s, int from, int to) {
  std::vector<int> out = {from};
  for (int j : s.pathFrom(from, to))
    if (j != to) out.push_back(j);
  return out;
}

// How far her trunk (pelvis joint to neck, in the pelvis's frame) leans forward for the spine's bend
// alone: lowerBack and waist folded by kBendProbeDeg each (posing with every other channel at rest).
constexpr double kBendProbeDeg = 10.0;
double trunkBendLean(const Character& rider) {
  RiderChannels r{};
  r[RiderChannel::lowerBackRz] = kBendProbeDeg;
  r[RiderChannel::waistRz] = kBendProbeDeg;
  std::vector<glm::mat4> local = restLocals(rider.skeleton), world(rider.skeleton.size());
  poseRiderSpine(rider, r, 10.0, RiderPoseParams{}, local);
  localToWorld(rider.skeleton, local, world);
  const glm::vec3 d = glm::vec3(world[rider.role("neck")][3] - world[rider.role("pelvis")][3]);
  const glm::vec3 rest = rider.skeleton.restPosition(rider.role("neck")) - rider.skeleton.restPosition(rider.role("pelvis"));
  return toDegrees(std::atan2(d.x, d.y)) - toDegrees(std::atan2(rest.x, rest.y));
}

// The gain on her spine's bend that makes her trunk lean for it as the generated rider's trunk does.
float spineBendGain(const Character& rider) {
  static const double reference = trunkBendLean(buildRiderTrunk(RiderParams{}));
  const double own = trunkBendLean(rider);
  if (!(std::abs(own) > 1e-3)) return 1.0f;
  return static_cast<float>(std::clamp(reference / own, kMinSpineBendGain, kMaxSpineBendGain));
}

}  // namespace

Character::FoldGuard foldGuard(const Character& rider, const Character& horse) {
  Character::FoldGuard g;
  // One point per cube: the first vertex met in each (the mesh's order is the file's: deterministic).
  const auto thin = [](const Character& c, const std::vector<char>& keep, const glm::vec3 offset, std::vector<int>& joint,
                       std::vector<glm::vec3>& local) {
    const std::vector<glm::vec3> mesh = restMesh(c);
    const std::vector<glm::mat4> rest = restWorlds(c.skeleton);
    std::unordered_map<std::int64_t, char> seen;
    for (std::size_t v = 0; v < mesh.size(); ++v) {
      const int j = dominantJoint(c.mesh, v);
      if (!keep[j]) continue;
      const glm::ivec3 k(glm::floor((mesh[v] - offset) / kFoldGuardCellCm));
      const std::int64_t key = (std::int64_t(k.x & 0x1FFFFF) << 42) | (std::int64_t(k.y & 0x1FFFFF) << 21) | std::int64_t(k.z & 0x1FFFFF);
      if (!seen.emplace(key, 1).second) continue;
      joint.push_back(j);
      local.push_back(glm::vec3(glm::inverse(rest[j]) * glm::vec4(mesh[v], 1.0f)));
    }
  };
  const Skeleton& rs = rider.skeleton;
  std::vector<char> upper(rs.size(), 1);
  for (const char* role : {"lElbow", "rElbow", "lHip", "rHip"}) {
    const std::vector<char> below = subtree(rs, rider.role(role));
    for (std::size_t j = 0; j < rs.size(); ++j) upper[j] = upper[j] && !below[j];
  }
  thin(rider, upper, glm::vec3(0.0f), g.rider_joint, g.rider_local);
  std::vector<char> neck = subtree(horse.skeleton, horse.role("neck1"));
  // The reins and bit hang from the head but are held, not a surface to keep from.
  for (const char* role : {"lRein", "rRein"})
    if (const auto it = horse.roles.find(role); it != horse.roles.end() && it->second != horse.role("neck1")) {
      const std::vector<char> below = subtree(horse.skeleton, it->second);
      for (std::size_t j = 0; j < neck.size(); ++j) neck[j] = neck[j] && !below[j];
    }
  thin(horse, neck, glm::vec3(0.0f), g.horse_joint, g.horse_local);
  return g;
}

bool restIsStanding(const Character& rider) {
  const Skeleton& s = rider.skeleton;
  for (const char* side : {"l", "r"}) {
    const glm::vec3 thigh = s.restPosition(rider.role(std::string(side) + "Knee")) - s.restPosition(rider.role(std::string(side) + "Hip"));
    if (glm::length(thigh) < 1e-3f) return false;
    if (glm::normalize(thigh).y > -std::cos(toRadians(kStandingThighDeg))) return false;
  }
  return true;
}

namespace {

// One seating in progress: the rider as she is being seated (rig points added), what is decided about
// her joints, and the horse's seat, stirrups and rein grips in saddle space. The steps below fill it in
// order: trunk (a standing rider only), leathers, legs, arms; then the joints are placed.
struct LegFit {
  glm::vec3 knee{0.0f}, ankle{0.0f}, pole{0.0f};
  float turn_deg = 0.0f, clearance = 0.0f, knee_radius = 0.0f, calf_radius = 0.0f;
  bool at_reach = false;
};

struct Seating {
  Character c;
  SeatReport report;
  std::vector<glm::vec3> mesh;  // her mesh at rest, as her file binds it (before this seating)
  float stature = 0.0f;
  glm::mat4 trunk{1.0f};        // where her pelvis and everything it carries go (identity: kept)
  std::vector<std::optional<glm::mat4>> set;  // the seating of joints placed explicitly
  // The horse, saddle space (the saddle's rest is translation-only).
  glm::vec3 seat{0.0f};
  std::array<glm::vec3, 2> stirrup{}, grip{};
  HorseWidth width;
  // Decided: the treads' height (saddle space), how far the leathers change and the treads move out.
  float tread_y = 0.0f, leather_drop = 0.0f, tread_out = 0.0f;
  std::array<LegFit, 2> legs{};

  glm::vec3 at(int j) const { return c.skeleton.restPosition(j); }
  std::string jointName(int j) const { return "\"" + c.skeleton.joints[std::size_t(j)].name + "\""; }
};

Seating startSeating(Character rider, const Character& horse, const std::vector<glm::vec3>& mesh, float stature, SeatReport report) {
  Seating w;
  w.c = std::move(rider);
  w.report = std::move(report);
  w.mesh = mesh;
  w.stature = stature;
  w.set.assign(w.c.skeleton.size(), std::nullopt);
  w.seat = horse.skeleton.restPosition(horse.role("saddle"));
  w.stirrup = {horse.skeleton.restPosition(horse.role("lStirrup")) - w.seat, horse.skeleton.restPosition(horse.role("rStirrup")) - w.seat};
  w.grip = {horse.skeleton.restPosition(horse.role("lRein")) - w.seat, horse.skeleton.restPosition(horse.role("rRein")) - w.seat};
  w.width = horseWidth(horse, w.seat);
  return w;
}

// A standing rider's trunk: turned so the pelvis-to-neck line leans as the generated rider's does at
// rest, the hip joints over the seat, as high above it as her seat bones are below them; the head
// turned up toward the generated rider's (a few degrees at most).
void seatTrunk(Seating& w, const SeatParams& params) {
  const RiderParams built;
  const Character& c = w.c;
  const int pelvis = c.role("pelvis"), neck = c.role("neck"), head = c.role("head");
  const glm::vec3 trunk_now = w.at(neck) - w.at(pelvis);
  if (glm::length(trunk_now) < 1.0f)
    throw InputError("roles.neck: joint " + w.jointName(neck) + " is where the pelvis " + w.jointName(pelvis) + " is (expected the base of the neck)");
  const glm::mat3 trunk_turn = arc(trunk_now, built.neck - built.pelvis);
  const glm::vec3 hips_now = 0.5f * (w.at(c.role("lHip")) + w.at(c.role("rHip")));
  float depth = kSeatDepthPerStature * w.stature;
  {
    const float half = 0.5f * std::abs(w.at(c.role("lHip")).z - w.at(c.role("rHip")).z) + 2.0f;
    float lowest = 1e30f;
    for (std::size_t v = 0; v < w.mesh.size(); ++v) {
      float on_pelvis = 0.0f;
      for (int k = 0; k < kMaxInfluences; ++k)
        if (c.mesh.joints[v][k] == pelvis) on_pelvis += c.mesh.weights[v][k];
      const glm::vec3& p = w.mesh[v];
      if (on_pelvis >= 0.25f && std::abs(p.z - hips_now.z) <= half && p.y < hips_now.y) lowest = std::min(lowest, p.y);
    }
    if (lowest < 1e29f) depth = std::clamp(hips_now.y - lowest, kSeatDepthMin * w.stature, kSeatDepthMax * w.stature);
  }
  w.report.seat_depth_cm = depth;
  const glm::vec3 hips_seated(-params.hip_behind_seat_centre_cm, depth, 0.0f);
  w.trunk = translate(hips_seated) * glm::mat4(trunk_turn) * translate(-hips_now);
  w.set[std::size_t(pelvis)] = w.trunk;

  const glm::vec3 n = apply(w.trunk, w.at(neck));
  const glm::vec3 up_now = trunk_turn * (w.at(head) - w.at(neck));
  glm::mat3 fix = arc(up_now, built.head - built.neck);
  const float angle = toDegrees(std::acos(std::clamp((fix[0][0] + fix[1][1] + fix[2][2] - 1.0f) * 0.5f, -1.0f, 1.0f)));
  if (angle > kMaxHeadTurnDeg) fix = glm::mat3(1.0f);  // a head modelled looking far off: keep it
  w.set[std::size_t(neck)] = translate(n) * glm::mat4(fix) * translate(-n) * w.trunk;
}

// Leathers: with the leg hanging long beside the horse (hip to ankle straight, out to the stirrup's
// side), the tread at the ankle, then taken up by the style.
void setLeathers(Seating& w, const SeatParams& params) {
  const Character& c = w.c;
  float tread_y = 0.0f;
  w.report.leg_cm = 0.0f;
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const glm::vec3 h = apply(w.trunk, w.at(c.role(n + "Hip")));
    const float leg = glm::length(w.at(c.role(n + "Knee")) - w.at(c.role(n + "Hip"))) +
                      glm::length(w.at(c.role(n + "Ankle")) - w.at(c.role(n + "Knee")));
    const float out_to_stirrup = std::max(std::abs(w.stirrup[std::size_t(side)].z) - std::abs(h.z), 0.0f);
    tread_y += 0.5f * (h.y - std::sqrt(std::max(leg * leg - out_to_stirrup * out_to_stirrup, 0.0f)) +
                       params.stirrup_holes_up * kLeatherHoleCm);
    w.report.leg_cm += 0.5f * leg;
  }
  w.tread_y = tread_y;
  w.leather_drop = tread_y - 0.5f * (w.stirrup[0].y + w.stirrup[1].y);  // + raises the treads
  w.report.tread_below_seat_cm = -tread_y;
  w.report.leather_change_cm = -w.leather_drop;
}

// One leg: the sole's contact on the tread (moved `tread_out` away from the horse), heel down; the knee
// bent forward and out, turned further out (up to kMaxKneeTurnDeg) until the leg clears the horse.
LegFit fitLeg(const Seating& w, const SeatParams& params, int side, float tread_out) {
  const Character& c = w.c;
  const std::string n = side == 0 ? "l" : "r";
  const float out_sign = side == 0 ? -1.0f : 1.0f;
  const glm::mat3 heel_down = glm::mat3(glm::rotate(glm::mat4(1.0f), toRadians(params.heel_down_deg), glm::vec3(0, 0, 1)));
  const int hip = c.role(n + "Hip"), knee = c.role(n + "Knee"), ankle = c.role(n + "Ankle"), ball = c.role(n + "Ball");
  const glm::vec3 hs = w.at(hip), ks = w.at(knee), as = w.at(ankle), bs = w.at(ball);
  const float thigh = glm::length(ks - hs), shin = glm::length(as - ks);
  if (thigh < 1.0f || shin < 1.0f)
    throw InputError("roles." + n + "Knee: joint " + w.jointName(knee) + " leaves a thigh or shin of no length (expected the knee between " +
                     w.jointName(hip) + " and " + w.jointName(ankle) + ")");
  const glm::vec3 h = apply(w.trunk, hs);
  const glm::vec3 tread(w.stirrup[std::size_t(side)].x, w.tread_y, w.stirrup[std::size_t(side)].z + out_sign * tread_out);
  LegFit fit;
  fit.ankle = tread + heel_down * (as - bs);
  const glm::vec3 d = fit.ankle - h;
  const float reach = glm::length(d);
  fit.at_reach = reach >= thigh + shin - params.limb_soften_cm;
  const glm::vec3 dir = d / std::max(reach, 1e-3f);
  const float r = std::min(reach, thigh + shin - params.limb_soften_cm);
  const float along = (thigh * thigh - shin * shin + r * r) / (2.0f * r);
  const float across = std::sqrt(std::max(thigh * thigh - along * along, 0.0f));
  const glm::vec3 pole = mirror(params.knee_pole_dir, -out_sign);  // the parameter is the left side's
  const glm::vec3 u0 = glm::normalize(pole - dir * glm::dot(pole, dir));
  glm::vec3 v0 = glm::normalize(glm::cross(dir, u0));
  if (v0.z * out_sign < 0.0f) v0 = -v0;
  const glm::vec3 centre = h + dir * along;
  const std::vector<int> thigh_joints = segmentJoints(c.skeleton, hip, knee), shin_joints = segmentJoints(c.skeleton, knee, ankle);
  std::vector<int> knee_joints = thigh_joints;
  knee_joints.insert(knee_joints.end(), shin_joints.begin(), shin_joints.end());
  const float knee_r = limbRadius(c, w.mesh, knee_joints, ks, as, 0.0f, 5.0f, 0.033f * w.stature);
  float thigh_r = 0.0f;  // the widest of the thigh's upper, middle and lower part
  for (float a : {0.25f, 0.5f, 0.75f})
    thigh_r = std::max(thigh_r, limbRadius(c, w.mesh, thigh_joints, hs, ks, a, 0.1f * thigh, 0.047f * w.stature));
  const float calf_r = limbRadius(c, w.mesh, shin_joints, ks, as, 0.35f, 0.15f * shin, 0.033f * w.stature);
  fit.knee_radius = knee_r;
  fit.calf_radius = calf_r;
  // The smallest clearance along the leg (the thigh's middle and lower part, the knee, the shin).
  // The thigh lies on the saddle (thigh_clearance_cm from it, for the pelvis's roll at the trot), the knee
  // and calf stand clear of it by knee_clearance_cm, which the rider channels' knee and foot movements
  // eat into.
  const auto clearance = [&](glm::vec3 k) {
    float worst = 1e30f;
    const auto check = [&](glm::vec3 p, float radius, float room) {
      const float wide = w.width.near(p, out_sign, 4.0f);
      if (wide > -1e29f) worst = std::min(worst, p.z * out_sign - radius - wide - room);
    };
    for (float t : {0.25f, 0.5f, 0.75f}) check(h + (k - h) * t, thigh_r, params.thigh_clearance_cm);
    check(k, knee_r, params.knee_clearance_cm);
    // The calf with the foot where the channels can take it: in toward the belly by the posing limit
    // (RiderPoseParams::max_foot_in_cm), the heel turned in about the ball by its limit
    // (max_foot_twist_deg), and the leg swung back (the stirrup's swing moves the calf back by about
    // half the foot's).
    const RiderPoseParams limits;
    const glm::vec2 heel(as.x - bs.x, as.z - bs.z);
    const float twist_in = glm::length(heel) * std::sin(toRadians(limits.max_foot_twist_deg));
    const glm::vec3 foot_in = fit.ankle - glm::vec3(0.0f, 0.0f, out_sign * (limits.max_foot_in_cm + twist_in));
    const glm::vec3 swung_back(-0.5f * limits.max_foot_swing_cm, 0.0f, 0.0f);
    for (float t : {0.25f, 0.5f, 0.75f}) {
      check(k + (fit.ankle - k) * t, calf_r, params.knee_clearance_cm);
      check(k + (foot_in - k) * t, calf_r, 0.0f);
      check(k + (foot_in - k) * t + swung_back, calf_r, 0.0f);
    }
    return worst;  // >= 0: clear
  };
  fit.clearance = -1e30f;
  for (float phi = 0.0f; phi <= kMaxKneeTurnDeg + 1e-3f; phi += kKneeTurnStepDeg) {
    const glm::vec3 k = centre + across * (std::cos(toRadians(phi)) * u0 + std::sin(toRadians(phi)) * v0);
    const float cl = clearance(k);
    if (cl > fit.clearance) fit.clearance = cl, fit.turn_deg = phi, fit.knee = k;
    if (cl >= 0.0f) break;
  }
  fit.pole = centre + (fit.knee - centre) * 10.0f;
  return fit;
}

// Both legs; where even the knees' turn leaves a leg against the horse (a thick calf against the flap),
// the treads move out with the leathers hanging wider, as a rider's legs push them.
void fitLegs(Seating& w, const SeatParams& params) {
  w.tread_out = 0.0f;
  for (int attempt = 0;; ++attempt) {
    w.legs = {fitLeg(w, params, 0, w.tread_out), fitLeg(w, params, 1, w.tread_out)};
    const float short_by = -std::min(w.legs[0].clearance, w.legs[1].clearance);
    if (short_by <= 0.01f || attempt >= kMaxTreadOutSteps || w.tread_out >= kMaxTreadOutCm) break;
    w.tread_out = std::min(w.tread_out + short_by, kMaxTreadOutCm);
  }
  w.report.tread_out_cm = w.tread_out;
  const glm::mat3 heel_down = glm::mat3(glm::rotate(glm::mat4(1.0f), toRadians(params.heel_down_deg), glm::vec3(0, 0, 1)));
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const LegFit& fit = w.legs[std::size_t(side)];
    w.report.knee_turn_out_deg = std::max(w.report.knee_turn_out_deg, fit.turn_deg);
    if (fit.at_reach) w.report.notes.push_back(n + " leg: the tread is at the end of its reach");
    if (fit.clearance < 0.0f) w.report.notes.push_back(n + " leg: " + numberText(-fit.clearance) + " cm short of clear of the horse");
    const int hip = w.c.role(n + "Hip"), knee = w.c.role(n + "Knee"), ankle = w.c.role(n + "Ankle");
    const glm::vec3 hs = w.at(hip), ks = w.at(knee), as = w.at(ankle);
    // The standing knee bends forward; the seated one toward the knee chosen.
    const LimbPose limb = solveLimb(hs, ks, as, ks + glm::vec3(50.0f, 0.0f, 0.0f), apply(w.trunk, hs), fit.ankle, fit.pole, 0.0f);
    w.set[std::size_t(hip)] = limb.upper * translate(-hs);
    w.set[std::size_t(knee)] = limb.middle * translate(-ks);
    w.set[std::size_t(ankle)] = translate(limb.end) * glm::mat4(heel_down) * translate(-as);
  }
}

// The palm's normal at rest: the flattest direction of the hand's mesh, signed as a hand hangs from an
// arm held out (palm down in a T-pose, in toward the body with the arms relaxed).
glm::vec3 palmNormal(const Seating& w, int wrist, glm::vec3 hand_now, float out_sign) {
  glm::vec3 palm = -out_sign * glm::cross(hand_now, glm::vec3(1.0f, 0.0f, 0.0f));
  if (glm::length(palm) < 0.2f) palm = glm::vec3(0.0f, -1.0f, 0.0f);
  palm = glm::normalize(palm - hand_now * glm::dot(palm, hand_now));
  const std::vector<char> below = subtree(w.c.skeleton, wrist);
  glm::vec3 mean(0.0f);
  std::vector<glm::vec3> pts;
  for (std::size_t v = 0; v < w.mesh.size(); ++v)
    if (below[std::size_t(dominantJoint(w.c.mesh, v))]) pts.push_back(w.mesh[v]), mean += w.mesh[v];
  if (pts.size() < 12) return palm;
  mean /= float(pts.size());
  glm::mat3 cov(0.0f);
  for (const glm::vec3& p : pts) cov += glm::outerProduct(p - mean, p - mean);
  // The smallest eigenvector by inverse iteration on the covariance made positive definite.
  const glm::mat3 inv = glm::inverse(cov + glm::mat3(1e-3f * (cov[0][0] + cov[1][1] + cov[2][2])));
  glm::vec3 e = palm;
  for (int it = 0; it < 32; ++it) e = glm::normalize(inv * e);
  e = glm::normalize(e - hand_now * glm::dot(e, hand_now));
  if (glm::length(e) > 0.5f) palm = glm::dot(e, palm) < 0.0f ? -e : e;
  return palm;
}

// Arms: the grip on the rein, the hand pointing forward and in with the thumb up, the elbow back and
// down; a rider whose arms do not reach keeps her hands as far forward as they go.
void fitArms(Seating& w, const SeatParams& params) {
  const Character& c = w.c;
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const float out_sign = side == 0 ? -1.0f : 1.0f;
    const int shoulder = c.role(n + "Shoulder"), elbow = c.role(n + "Elbow"), wrist = c.role(n + "Wrist"), hand = c.role(n + "Hand");
    const glm::vec3 ss = w.at(shoulder), es = w.at(elbow), ws = w.at(wrist), gs = w.at(hand);
    const float upper = glm::length(es - ss), fore = glm::length(ws - es);
    if (upper < 1.0f || fore < 1.0f)
      throw InputError("roles." + n + "Elbow: joint " + w.jointName(elbow) + " leaves an upper arm or forearm of no length (expected the elbow between " +
                       w.jointName(shoulder) + " and " + w.jointName(wrist) + ")");
    const glm::vec3 hand_now = glm::length(gs - ws) > 1e-3f ? glm::normalize(gs - ws) : glm::normalize(ws - es);
    const glm::vec3 palm = palmNormal(w, wrist, hand_now, out_sign);
    const glm::vec3 hand_dir = glm::normalize(mirror(params.hand_dir, -out_sign));
    const glm::vec3 palm_seated = glm::vec3(0.0f, 0.0f, -out_sign);  // toward the midline: thumbs up
    const glm::mat3 hand_turn = frame(hand_dir, palm_seated) * glm::transpose(frame(hand_now, palm));
    const glm::vec3 sh = apply(w.trunk, ss);
    glm::vec3 target = w.grip[std::size_t(side)] - hand_turn * (gs - ws);
    const float reach = glm::length(target - sh), most = kArmReach * (upper + fore);
    if (reach > most) {
      w.report.hand_shortfall_cm = std::max(w.report.hand_shortfall_cm, reach - most);
      target = sh + (target - sh) * (most / reach);
    }
    const glm::vec3 pole = 0.5f * (sh + target) + glm::normalize(mirror(params.elbow_pole_dir, -out_sign)) * 40.0f;
    const LimbPose limb = solveLimb(ss, es, ws, es + glm::vec3(-40.0f, 0.0f, 0.0f), sh, target, pole, 0.0f);
    w.set[std::size_t(shoulder)] = limb.upper * translate(-ss);
    w.set[std::size_t(elbow)] = limb.middle * translate(-es);
    w.set[std::size_t(wrist)] = translate(limb.end) * glm::mat4(hand_turn) * translate(-ws);
  }
  if (w.report.hand_shortfall_cm > 0.0f)
    w.report.notes.push_back("hands " + numberText(w.report.hand_shortfall_cm) + " cm short of the rein grips (arms too short)");
}

// The horse's side where her legs lie, for posing to keep her knees and calves out of it.
Character::LegGuard legGuard(const Seating& w) {
  Character::LegGuard g;
  g.x0 = kGuardMin.x;
  g.y0 = kGuardMin.y;
  g.cell_cm = kGuardCellCm;
  g.nx = static_cast<int>(std::ceil((kGuardMax.x - kGuardMin.x) / kGuardCellCm));
  g.ny = static_cast<int>(std::ceil((kGuardMax.y - kGuardMin.y) / kGuardCellCm));
  g.half_width.assign(std::size_t(g.nx) * std::size_t(g.ny), -std::numeric_limits<float>::infinity());
  for (const glm::vec3& p : w.width.points) {
    const int i = static_cast<int>(std::floor((p.x - g.x0) / g.cell_cm)), j = static_cast<int>(std::floor((p.y - g.y0) / g.cell_cm));
    if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) continue;
    float& half = g.half_width[std::size_t(j) * std::size_t(g.nx) + std::size_t(i)];
    half = std::max(half, std::abs(p.z));
  }
  g.knee_radius_cm = std::max(w.legs[0].knee_radius, w.legs[1].knee_radius);
  g.calf_radius_cm = std::max(w.legs[0].calf_radius, w.legs[1].calf_radius);
  g.room_cm = kGuardRoomCm;
  return g;
}

// Every joint where the steps put it, or carried by its parent (the trunk for joints above the
// pelvis): a translation-only rest at its seated place, the file's mesh kept by the bind offsets.
Character placeJoints(const Seating& w) {
  const Skeleton& s = w.c.skeleton;
  const std::size_t nj = s.size();
  std::vector<glm::mat4> m(nj);
  for (std::size_t j = 0; j < nj; ++j) {
    const int p = s.joints[j].parent;
    m[j] = w.set[j] ? *w.set[j] : (p >= 0 ? m[std::size_t(p)] : w.trunk);
  }
  Character seated = w.c;
  Skeleton& ss = seated.skeleton;
  std::vector<glm::vec3> q(nj);
  for (std::size_t j = 0; j < nj; ++j) {
    q[j] = apply(m[j], w.at(static_cast<int>(j)));
    const int p = ss.joints[j].parent;
    ss.joints[j].rest_local = translate(q[j] - (p >= 0 ? q[std::size_t(p)] : glm::vec3(0.0f)));
    ss.joints[j].inverse_bind = translate(-q[j]);
    ss.joints[j].bind_offset = m[j] * w.c.skeleton.joints[j].bind_offset;
  }
  seated.leg_guard = legGuard(w);
  return seated;
}

// The horse's stirrups at the leathers just set (the irons move; the leathers, bound to the saddle and
// the stirrup, stretch or shorten), and out where her legs pushed them.
void moveStirrups(Character& horse, const Seating& w, SeatReport& report) {
  for (const char* role : {"lStirrup", "rStirrup"}) {
    const int j = horse.role(role);
    bool shared = false;
    for (const auto& [other, k] : horse.roles) shared = shared || (k == j && other != role);
    if (shared) {
      report.notes.push_back(std::string("the horse's ") + role + " is not a joint of its own: its leathers were left as they are");
      continue;
    }
    const float out_sign = std::string(role) == "lStirrup" ? -1.0f : 1.0f;
    const glm::mat4 drop = translate(glm::vec3(0.0f, w.leather_drop, out_sign * w.tread_out));
    const std::vector<char> below = subtree(horse.skeleton, j);
    horse.skeleton.joints[std::size_t(j)].rest_local = drop * horse.skeleton.joints[std::size_t(j)].rest_local;
    for (std::size_t k = 0; k < horse.skeleton.size(); ++k)
      if (below[k]) {
        Joint& jt = horse.skeleton.joints[k];
        jt.inverse_bind = jt.inverse_bind * glm::inverse(drop);
        jt.bind_offset = drop * jt.bind_offset;
      }
  }
}

}  // namespace

std::string seatedMisfit(const Character& rider, const Character& horse) {
  const glm::vec3 seat = horse.skeleton.restPosition(horse.role("saddle"));
  std::string why;
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const auto ball = roleIfMapped(rider, n + "Ball"), hand = roleIfMapped(rider, n + "Hand");
    const glm::vec3 tread = horse.skeleton.restPosition(horse.role(n + "Stirrup")) - seat;
    const glm::vec3 grip = horse.skeleton.restPosition(horse.role(n + "Rein")) - seat;
    if (ball && glm::length(rider.skeleton.restPosition(*ball) - tread) > kSeatedFitCm)
      why += (why.empty() ? "" : "; ") + n + " foot " + numberText(glm::length(rider.skeleton.restPosition(*ball) - tread)) + " cm off its tread";
    if (hand && glm::length(rider.skeleton.restPosition(*hand) - grip) > kSeatedFitCm)
      why += (why.empty() ? "" : "; ") + n + " hand " + numberText(glm::length(rider.skeleton.restPosition(*hand) - grip)) + " cm off its rein";
  }
  return why;
}

SeatedRider seatRider(const Character& rider, const Character& horse, const SeatParams& params) {
  SeatReport report;
  report.stirrup_holes_up = params.stirrup_holes_up;
  Character c = rider;
  const bool standing = restIsStanding(c);
  bool complete = true;
  for (const char* side : {"l", "r"}) {
    const std::string n = side;
    const auto hand = roleIfMapped(c, n + "Hand"), ball = roleIfMapped(c, n + "Ball");
    complete = complete && hand && *hand != c.role(n + "Wrist") && ball && *ball != c.role(n + "Ankle");
  }
  // A rider modelled seated keeps her rest where it fits this horse (her feet on its treads, her hands
  // on its reins: the generated rider on the horse she was built for); on another horse her legs and
  // arms are fitted to it as a standing rider's are, her trunk kept as modelled.
  const std::string misfit = standing || !complete ? std::string() : seatedMisfit(c, horse);
  if (!standing && complete && misfit.empty()) return {std::move(c), horse, report};
  const std::vector<glm::vec3> mesh = restMesh(c);
  const float stature = statureOf(mesh);
  report.stature_cm = stature;
  addMissingPoints(c, mesh, stature, standing, report);
  if (!standing && seatedMisfit(c, horse).empty()) return {std::move(c), horse, report};
  if (standing) {
    report.seated_by_rig = true;
    // Where her trunk folds (the balance stage's pivot): her hip joints' midpoint, which the pelvis joint
    // of a user's rig need not be.
    addRigPoint(c, "hipCentre", c.role("pelvis"),
                0.5f * (c.skeleton.restPosition(c.role("lHip")) + c.skeleton.restPosition(c.role("rHip"))), report);
  } else {
    report.fitted_to_horse = true;
    report.notes.push_back("modelled seated, fitted to this horse (" + (misfit.empty() ? seatedMisfit(c, horse) : misfit) + ")");
  }
  Seating w = startSeating(std::move(c), horse, mesh, stature, std::move(report));
  if (standing) seatTrunk(w, params);
  setLeathers(w, params);
  fitLegs(w, params);
  fitArms(w, params);
  SeatedRider out{placeJoints(w), horse, std::move(w.report)};
  if (standing) {
    out.rider.spine_bend_gain = spineBendGain(out.rider);
    out.report.spine_bend_gain = out.rider.spine_bend_gain;
    out.rider.balance_com_height_cm =
        kReferenceComHeightCm * (out.report.tread_below_seat_cm + out.report.seat_depth_cm) / kReferenceHipsToTreadCm;
    out.report.balance_com_height_cm = out.rider.balance_com_height_cm;
  }
  moveStirrups(out.horse, w, out.report);
  return out;
}

std::vector<std::string> addContactPoints(Character& rider) {
  SeatReport report;
  const std::vector<glm::vec3> mesh = restMesh(rider);
  addMissingPoints(rider, mesh, statureOf(mesh), restIsStanding(rider), report);
  return report.added_points;
}

}  // namespace stirrup::rig
