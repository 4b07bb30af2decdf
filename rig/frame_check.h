// What `stirrup check` measures on a ridden pair's posed frames, in world space: the faults an animator
// would otherwise find by watching every frame. Two jobs with explicit inputs and outputs:
//
//   const PairCheck check(horse, rider, profile.balance);       // once a pair: what the rules need of it
//   FrameMeasures m = check.measure(frame, seconds, pose, height); // any frame, in any order or thread
//   std::vector<CheckFinding> f = check.judge(measures, pair);   // the frames in order: the findings
//
// The rules (FrameCheckLimits has the numbers and their sources):
//   hoof-slide      a hoof down (hoofDown: its sole on the ground) in two consecutive frames moves
//                   along the ground between them (the least any point of its sole moves: rolling over
//                   the toe is not sliding);
//   over-reach      a hoof short of its target, its leg at full reach (rig::HorseReach: posed from a clip);
//   hoof-in-ground  the lowest vertex of a hoof below the ground under it;
//   rider-in-horse  the deepest rider vertex inside the horse's skin (rig/contact_depth.h, the tack she
//                   holds or stands in left out);
//   hand-off-rein   a hand away from the end of its rein (the horse's lRein / rRein joints);
//   foot-off-stirrup the ball of a foot away from its stirrup tread (the horse's lStirrup / rStirrup);
//   trunk-balance   the trunk's lean (pelvis to neck, from the vertical toward the horse's heading)
//                   outside the balance band the rig profile keeps her in (rig/balance.h).
// A rule the characters cannot be measured by (a horse with no rein joints) is left out and said so
// (PairCheck::unmeasured), never reported clean in silence.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <utility>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"

namespace stirrup::rig {

enum class CheckSeverity { Note, Warning, Failure };
const char* checkSeverityName(CheckSeverity s);  // "note", "warning", "failure"

// Each rule warns at its first number and fails at its second. [C] a figure from a source, [E] an estimate.
struct FrameCheckLimits {
  // A down hoof's controls move at most "a few mm per frame" (the gait reference; `clip info` holds a
  // clip to 3 mm) [C]. Posed, a hoof may stand up to HorseReach::kOverReachCm off its print before
  // over-reach reports it (the shipped walk's landing leaves a sole 0.42 cm behind its print for a
  // frame), so its sole sliding less than that a frame is within what the leg solve leaves [E];
  // 3 cm a frame skates plainly at review size (a pixel is about 1 cm) [E].
  double slide_warn_cm = 1.0, slide_fail_cm = 3.0;
  // Over-reach: rig::HorseReach::kOverReachCm (enough to see) [E]; 5 cm, beyond the stance settle
  // (HorsePoseParams::max_stance_settle_cm), is a hoof clearly hovering over its print [E].
  double reach_warn_cm = 1.0, reach_fail_cm = 5.0;
  // Hooves "never below the ground" (gait reference) [C]: 1 cm for the hoof's rounded sole meeting a
  // slope [E]; 3 cm, a quarter of the default hoof's 12 cm height, hides the coronet band [E].
  double ground_warn_cm = 1.0, ground_fail_cm = 3.0;
  // The default clips press calves on the flaps and the coat on the cantle up to 3.9 cm deep
  // (docs/characters.md, "Contact") [C, measured]; 5 cm is more than cloth pressed on leather [E];
  // 10 cm is a limb through the barrel [E].
  double depth_warn_cm = 5.0, depth_fail_cm = 10.0;
  // A hand on the rein: within 3 cm of the rein's end (the seating tests' tolerance for a hand on its
  // grip) [E]; 10 cm, a hand's width, has let go [E].
  double hand_warn_cm = 3.0, hand_fail_cm = 10.0;
  // The ball of the foot on the tread: 3 cm (the seating tests' tolerance) [E]; 6 cm, half a stirrup
  // iron's 12 cm tread, is out of the iron [E].
  double foot_warn_cm = 3.0, foot_fail_cm = 6.0;
  // The trunk's lean past the profile's band (RigProfile::Balance band_forward_deg / band_back_deg),
  // which the balance stage approaches but never passes: 5 degrees past it [E]; 15 past it [E].
  double lean_warn_deg = 5.0, lean_fail_deg = 15.0;
};

// One frame of one pair, measured. Distances in cm; -1 where the frame gives no measurement.
struct FrameMeasures {
  int frame = 0;
  double time_s = 0;
  std::array<glm::vec3, 4> hoof{};          // lf, rf, lb, rb: the hoof joints, world
  std::array<float, 4> lift_cm{};           // hoofLiftCm: the lowest of the sole's centre and edges above the ground
  std::array<bool, 4> down{};               // hoofDown(lift_cm): the one contact test of a scene's and a shot's frames
  std::array<bool, 4> target_planted{};     // the clip plants the hoof's target (HorseReach::planted): over-reach's
  std::array<bool, 4> sliding{};            // the clip slides it on purpose (HorseFrame::hoof_sliding): no slide fault
  std::array<float, 4> reach_short_cm{};    // HorseReach::short_cm
  std::array<float, 4> below_ground_cm{};   // the hoof's lowest vertex below the ground (0: not below)
  // A down hoof's vertices within kContactBandCm of its lowest (the sole where it meets the ground), by
  // vertex index, ascending, with their world places: a slide is the least any of them moves, so a
  // hoof rolling over its toe (the toe stays) does not slide, and one skating does (every vertex moves).
  static constexpr float kContactBandCm = 1.0f;
  std::array<std::vector<std::pair<int, glm::vec3>>, 4> contact;
  float rider_depth_cm = 0;                 // the deepest rider vertex inside the horse (0: none)
  std::string rider_depth_joint;            // the rider joint that vertex follows most
  std::array<float, 2> hand_off_cm{-1, -1}; // left, right
  std::array<float, 2> foot_off_cm{-1, -1};
  double trunk_lean_deg = 0;                // forward +
};

struct CheckFinding {
  int frame = 0;
  double time_s = 0;
  int pair = 0;
  CheckSeverity severity = CheckSeverity::Note;
  std::string rule;   // hoof-slide, over-reach, ... (above); `limit` and `gait` come from the scene and clip
  std::string where;  // the hoof (lf, rf, lb, rb), side (left, right) or joint; empty for the whole frame
  double value = 0, bound = 0;  // the measurement and the threshold it passed
  std::string text;   // one line, without the frame
};

// The contact test, the one both kinds of frame go through (a scene's, posed by the rig; a baked
// shot's, as its file keys it): a hoof is down when its lift is at most kHoofContactCm. Its lift is how
// far above the ground under it the lowest of three points of its sole stands: the sole's centre and
// the two edges the rig rolls a hoof over when the leg is at its full reach (rig/horse_leg.h:
// HorseLegParams::toe_cm ahead, heel_cm behind), each the hoof joint's rest height below the joint in
// the hoof's own frame (where the sole is, whether the joint is on it or above it). A hoof rolling over its toe at the end of a stance (breakover) or landing on its
// heel keeps that edge on the ground, and is down. Measured from the posed joint, so a baked shot and
// the scene it was baked from find the same hooves down.
//
// 0.3 cm [E, measured]: over every default scene's frames, 99.9% of the hoof-frames the clips plant
// lift 0.32 cm or less by this measure (the rest, 16 of 13 905, hover 0.3-0.8 cm over prints the leg
// cannot quite reach), while a hoof the clip has begun to lift by half a centimetre already moves a
// centimetre a frame at the trot: a band of 0.5 cm read 17 such lift-offs and landings on the default
// scenes' slopes as slides (docs/check.md, "One truth").
inline constexpr double kHoofContactCm = 0.3;
double hoofLiftCm(const glm::mat4& hoof_world, double rest_height_cm, const std::function<double(double x, double z)>& ground_height);
inline bool hoofDown(double lift_cm) { return lift_cm <= kHoofContactCm; }

// How far a down hoof slid between two frames: the least horizontal movement of any point of its sole
// on the ground in both (FrameMeasures::contact: its vertices, and the segments between them); with no
// vertex on the ground in both, the movement of the soles' middles.
double soleSlide(std::span<const std::pair<int, glm::vec3>> before, std::span<const std::pair<int, glm::vec3>> after);

class PairCheck {
 public:
  PairCheck(const Character& horse, const Character& rider, const RigProfile::Balance& band, FrameCheckLimits limits = {});

  // One posed frame: `horse_frame` the clip's frame it was posed from (poseMounted; a baked shot's: its
  // hooves' targets none), its hooves down where their soles touch the ground (hoofDown).
  // `ground_height(x, z)`: the ground's height (cm) under a point (a scene's terrain, a shot's ground
  // mesh, or 0).
  using GroundHeight = std::function<double(double x, double z)>;
  FrameMeasures measure(int frame, double time_s, const HorseFrame& horse_frame, const MountedPose& pose,
                        const GroundHeight& ground_height) const;
  // The findings of a pair's frames in frame order (slides between frames one apart).
  std::vector<CheckFinding> judge(std::span<const FrameMeasures> frames, int pair) const;

  // Rules these characters cannot be measured by, one line each (e.g. "hand-off-rein: the horse has no
  // rein joints (lRein, rRein)").
  const std::vector<std::string>& unmeasured() const { return unmeasured_; }
  const FrameCheckLimits& limits() const { return limits_; }

 private:
  const Character& horse_;
  const Character& rider_;
  RigProfile::Balance band_;
  FrameCheckLimits limits_;
  std::vector<bool> tack_;                       // horse vertices left out of the rider-in-horse surface
  std::array<std::vector<int>, 4> hoof_vertices_;  // the mesh vertices each hoof joint carries most
  std::vector<int> rider_vertex_joint_;          // the joint each rider vertex follows most
  std::array<int, 4> hoof_joint_{};
  std::array<int, 2> rein_{-1, -1}, hand_{-1, -1}, stirrup_{-1, -1}, ball_{-1, -1};
  int saddle_ = -1, pelvis_ = -1, neck_ = -1;
  std::vector<std::string> unmeasured_;
};

}  // namespace stirrup::rig
