// Posing the rider: seated in the posed horse's saddle, her spine laid on the curve spine, her limbs
// reaching for the reins and the stirrups, the balance stage turning her trunk. World matrices, one per
// joint of the rider's skeleton, for skinMesh. Signs as rig/pose.h gives them.
//
// Decisions where the contract leaves the sense open (all in saddle space):
//   head.ry          tilts the head's top toward her right (+X rotation), the sense of rearPivot.rx +
//   lowerBack.rx     twists the chest toward her right (about -Y)
//   lFoot/rFoot.rz   toe up: the foot turns about the ball in the stirrup, so the heel drops
//   lFoot/rFoot.ry   toe turns toward the horse's right (about -Y); .rx sole rolls right (+X)
//   lKnee/rKnee.tz/ty move the knee's IK pole (away from the belly / up), scaled by knee_pole_gain
//   lWrist/rWrist    offsets of the hand target in saddle space (not in the rider's chest frame)
//   hair.*, cloth.*  degrees of swing per unit (hair_deg_per_unit, cloth_deg_per_unit); "up" swings
//                    the braid / coat skirt backward and up, "side" toward her right
//   spineC/D/F.ty    the curve spine's stretch: the top of the chain rises by their sum (as the
//                    three joints' offsets added up on the FK spine), Kuhnel's Eq 9 acting on the
//                    chain through CurveSpine::stretchForOffset; neck.ty neck; headA.ty head
//   lowerBack.rx     (with the curve spine) is the top controller's twist, spread along the chain
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "rig/balance.h"
#include "rig/channels.h"
#include "rig/character.h"
#include "rig/curve_spine.h"
#include "rig/rig_profile.h"

namespace stirrup::rig {

struct RiderPoseParams {
  float chest_follow = 0.5f;       // fraction of waist.rz the chest adds on top
  float hair_deg_per_unit = 1.0f;  // braid swing (degrees over the whole braid) per hair.up/side unit
  float cloth_deg_per_unit = 1.0f; // coat-tail swing per cloth.up/side unit
  float limb_soften = 0.5f;        // IK reach softening (cm)
  // The knee channels move the knee's pole point, 50 cm out; this gain makes a knee offset of
  // one cm move the knee by roughly one cm.
  float knee_pole_gain = 3.0f;
  // Posing limits (docs/rider-rig.md, "Posing limits"): the thesis expressions grow with the horse's
  // pitch without bound, so on a 55° rear they fold the rider 170° forward into the neck and swing
  // her feet 130 cm back. The forward lean of the torso relative to the saddle (hip.rz + lowerBack.rz
  // + waist.rz · (1 + chest_follow)) is scaled down to at most max_lean_deg, keeping the proportions
  // between the joints; the stirrup swing (foot tx) and the foot's toe-up turn (foot rz) are clamped.
  float max_lean_deg = 45.0f;
  float max_foot_swing_cm = 15.0f;
  float max_foot_turn_deg = 30.0f;
  // Contact (docs/rider-rig.md, "Posing limits"; tests/rig/contact_test.cpp): on jump and rear Eq 17
  // brings the feet 7.5 cm in against the belly and Eq 16 turns the heels 26° in, which put the
  // calves 6 cm into the saddle flaps; and Eq 8's seat shift back to 10 cm put the seat and the
  // coat's skirt 5 cm into the cantle. The stirrup leather hangs against the flap, so the foot
  // (foot tz, toward the belly) comes in at most max_foot_in_cm and the heel turns in (foot ry)
  // at most max_foot_twist_deg; the pelvis slides back (cog tx) at most max_seat_back_cm, where the
  // buttocks meet the cantle.
  float max_foot_in_cm = 3.0f;
  float max_foot_twist_deg = 15.0f;
  float max_seat_back_cm = 6.0f;
};

// The torso's fold relative to the saddle the channels ask for: hip.rz + lowerBack.rz + waist.rz ·
// (1 + chest_follow), degrees forward.
double torsoFold(const RiderChannels& r, const RiderPoseParams& params);

// The rider channels within the posing limits above (poseMounted applies this).
RiderChannels limitRiderChannels(RiderChannels r, const RiderPoseParams& params, double rider_unit_cm);

// The curve spine's controllers from the rider channels (docs/curve-spine.md, "The rider"): lower =
// lowerBack (ry side, rz lean), middle = waist (rz), top = the chest's follow of the waist
// (chest_follow · waist.rz) with the lowerBack twist, which the chain spreads from the lower back up
// (rx = −lowerBack.rx: the spine's +rx turns the front to her left).
SpineControllers riderSpineControllers(const RiderChannels& r, const RiderPoseParams& params);
// Equation 9 on the chain: the stretch that raises the top of the spine by
// (spineC + spineD + spineF).ty · rider_unit_cm at rest, kept ≥ kMinRiderSpineStretch.
inline constexpr double kMinRiderSpineStretch = 0.25;
double riderSpineStretch(const CurveSpine& spine, const RiderChannels& r, double rider_unit_cm);

// The rider's spine and head, local transforms (saddle space at the pelvis). The torso is the curve
// spine (rig/curve_spine.h): the FK controllers lowerBack/waist/chest are posed from the channels,
// the chain spine0..spine<N> is laid on the curve they drive, and neck and head ride on the chain's
// tip. `local` holds one matrix per rider joint; only pelvis, spine, neck and head entries are
// written.
void poseRiderSpine(const Character& rider, const RiderChannels& r, double rider_unit_cm,
                    const RiderPoseParams& params, std::span<glm::mat4> local);

// The balance stage as poseRider runs it (rig/balance.h): its parameters, and how many times larger
// the channels' fold was than the posing limit let through (limitRiderChannels; 1 when it did not act).
struct BalanceStage {
  RigProfile::Balance params;
  double fold_scale = 1;
  double accel_cm_s2 = 0;  // the horse's travel acceleration (HorseFrame::travel_accel_cm_s2)
  double ground_pitch_deg = 0;  // the ground's slope under the horse (HorseFrame::ground_pitch_deg, + uphill)
};

// The rider seated in the posed horse's saddle, moved by the rider channels (translations in rider
// units; rider_unit_cm converts them). Hands reach for the reins, feet for the stirrups. With
// `balance`, the balance stage turns her trunk about her hips after the spine is laid out (and
// `balance_result`, when given, receives what it decided); without, the channels' pose as it is.
std::vector<glm::mat4> poseRider(const Character& rider, const Character& horse,
                                 std::span<const glm::mat4> horseWorld, const RiderChannels& r,
                                 double rider_unit_cm, const RiderPoseParams& params = {},
                                 const BalanceStage* balance = nullptr, BalanceResult* balance_result = nullptr);

}  // namespace stirrup::rig
