// Posing the horse: its travel frame, its body and neck and tail from the horse channels, each leg
// solved to its hoof target, and how far a hoof falls short. World matrices, one per joint of the
// horse's skeleton, for skinMesh. Signs as rig/pose.h gives them.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"
#include "rig/clip.h"
#include "rig/horse_leg.h"

namespace stirrup::rig {

struct HorsePoseParams {
  float hoof_flex_deg = 55.0f;        // pastern fold (hoof sole turning back) when a hoof is lifted
  float hoof_flex_full_lift = 18.0f;  // lift (cm) at which the fold is complete
  HorseLegParams leg;                 // the legs' reach (its soften_cm also softens two-bone legs)
  // How far the body may settle (cm, along the travel frame's up) onto a planted leg that falls short
  // of its print: over the crest of a hill the ground under a hoof drops below the plane the clip
  // carries the body on (trail's trot, 2.3 cm). A horse's trunk sinks onto its stance legs as the
  // fetlocks extend under load, by several centimetres at the trot; 5 cm is an estimate kept below that
  // sink, so a hoof planted farther than this from its leg's reach stays flagged (HorseReach).
  float max_stance_settle_cm = 5.0f;
};

// The travel frame of a horse frame: world from travel-frame coordinates (its origin at (travel_cm, 0,
// travel_z_cm), turned by heading_deg).
glm::mat4 travelMatrix(const HorseFrame& frame);
// The horse's hooves standing square, in its travel frame: (x forward, z right) cm, lf rf lb rb. A
// path clip turns planted hooves about these (scene::ClipSpec::hoof_rest).
std::array<glm::dvec2, 4> restHoofPlaces(const Character& horse);

// The horse at one frame: in its travel frame (travelMatrix); the body (root at the hips) moved and
// turned by rearPivot, the front half turned at backMid (or the back joint rig/horse_body.h finds),
// neck/head/tail by the frame's follow-through spread over the chains the skeleton has (horseBody),
// each leg solved by two-bone IK to its hoof target (rest hoof place + hoof tx/ty/tz), knees bending
// forward in front and hocks backward behind, the pastern folding as the hoof lifts; joints no role or
// chain names carried by their parents. No bone changes length.
// Never a rubber leg: a hoof target beyond its leg's reach leaves the leg at its full reach,
// every bone its own length, and `reach` (when given) records how far short each hoof stays. A planted
// hoof short of its print by HorseReach::kOverReachCm or more first lets the body settle onto it (at
// most HorsePoseParams::max_stance_settle_cm); what is still short after that is recorded.
struct HorseReach {
  // A hoof this far (cm) or more short of its target is over-reached: beyond the two-bone solve's
  // softening (HorseLegParams::soften_cm, 0.3 cm) by more than rounding, and enough to see.
  static constexpr float kOverReachCm = 1.0f;
  std::array<float, 4> short_cm{};  // lf, rf, lb, rb: the fetlock's distance from where its target wants it
  // Whether the hoof is down (its lift, the hoof's ty, 0): a planted hoof short of its target hovers
  // over its print or lands late; a swinging one misses a point in the air.
  std::array<bool, 4> planted{};
  bool overReached(int leg) const { return short_cm[std::size_t(leg)] >= kOverReachCm; }
  bool any() const { return overReached(0) || overReached(1) || overReached(2) || overReached(3); }
};
// A horse keyed by its clip (HorseFrame::keyed_pose) is posed as keyed instead; a keyed hoof is down
// within kKeyedContactCm of its rest height: a hand-keyed stance is not exactly at rest height, as a
// generated one is [E].
inline constexpr double kKeyedContactCm = 0.5;
std::vector<glm::mat4> poseHorse(const Character& horse, const HorseFrame& frame,
                                 const HorsePoseParams& params = {}, HorseReach* reach = nullptr);

}  // namespace stirrup::rig
