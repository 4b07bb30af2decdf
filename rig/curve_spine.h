// A curve spine driven by a traditional three-bone FK spine (Raisani 2004, "Curve based spine rig",
// Part III; project issue 4). The animator rotates three controllers — lower, middle, top — exactly as
// on a three-bone spine; translations and scales are locked (only rotations enter this API). From the
// FK chain a C² cubic (CubicSpline) is built through the root of bone 1, the three bone midpoints and
// the tip of bone 3, and a chain of N equal bones is laid on it:
//
//  * Chain layout (ChainLayout): every joint lies on the curve, the first at its start and the last at
//    its end, and every bone is the same length. A bone is measured the way the skin it drives sees it,
//    along the curve between its two joints, so by default (EqualArcLength) joint j sits at arc length
//    j·L/N and the N bones sum to the curve's exact arc length L: the chain neither kinks nor
//    overshoots, at rest or at any bend, and it moves continuously with the pose. Straight segments
//    between joints on a bent curve are always a little shorter than the arcs they span (the
//    chord-vs-arc deficit, SpineResult::chain_deficit: 0 at rest, 0.06% at ±45°, 0.3% at ±90°, a few
//    percent at hairpins; docs/curve-spine.md). EqualChord instead makes the straight segments equal
//    (Newton's method from the equal-arc layout), for tools that want equal chords; its chain is then
//    as long as the polyline it inscribes, shorter than the curve by that deficit.
//  * Frames: a rotation-minimizing frame (double reflection) runs along the curve from the lower
//    controller's frame; each bone takes that frame at the arc-length middle of the bone, turned by the
//    smallest rotation onto its chord. No Frenet frame, no up vector, hence no flips.
//  * Twist: the top controller's twist rx is spread evenly, bone i (1-based) turning i·rx/N about its
//    own axis (Raisani 2004, Part III: roll = RX / NB per bone, inherited down the chain). The twist is
//    the scalar channel value, never decomposed from a matrix, so 270° or 720° twist just works.
//
// Conventions. Lengths in cm, angles in degrees. World: Y up, +X forward (the rider faces +X), +Z
// right. Bone axes as in both theses' rigs: x along the bone toward its tip, rx twist about x, ry side
// to side, rz bend front/back. At rest every bone points up: bone x = world +Y, bone y = world +X
// (forward), bone z = x × y = world −Z (left). So +rz bends forward (toward +X), +ry leans right
// (toward +Z), and +rx turns the front toward the left (right-hand rule about the bone).
// Rotation order "XYZ" (as XSI's and Maya's default): R = Rz(rz) · Ry(ry) · Rx(rx) on column vectors —
// the twist rx is applied first, about the bone's own axis, then ry, then rz, about the parent's axes.
// Each controller is parented under the one below: world frame of bone k = Rest · R(lower) ⋯ R(k).
#pragma once

#include <array>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "rig/cubic_spline.h"

namespace stirrup::rig {

// Controller rotations in degrees: (rx twist, ry side to side, rz bend front/back).
struct SpineControllers {
  glm::dvec3 lower{0.0}, middle{0.0}, top{0.0};
};

// A joint of the chain: its position and the world frame of the bone starting there (x along the
// bone toward the next joint, y forward at rest, z = x × y). The last joint (the tip) carries the
// frame at the end of the curve, x along the end tangent, with the full twist.
struct SpineJoint {
  glm::dvec3 position{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
};

// How the chain's joints are spaced along the curve (see the header comment).
enum class ChainLayout {
  EqualArcLength,  // bones of equal arc length L/N: the chain is exactly as long as the curve (default)
  EqualChord,      // bones of equal straight length: the chain is the inscribed equilateral polyline
};

// What solve() works out: everything (the `stirrup spine` report and tests read the curve's samples and
// Raisani's length estimate), or the joints alone, which is all a pose reads (rig/rider_pose.cpp): the 129
// samples are most of a solve's arc-length lookups. The joints are the same to the bit either way.
enum class SpineDetail {
  Full,    // every field of SpineResult
  Joints,  // SpineResult::samples left empty and ten_null_length 0; every other field as Full's
};

struct SpineResult {
  std::array<glm::dvec3, 4> fk;               // FK joints: root, tips of bones 1, 2, 3
  std::array<glm::dvec3, 5> curve_points;     // root, three bone midpoints, tip of bone 3
  double length = 0.0;                        // exact arc length of the curve (cm)
  std::vector<glm::dvec3> samples;            // curve points at equal arc length, both ends included
  std::vector<SpineJoint> joints;             // N + 1 joints, root first
  ChainLayout layout = ChainLayout::EqualArcLength;
  double bone_length = 0.0;                   // every bone's length in the layout's measure (cm):
                                              // arc length (EqualArcLength) or chord (EqualChord)
  double chain_length = 0.0;                  // N · bone_length; equals `length` for EqualArcLength
  std::vector<double> bone_chords;            // straight distance between each bone's joints (cm)
  double chain_deficit = 0.0;                 // 1 − Σ bone_chords / length (≥ 0): what straight bones lose
  bool layout_converged = true;               // EqualChord only — false: fell back to equal arcs
  std::vector<double> joint_arc_lengths;      // arc length of every joint along the curve
  std::vector<glm::dquat> untwisted_rotations;  // the joint frames before the twist (RMF on the chord)
  std::vector<double> twist_deg;              // the twist added to each joint, i·rx/N
  double ten_null_length = 0.0;               // Raisani's ten-null length estimate, for comparison
};

// World rotation of a controller's Euler angles (degrees) in the order stated above.
glm::dquat controllerRotation(const glm::dvec3& degrees);
// The rest frame of every spine bone: bone x → world +Y, y → +X, z → −Z.
glm::dquat restBoneFrame();

// Raisani 2004, Part III §2 (and the Appendix A script): ten nulls at equal path percentage, the
// curve's length taken as the distance between the first two times the number of gaps,
// Ctr_Dist(N1, N2) · (NN − 1). Kept only to measure how far it is off the exact length.
inline constexpr int kRaisaniLengthNulls = 10;  // NN, Raisani 2004, Part III §2 and Appendix A
double tenNullLengthEstimate(const CubicSpline& curve);

class CurveSpine {
 public:
  static constexpr int kMinSegments = 3;
  static constexpr int kMaxSegments = 32;
  // Raisani 2004, Part III §1: "for a humanoid character of average height, eight to ten bones".
  static constexpr int kRiderSegments = 10;
  static constexpr int kSampleCount = 129;  // curve samples in SpineResult::samples

  // Throws std::invalid_argument for a non-positive or non-finite length or segments outside 3..32.
  CurveSpine(std::array<double, 3> boneLengths, int segments,
             ChainLayout layout = ChainLayout::EqualArcLength);

  // The curve, joints and frames for one pose. `stretch` (> 0) scales the three FK bone lengths and so
  // the whole spine along its curve — the squash and stretch of Kuhnel's equation 9 acting on the
  // chain; use stretchForOffset to turn a vertical offset in cm into a stretch.
  SpineResult solve(const SpineControllers& controllers, double stretch = 1.0,
                    SpineDetail detail = SpineDetail::Full) const;

  // The curve's frames at arc-length fractions (ascending, each in [0, 1]): the rotation-minimizing
  // frame transported from the lower controller's frame, as solve() transports it, with the top
  // controller's twist spread in proportion to the arc (fraction f turns f·rx about the tangent).
  // For chains that are not laid on the curve (a user's spine, rig/rider_spine.h): each of their
  // bones turns with the frame at its middle, and so keeps its length.
  std::vector<glm::dquat> framesAt(const SpineControllers& controllers, double stretch,
                                   const std::vector<double>& fractions) const;

  // Pieces of solve, for tools and tests.
  std::array<glm::dquat, 3> controllerFrames(const SpineControllers& controllers) const;
  std::array<glm::dvec3, 4> fkJoints(const SpineControllers& controllers, double stretch = 1.0) const;
  CubicSpline curve(const SpineControllers& controllers, double stretch = 1.0) const;

  // Length of the straight FK chain, L1 + L2 + L3.
  double restLength() const { return lengths_[0] + lengths_[1] + lengths_[2]; }
  // The stretch that lengthens the spine by `offsetCm` at rest: (rest + offset) / rest.
  double stretchForOffset(double offsetCm) const { return (restLength() + offsetCm) / restLength(); }

  int segments() const { return segments_; }
  ChainLayout layout() const { return layout_; }
  const std::array<double, 3>& boneLengths() const { return lengths_; }

 private:
  std::array<double, 3> lengths_;
  int segments_;
  ChainLayout layout_;
};

}  // namespace stirrup::rig
