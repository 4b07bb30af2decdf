#include "rig/characters/seating.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "rig/error.h"
#include "rig/ik.h"
#include "rig/skin.h"
#include "rig/characters/rider_character.h"

namespace stirrup::rig {
namespace {

constexpr float kPi = 3.14159265358979323846f;
float radians(float degrees) { return degrees * kPi / 180.0f; }
float degrees(float radians) { return radians * 180.0f / kPi; }

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
constexpr float kSeatDepthMin = 0.035f, kSeatDepthMax = 0.08f;
// A thigh hanging within this angle of straight down is a standing rest.
constexpr float kStandingThighDeg = 30.0f;
// How far the knee's bend may turn out beyond the pole direction to clear the barrel, and in what steps.
constexpr float kMaxKneeTurnDeg = 60.0f, kKneeTurnStepDeg = 1.0f;
// The arm reaches at most this share of its length: a straight arm locks the elbow.
constexpr float kArmReach = 0.97f;
// The head is turned upright by at most this (a neck's comfortable range is far larger).
constexpr float kMaxHeadTurnDeg = 20.0f;

glm::mat4 translate(glm::vec3 t) { return glm::translate(glm::mat4(1.0f), t); }
glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }
glm::vec3 mirror(glm::vec3 v, float side) { return {v.x, v.y, v.z * side}; }  // side -1 left, +1 right

std::optional<int> optionalRole(const Character& c, const std::string& role) {
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
    const auto hand = optionalRole(c, n + "Hand");
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
    const auto ball = optionalRole(c, n + "Ball");
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
// tack that hangs free or is held (stirrups, reins). Saddle space.
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
  std::vector<char> loose(horse.skeleton.size(), 0);
  for (const char* role : {"lStirrup", "rStirrup", "lRein", "rRein"})
    if (const auto j = optionalRole(horse, role); j && *j != horse.role("saddle")) loose[*j] = 1;
  const std::vector<glm::vec3> mesh = restMesh(horse);
  for (std::size_t v = 0; v < mesh.size(); ++v) {
    bool tack = false;
    for (int k = 0; k < kMaxInfluences; ++k) tack = tack || (horse.mesh.weights[v][k] > 0.0f && loose[horse.mesh.joints[v][k]]);
    if (!tack) out.points.push_back(mesh[v] - saddle);
  }
  return out;
}

// A limb's surface radius around a joint: the 80th percentile of the distances from the bone's axis
// (joint -> next joint) of the vertices bound mostly to the joint or its parent within `span` cm of it.
float limbRadius(const Character& c, const std::vector<glm::vec3>& mesh, int joint, glm::vec3 axis_to, float span, float fallback) {
  const Skeleton& s = c.skeleton;
  const glm::vec3 at = s.restPosition(joint);
  const glm::vec3 axis = glm::normalize(axis_to - at);
  const int parent = s.joints[joint].parent;
  std::vector<float> d;
  for (std::size_t v = 0; v < mesh.size(); ++v) {
    const int j = dominantJoint(c.mesh, v);
    if (j != joint && j != parent) continue;
    const glm::vec3 r = mesh[v] - at;
    const float along = glm::dot(r, axis);
    if (std::abs(along) > span) continue;
    d.push_back(glm::length(r - axis * along));
  }
  if (d.size() < 8) return fallback;
  std::sort(d.begin(), d.end());
  return d[d.size() * 8 / 10];
}

}  // namespace

bool restIsStanding(const Character& rider) {
  const Skeleton& s = rider.skeleton;
  for (const char* side : {"l", "r"}) {
    const glm::vec3 thigh = s.restPosition(rider.role(std::string(side) + "Knee")) - s.restPosition(rider.role(std::string(side) + "Hip"));
    if (glm::length(thigh) < 1e-3f) return false;
    if (glm::normalize(thigh).y > -std::cos(radians(kStandingThighDeg))) return false;
  }
  return true;
}

SeatedRider seatRider(const Character& rider, const Character& horse, const SeatParams& params) {
  SeatedRider out;
  out.horse = horse;
  SeatReport& report = out.report;
  report.stirrup_holes_up = params.stirrup_holes_up;
  Character c = rider;
  const bool standing = restIsStanding(c);
  bool complete = true;
  for (const char* side : {"l", "r"}) {
    const std::string n = side;
    const auto hand = optionalRole(c, n + "Hand"), ball = optionalRole(c, n + "Ball");
    complete = complete && hand && *hand != c.role(n + "Wrist") && ball && *ball != c.role(n + "Ankle");
  }
  if (!standing && complete) {
    out.rider = std::move(c);
    return out;
  }
  const std::vector<glm::vec3> standing_mesh = restMesh(c);
  const float stature = statureOf(standing_mesh);
  report.stature_cm = stature;
  addMissingPoints(c, standing_mesh, stature, standing, report);
  if (!standing) {
    out.rider = std::move(c);
    return out;
  }
  report.seated_by_rig = true;
  const Skeleton& s = c.skeleton;
  const std::size_t nj = s.size();
  const auto at = [&](int j) { return s.restPosition(j); };
  const auto jointName = [&](int j) { return "\"" + s.joints[j].name + "\""; };

  // The horse's seat, stirrups and rein grips, in saddle space (the saddle's rest is translation-only).
  const glm::vec3 seat = horse.skeleton.restPosition(horse.role("saddle"));
  const std::array<glm::vec3, 2> stirrup = {horse.skeleton.restPosition(horse.role("lStirrup")) - seat,
                                            horse.skeleton.restPosition(horse.role("rStirrup")) - seat};
  const std::array<glm::vec3, 2> grip = {horse.skeleton.restPosition(horse.role("lRein")) - seat,
                                         horse.skeleton.restPosition(horse.role("rRein")) - seat};
  const HorseWidth width = horseWidth(horse, seat);

  // Trunk: turned so the pelvis-to-neck line leans as the generated rider's does at rest, the hip
  // joints over the seat, as high above it as her seat bones are below them.
  const RiderParams built;
  const int pelvis = c.role("pelvis"), neck = c.role("neck"), head = c.role("head");
  const glm::vec3 trunk_now = at(neck) - at(pelvis);
  if (glm::length(trunk_now) < 1.0f)
    throw InputError("roles.neck: joint " + jointName(neck) + " is where the pelvis " + jointName(pelvis) + " is (expected the base of the neck)");
  const glm::mat3 trunk_turn = arc(trunk_now, built.neck - built.pelvis);
  const glm::vec3 hips_now = 0.5f * (at(c.role("lHip")) + at(c.role("rHip")));
  float depth = kSeatDepthPerStature * stature;
  {
    const float half = 0.5f * std::abs(at(c.role("lHip")).z - at(c.role("rHip")).z) + 2.0f;
    float lowest = 1e30f;
    for (std::size_t v = 0; v < standing_mesh.size(); ++v) {
      float on_pelvis = 0.0f;
      for (int k = 0; k < kMaxInfluences; ++k)
        if (c.mesh.joints[v][k] == pelvis) on_pelvis += c.mesh.weights[v][k];
      const glm::vec3& p = standing_mesh[v];
      if (on_pelvis >= 0.25f && std::abs(p.z - hips_now.z) <= half && p.y < hips_now.y) lowest = std::min(lowest, p.y);
    }
    if (lowest < 1e29f) depth = std::clamp(hips_now.y - lowest, kSeatDepthMin * stature, kSeatDepthMax * stature);
  }
  report.seat_depth_cm = depth;
  const glm::vec3 hips_seated(-params.hip_behind_seat_centre_cm, depth, 0.0f);
  const glm::mat4 trunk = translate(hips_seated) * glm::mat4(trunk_turn) * translate(-hips_now);

  std::vector<std::optional<glm::mat4>> set(nj);  // the seating of joints placed explicitly
  set[pelvis] = trunk;

  // Head up: the neck-to-head line turned toward the generated rider's (a few degrees at most).
  {
    const glm::vec3 n = apply(trunk, at(neck));
    const glm::vec3 up_now = trunk_turn * (at(head) - at(neck));
    glm::mat3 fix = arc(up_now, built.head - built.neck);
    const float angle = degrees(std::acos(std::clamp((fix[0][0] + fix[1][1] + fix[2][2] - 1.0f) * 0.5f, -1.0f, 1.0f)));
    if (angle > kMaxHeadTurnDeg) fix = glm::mat3(1.0f);  // a head modelled looking far off: keep it
    set[neck] = translate(n) * glm::mat4(fix) * translate(-n) * trunk;
  }

  // Leathers: with the leg hanging long beside the horse (hip to ankle straight, out to the
  // stirrup's side), the tread at the ankle, then taken up by the style.
  float tread_y = 0.0f;
  report.leg_cm = 0.0f;
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const glm::vec3 h = apply(trunk, at(c.role(n + "Hip")));
    const float leg = glm::length(at(c.role(n + "Knee")) - at(c.role(n + "Hip"))) +
                      glm::length(at(c.role(n + "Ankle")) - at(c.role(n + "Knee")));
    const float out_to_stirrup = std::max(std::abs(stirrup[side].z) - std::abs(h.z), 0.0f);
    tread_y += 0.5f * (h.y - std::sqrt(std::max(leg * leg - out_to_stirrup * out_to_stirrup, 0.0f)) +
                       params.stirrup_holes_up * kLeatherHoleCm);
    report.leg_cm += 0.5f * leg;
  }
  const float leather_drop = tread_y - 0.5f * (stirrup[0].y + stirrup[1].y);  // + raises the treads
  report.tread_below_seat_cm = -tread_y;
  report.leather_change_cm = -leather_drop;

  // Legs: the sole's contact on the tread, heel down; the knee bent forward and out, turned further
  // out where the barrel needs it.
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const float out_sign = side == 0 ? -1.0f : 1.0f;
    const int hip = c.role(n + "Hip"), knee = c.role(n + "Knee"), ankle = c.role(n + "Ankle"), ball = c.role(n + "Ball");
    const glm::vec3 hs = at(hip), ks = at(knee), as = at(ankle), bs = at(ball);
    const float thigh = glm::length(ks - hs), shin = glm::length(as - ks);
    if (thigh < 1.0f || shin < 1.0f)
      throw InputError("roles." + n + "Knee: joint " + jointName(knee) + " leaves a thigh or shin of no length (expected the knee between " +
                       jointName(hip) + " and " + jointName(ankle) + ")");
    const glm::vec3 h = apply(trunk, hs);
    const glm::vec3 tread(stirrup[side].x, tread_y, stirrup[side].z);
    const glm::mat3 heel_down = glm::mat3(glm::rotate(glm::mat4(1.0f), radians(params.heel_down_deg), glm::vec3(0, 0, 1)));
    const glm::vec3 a = tread + heel_down * (as - bs);
    const glm::vec3 d = a - h;
    const float reach = glm::length(d);
    if (reach >= thigh + shin - params.limb_soften_cm)
      report.notes.push_back(n + " leg: the tread is at the end of its reach");
    const glm::vec3 dir = d / std::max(reach, 1e-3f);
    const float r = std::min(reach, thigh + shin - params.limb_soften_cm);
    const float along = (thigh * thigh - shin * shin + r * r) / (2.0f * r);
    const float across = std::sqrt(std::max(thigh * thigh - along * along, 0.0f));
    const glm::vec3 pole = mirror(params.knee_pole_dir, out_sign);
    const glm::vec3 u0 = glm::normalize(pole - dir * glm::dot(pole, dir));
    glm::vec3 v0 = glm::normalize(glm::cross(dir, u0));
    if (v0.z * out_sign < 0.0f) v0 = -v0;
    const glm::vec3 centre = h + dir * along;
    const float knee_r = limbRadius(c, standing_mesh, knee, as, 5.0f, 0.033f * stature);
    const float thigh_r = limbRadius(c, standing_mesh, hip, ks, 0.3f * thigh, 0.047f * stature);
    // The smallest clearance along the leg (the thigh's middle and lower part, the knee, the top of the shin).
    const auto clearance = [&](glm::vec3 k) {
      float worst = 1e30f;
      const auto check = [&](glm::vec3 p, float radius) {
        const float w = width.near(p, out_sign, 4.0f);
        if (w > -1e29f) worst = std::min(worst, p.z * out_sign - radius - w);
      };
      for (float t : {0.5f, 0.75f}) check(h + (k - h) * t, thigh_r);
      check(k, knee_r);
      check(k + (a - k) * 0.25f, knee_r);
      return worst;
    };
    float best_phi = 0.0f, best_clear = -1e30f;
    for (float phi = 0.0f; phi <= kMaxKneeTurnDeg + 1e-3f; phi += kKneeTurnStepDeg) {
      const glm::vec3 k = centre + across * (std::cos(radians(phi)) * u0 + std::sin(radians(phi)) * v0);
      const float cl = clearance(k);
      if (cl > best_clear) best_clear = cl, best_phi = phi;
      if (cl >= params.knee_clearance_cm) {
        best_phi = phi;
        best_clear = cl;
        break;
      }
    }
    report.knee_turn_out_deg = std::max(report.knee_turn_out_deg, best_phi);
    if (best_clear < params.knee_clearance_cm)
      report.notes.push_back(n + " leg: " + numberText(params.knee_clearance_cm - best_clear) + " cm short of clear of the horse");
    const glm::vec3 k = centre + across * (std::cos(radians(best_phi)) * u0 + std::sin(radians(best_phi)) * v0);
    // The standing knee bends forward; the seated one toward k.
    const LimbPose limb = solveLimb(hs, ks, as, ks + glm::vec3(50.0f, 0.0f, 0.0f), h, a, centre + (k - centre) * 10.0f, 0.0f);
    set[hip] = limb.upper * translate(-hs);
    set[knee] = limb.middle * translate(-ks);
    set[ankle] = translate(limb.end) * glm::mat4(heel_down) * translate(-as);
  }

  // Arms: the grip on the rein, the hand pointing forward and in with the thumb up, the elbow back and
  // down; a rider whose arms do not reach keeps her hands as far forward as they go.
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    const float out_sign = side == 0 ? -1.0f : 1.0f;
    const int shoulder = c.role(n + "Shoulder"), elbow = c.role(n + "Elbow"), wrist = c.role(n + "Wrist"), hand = c.role(n + "Hand");
    const glm::vec3 ss = at(shoulder), es = at(elbow), ws = at(wrist), gs = at(hand);
    const float upper = glm::length(es - ss), fore = glm::length(ws - es);
    if (upper < 1.0f || fore < 1.0f)
      throw InputError("roles." + n + "Elbow: joint " + jointName(elbow) + " leaves an upper arm or forearm of no length (expected the elbow between " +
                       jointName(shoulder) + " and " + jointName(wrist) + ")");
    // The palm's normal at rest: the flattest direction of the hand's mesh, signed as a hand hangs from
    // an arm held out (palm down in a T-pose, in toward the body with the arms relaxed).
    const glm::vec3 hand_now = glm::length(gs - ws) > 1e-3f ? glm::normalize(gs - ws) : glm::normalize(ws - es);
    glm::vec3 palm = -out_sign * glm::cross(hand_now, glm::vec3(1.0f, 0.0f, 0.0f));
    if (glm::length(palm) < 0.2f) palm = glm::vec3(0.0f, -1.0f, 0.0f);
    palm = glm::normalize(palm - hand_now * glm::dot(palm, hand_now));
    {
      const std::vector<char> below = subtree(s, wrist);
      glm::vec3 mean(0.0f);
      std::vector<glm::vec3> pts;
      for (std::size_t v = 0; v < standing_mesh.size(); ++v)
        if (below[dominantJoint(c.mesh, v)]) pts.push_back(standing_mesh[v]), mean += standing_mesh[v];
      if (pts.size() >= 12) {
        mean /= float(pts.size());
        glm::mat3 cov(0.0f);
        for (const glm::vec3& p : pts) cov += glm::outerProduct(p - mean, p - mean);
        // The smallest eigenvector by inverse iteration on the covariance made positive definite.
        const glm::mat3 inv = glm::inverse(cov + glm::mat3(1e-3f * (cov[0][0] + cov[1][1] + cov[2][2])));
        glm::vec3 e = palm;
        for (int it = 0; it < 32; ++it) e = glm::normalize(inv * e);
        e = glm::normalize(e - hand_now * glm::dot(e, hand_now));
        if (glm::length(e) > 0.5f) palm = glm::dot(e, palm) < 0.0f ? -e : e;
      }
    }
    const glm::vec3 hand_dir = glm::normalize(mirror(params.hand_dir, -out_sign));
    const glm::vec3 palm_seated = glm::vec3(0.0f, 0.0f, -out_sign);  // toward the midline: thumbs up
    const glm::mat3 hand_turn = frame(hand_dir, palm_seated) * glm::transpose(frame(hand_now, palm));
    const glm::vec3 sh = apply(trunk, ss);
    glm::vec3 w = grip[side] - hand_turn * (gs - ws);
    const float reach = glm::length(w - sh), most = kArmReach * (upper + fore);
    if (reach > most) {
      report.hand_shortfall_cm = std::max(report.hand_shortfall_cm, reach - most);
      w = sh + (w - sh) * (most / reach);
    }
    const glm::vec3 pole = 0.5f * (sh + w) + glm::normalize(mirror(params.elbow_pole_dir, -out_sign)) * 40.0f;
    const LimbPose limb = solveLimb(ss, es, ws, es + glm::vec3(-40.0f, 0.0f, 0.0f), sh, w, pole, 0.0f);
    set[shoulder] = limb.upper * translate(-ss);
    set[elbow] = limb.middle * translate(-es);
    set[wrist] = translate(limb.end) * glm::mat4(hand_turn) * translate(-ws);
  }
  if (report.hand_shortfall_cm > 0.0f)
    report.notes.push_back("hands " + numberText(report.hand_shortfall_cm) + " cm short of the rein grips (arms too short)");

  // Every joint: placed, or carried by its parent (the trunk for joints above the pelvis).
  std::vector<glm::mat4> m(nj);
  for (std::size_t j = 0; j < nj; ++j) {
    const int p = s.joints[j].parent;
    m[j] = set[j] ? *set[j] : (p >= 0 ? m[p] : trunk);
  }
  Character seated = c;
  Skeleton& ss = seated.skeleton;
  std::vector<glm::vec3> q(nj);
  for (std::size_t j = 0; j < nj; ++j) {
    q[j] = apply(m[j], at(static_cast<int>(j)));
    const int p = ss.joints[j].parent;
    ss.joints[j].rest_local = translate(q[j] - (p >= 0 ? q[p] : glm::vec3(0.0f)));
    ss.joints[j].inverse_bind = translate(-q[j]);
    ss.joints[j].bind_offset = m[j] * c.skeleton.joints[j].bind_offset;
  }
  out.rider = std::move(seated);

  // The horse's stirrups at the leathers just set (the irons move; the leathers, bound to the saddle
  // and the stirrup, stretch or shorten).
  for (const char* role : {"lStirrup", "rStirrup"}) {
    const int j = out.horse.role(role);
    bool shared = false;
    for (const auto& [other, k] : out.horse.roles) shared = shared || (k == j && other != role);
    if (shared) {
      report.notes.push_back(std::string("the horse's ") + role + " is not a joint of its own: its leathers were left as they are");
      continue;
    }
    const glm::mat4 drop = translate(glm::vec3(0.0f, leather_drop, 0.0f));
    const std::vector<char> below = subtree(out.horse.skeleton, j);
    out.horse.skeleton.joints[j].rest_local = drop * out.horse.skeleton.joints[j].rest_local;
    for (std::size_t k = 0; k < out.horse.skeleton.size(); ++k)
      if (below[k]) {
        Joint& jt = out.horse.skeleton.joints[k];
        jt.inverse_bind = jt.inverse_bind * glm::inverse(drop);
        jt.bind_offset = drop * jt.bind_offset;
      }
  }
  return out;
}

}  // namespace stirrup::rig
