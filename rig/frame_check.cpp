#include "rig/frame_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rig/balance.h"
#include "rig/loose_tack.h"
#include "rig/contact_depth.h"
#include "rig/horse_leg.h"
#include "rig/skin.h"

namespace stirrup::rig {
namespace {

constexpr std::array<const char*, 4> kLegs = {"lf", "rf", "lb", "rb"};
constexpr std::array<const char*, 2> kSides = {"left", "right"};

glm::vec3 at(const std::vector<glm::mat4>& world, int joint) { return glm::vec3(world[std::size_t(joint)][3]); }

// The joint a vertex follows most (its largest weight).
int mainJoint(const SkinnedMesh& mesh, std::size_t v) {
  int best = 0;
  for (int k = 1; k < 4; ++k)
    if (mesh.weights[v][k] > mesh.weights[v][best]) best = k;
  return mesh.joints[v][best];
}

int roleOr(const Character& c, const std::string& role, int missing = -1) {
  const auto it = c.roles.find(role);
  return it == c.roles.end() ? missing : it->second;
}

std::string format(const char* fmt, double a, double b) {
  char text[200];
  std::snprintf(text, sizeof text, fmt, a, b);
  return text;
}

}  // namespace

double soleSlide(std::span<const std::pair<int, glm::vec3>> before, std::span<const std::pair<int, glm::vec3>> after) {
  // Each common vertex's horizontal movement. The sole moves rigidly, so a point between two of them
  // moves by the same blend of their movements: the least movement of any point on the segment joining
  // them is the distance from zero to the segment of their movements, exact for a roll about an edge
  // that passes between vertices.
  std::vector<glm::dvec2> moved;
  std::size_t i = 0, j = 0;
  while (i < before.size() && j < after.size()) {
    if (before[i].first < after[j].first) ++i;
    else if (after[j].first < before[i].first) ++j;
    else {
      const glm::vec3 d = after[j].second - before[i].second;
      moved.emplace_back(d.x, d.z);
      ++i, ++j;
    }
  }
  if (moved.empty()) {
    // No vertex on the ground in both frames (a hoof landing on its other edge): the soles' middles.
    if (before.empty() || after.empty()) return 0;
    glm::dvec3 a(0), b(0);
    for (const auto& [v, p] : before) a += glm::dvec3(p);
    for (const auto& [v, p] : after) b += glm::dvec3(p);
    const glm::dvec3 d = b / double(after.size()) - a / double(before.size());
    return std::hypot(d.x, d.z);
  }
  double least = glm::length(moved[0]);
  for (std::size_t a = 0; a < moved.size(); ++a) {
    least = std::min(least, glm::length(moved[a]));
    for (std::size_t b = a + 1; b < moved.size(); ++b) {
      const glm::dvec2 e = moved[b] - moved[a];
      const double len2 = glm::dot(e, e);
      if (len2 <= 0) continue;
      const double t = std::clamp(-glm::dot(moved[a], e) / len2, 0.0, 1.0);
      least = std::min(least, glm::length(moved[a] + t * e));
    }
  }
  return least;
}

double hoofLiftCm(const glm::mat4& hoof_world, double rest_height_cm, const std::function<double(double x, double z)>& ground_height) {
  // The sole's centre and edges, where the leg solve keeps them: rest_height_cm below the joint in the
  // hoof's own frame (rig/horse_leg.cpp hoofRoll).
  const HorseLegParams edges;
  const float below = -float(rest_height_cm);
  double lowest = 1e30;
  for (const float along : {0.0f, edges.toe_cm, -edges.heel_cm}) {
    const glm::vec3 p(hoof_world * glm::vec4(along, below, 0.0f, 1.0f));
    lowest = std::min(lowest, double(p.y) - ground_height(p.x, p.z));
  }
  return lowest;
}

const char* checkSeverityName(CheckSeverity s) {
  switch (s) {
    case CheckSeverity::Note: return "note";
    case CheckSeverity::Warning: return "warning";
    case CheckSeverity::Failure: return "failure";
  }
  return "note";
}

PairCheck::PairCheck(const Character& horse, const Character& rider, const RigProfile::Balance& band, FrameCheckLimits limits)
    : horse_(horse), rider_(rider), band_(band), limits_(limits), tack_(horseLooseTack(horse)) {
  for (std::size_t leg = 0; leg < 4; ++leg) hoof_joint_[leg] = horse.role(std::string(kLegs[leg]) + "Hoof");
  // A hoof's vertices: those its hoof joint carries most (a user's horse may skin the hoof to joints
  // below it, a toe: those count too).
  const Skeleton& hs = horse.skeleton;
  const auto below = [&hs](int joint, int ancestor) {
    for (int j = joint; j >= 0; j = hs.joints[std::size_t(j)].parent)
      if (j == ancestor) return true;
    return false;
  };
  for (std::size_t v = 0; v < horse.mesh.vertexCount(); ++v) {
    if (tack_[v]) continue;
    const int j = mainJoint(horse.mesh, v);
    for (std::size_t leg = 0; leg < 4; ++leg)
      if (below(j, hoof_joint_[leg])) hoof_vertices_[leg].push_back(int(v));
  }
  for (std::size_t leg = 0; leg < 4; ++leg)
    if (hoof_vertices_[leg].empty())
      unmeasured_.push_back(std::string("hoof-in-ground: ") + kLegs[leg] + ": no vertex of the horse's mesh follows its hoof joint");
  rider_vertex_joint_.resize(rider.mesh.vertexCount());
  for (std::size_t v = 0; v < rider.mesh.vertexCount(); ++v) rider_vertex_joint_[v] = mainJoint(rider.mesh, v);

  saddle_ = roleOr(horse, "saddle");
  for (int side = 0; side < 2; ++side) {
    const std::string n = side == 0 ? "l" : "r";
    // Rein and stirrup joints that are the saddle itself (a user's horse mapped without tack) say nothing.
    const int rein = roleOr(horse, n + "Rein"), stirrup = roleOr(horse, n + "Stirrup");
    rein_[std::size_t(side)] = rein != saddle_ ? rein : -1;
    stirrup_[std::size_t(side)] = stirrup != saddle_ ? stirrup : -1;
    hand_[std::size_t(side)] = roleOr(rider, n + "Hand", roleOr(rider, n + "Wrist"));
    ball_[std::size_t(side)] = roleOr(rider, n + "Ball", roleOr(rider, n + "Ankle"));
  }
  if (rein_[0] < 0 || rein_[1] < 0 || hand_[0] < 0 || hand_[1] < 0)
    unmeasured_.push_back("hand-off-rein: the horse has no rein joints of its own (lRein, rRein) or the rider no hands");
  if (stirrup_[0] < 0 || stirrup_[1] < 0 || ball_[0] < 0 || ball_[1] < 0)
    unmeasured_.push_back("foot-off-stirrup: the horse has no stirrup joints of its own (lStirrup, rStirrup) or the rider no feet");
  pelvis_ = roleOr(rider, "pelvis");
  neck_ = roleOr(rider, "neck");
  if (saddle_ < 0 || pelvis_ < 0 || neck_ < 0) unmeasured_.push_back("trunk-balance: no saddle, pelvis or neck");
}

FrameMeasures PairCheck::measure(int frame, double time_s, const HorseFrame& horse_frame, const MountedPose& pose,
                                 const GroundHeight& ground_height) const {
  FrameMeasures m;
  m.frame = frame;
  m.time_s = time_s;
  std::vector<glm::vec3> hp, hn, rp, rn;
  skinMesh(horse_.mesh, horse_.skeleton, pose.horse, hp, hn);
  skinMesh(rider_.mesh, rider_.skeleton, pose.rider, rp, rn);

  for (std::size_t leg = 0; leg < 4; ++leg) {
    m.hoof[leg] = at(pose.horse, hoof_joint_[leg]);
    double lowest = 1e30;  // the hoof's lowest vertex above the ground under it
    for (const int v : hoof_vertices_[leg]) {
      const glm::vec3& p = hp[std::size_t(v)];
      lowest = std::min(lowest, double(p.y) - ground_height(p.x, p.z));
    }
    if (hoof_vertices_[leg].empty()) lowest = 0;
    m.below_ground_cm[leg] = float(std::max(0.0, -lowest));
    m.lift_cm[leg] = float(hoofLiftCm(pose.horse[std::size_t(hoof_joint_[leg])], horse_.skeleton.restPosition(hoof_joint_[leg]).y, ground_height));
    m.down[leg] = hoofDown(m.lift_cm[leg]);
    m.target_planted[leg] = pose.reach.planted[leg];
    m.sliding[leg] = horse_frame.hoof_sliding[leg];
    m.reach_short_cm[leg] = pose.reach.short_cm[leg];
    if (m.down[leg])
      for (const int v : hoof_vertices_[leg]) {
        const glm::vec3& p = hp[std::size_t(v)];
        if (double(p.y) - ground_height(p.x, p.z) <= lowest + FrameMeasures::kContactBandCm) m.contact[leg].emplace_back(v, p);
      }
  }

  const ContactDepth d = deepestRiderVertexInside(hp, hn, horse_.mesh.indices, tack_, rp);
  m.rider_depth_cm = d.depth_cm;
  if (d.vertex >= 0) m.rider_depth_joint = rider_.skeleton.joints[std::size_t(rider_vertex_joint_[std::size_t(d.vertex)])].name;

  for (std::size_t side = 0; side < 2; ++side) {
    if (rein_[side] >= 0 && hand_[side] >= 0)
      m.hand_off_cm[side] = glm::length(at(pose.horse, rein_[side]) - at(pose.rider, hand_[side]));
    if (stirrup_[side] >= 0 && ball_[side] >= 0)
      m.foot_off_cm[side] = glm::length(at(pose.horse, stirrup_[side]) - at(pose.rider, ball_[side]));
  }
  if (saddle_ >= 0 && pelvis_ >= 0 && neck_ >= 0)
    m.trunk_lean_deg = leanDegrees(at(pose.rider, neck_) - at(pose.rider, pelvis_), saddleHeading(pose.horse[std::size_t(saddle_)]));
  return m;
}

std::vector<CheckFinding> PairCheck::judge(std::span<const FrameMeasures> frames, int pair) const {
  std::vector<CheckFinding> out;
  const FrameCheckLimits& L = limits_;
  // A finding when `value` reaches the warning bound; a failure at the failure bound.
  const auto add = [&](const FrameMeasures& m, const char* rule, std::string where, double value, double warn, double fail,
                       std::string text) {
    if (!(value >= warn)) return;
    const bool failed = value >= fail;
    out.push_back({m.frame, m.time_s, pair, failed ? CheckSeverity::Failure : CheckSeverity::Warning, rule, std::move(where),
                   value, failed ? fail : warn, std::move(text)});
  };
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const FrameMeasures& m = frames[i];
    const FrameMeasures* prev = i > 0 && frames[i - 1].frame == m.frame - 1 ? &frames[i - 1] : nullptr;
    for (std::size_t leg = 0; leg < 4; ++leg) {
      const std::string hoof = kLegs[leg];
      if (prev && prev->down[leg] && m.down[leg] && !prev->sliding[leg] && !m.sliding[leg]) {
        const double slide = soleSlide(prev->contact[leg], m.contact[leg]);
        add(m, "hoof-slide", hoof, slide, L.slide_warn_cm, L.slide_fail_cm,
            hoof + " hoof down slides " + format("%.2f cm along the ground since the frame before (at most %.1f cm a frame)", slide, L.slide_warn_cm));
      }
      const double short_cm = m.reach_short_cm[leg];
      if (m.target_planted[leg]) {
        add(m, "over-reach", hoof, short_cm, L.reach_warn_cm, L.reach_fail_cm,
            hoof + " hoof planted " + format("%.2f cm short of its print, its leg at full reach (no bone stretched; at most %.1f cm)", short_cm, L.reach_warn_cm));
      } else if (short_cm >= L.reach_warn_cm) {
        // A swinging hoof missing a point in the air by a few centimetres: reported, not counted.
        out.push_back({m.frame, m.time_s, pair, CheckSeverity::Note, "over-reach", hoof, short_cm, L.reach_warn_cm,
                       hoof + " hoof in the air " + format("%.2f cm short of its target, its leg at full reach", short_cm, 0)});
      }
      add(m, "hoof-in-ground", hoof, m.below_ground_cm[leg], L.ground_warn_cm, L.ground_fail_cm,
          hoof + " hoof " + format("%.2f cm into the ground (at most %.1f cm)", m.below_ground_cm[leg], L.ground_warn_cm));
    }
    add(m, "rider-in-horse", m.rider_depth_joint, m.rider_depth_cm, L.depth_warn_cm, L.depth_fail_cm,
        "the rider's " + m.rider_depth_joint + format(" %.2f cm inside the horse (at most %.1f cm)", m.rider_depth_cm, L.depth_warn_cm));
    for (std::size_t side = 0; side < 2; ++side) {
      const std::string s = kSides[side];
      if (m.hand_off_cm[side] >= 0)
        add(m, "hand-off-rein", s, m.hand_off_cm[side], L.hand_warn_cm, L.hand_fail_cm,
            s + " hand " + format("%.2f cm from its rein (at most %.1f cm)", m.hand_off_cm[side], L.hand_warn_cm));
      if (m.foot_off_cm[side] >= 0)
        add(m, "foot-off-stirrup", s, m.foot_off_cm[side], L.foot_warn_cm, L.foot_fail_cm,
            s + " foot " + format("%.2f cm from its stirrup tread (at most %.1f cm)", m.foot_off_cm[side], L.foot_warn_cm));
    }
    if (saddle_ >= 0 && pelvis_ >= 0 && neck_ >= 0) {
      const double lean = m.trunk_lean_deg;
      const bool forward = lean >= 0;
      const double band = forward ? band_.band_forward_deg : band_.band_back_deg;
      const double past = std::abs(lean) - band;
      add(m, "trunk-balance", forward ? "forward" : "back", past, L.lean_warn_deg, L.lean_fail_deg,
          format(forward ? "the trunk leans %.1f deg forward, past the balance band's %.0f deg" : "the trunk leans %.1f deg back, past the balance band's %.0f deg",
                 std::abs(lean), band));
    }
  }
  return out;
}

}  // namespace stirrup::rig
