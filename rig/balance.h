// The balance stage: how the rider channels' fold becomes the trunk's pose, decided in world space.
// It runs in posing, after the channels are evaluated and the spine is laid out (rig::poseRider), so
// the channels themselves stay exactly Appendix B's (`stirrup rig eval` does not change).
//
// The thesis's expressions fold the rider relative to the saddle. That holds on level ground, but not
// when the horse pitches far: on a 55° rear they ask for a 170° fold (posing limits scaled it to 45°
// relative to the saddle, which left her 24° behind the vertical, pulling the horse over); in the
// buck's kick they fold her back by about the horse's pitch, which the curve spine turns into a lean
// forward of the vertical. Kuhnel 5.4, 5.6 and 9.5 say the opposite: she leans toward the neck as the
// forehand rises and back as the hind end kicks up. Riders do so to keep their centre of mass over
// their base of support (the jumping seat: "centred over her feet").
//
// The stage, per frame, with the trunk's lean measured from the pelvis joint to the neck joint,
// forward toward the horse's head positive:
//   1. channel lean: the world lean the channels' pose gives, extended by the fold the posing limit
//      removed (so the 170° request reads as far forward, not as 45° relative);
//   2. support lean: the lean that moves the trunk's centre of mass (head, arms and trunk) over her
//      base of support, a point between her seat and her stirrups (stirrup_share of the way), as the
//      horse's pitch swings the stirrups ahead of or behind her seat; zero with the saddle level;
//  2b. inertia lean: the lean toward the vertical of gravity less inertia_share of the horse's travel
//      acceleration, so she sits back as the horse brakes and forward as it speeds up (the rest she
//      takes in her legs); a turn's centripetal acceleration will enter here the same way;
//  2c. slope lean: riders lean forward going uphill (off the horse's loins) and sit upright or a little
//      back going downhill. The support term (2.) already holds her trunk near the world's vertical as
//      the slope pitches the horse (her stirrups swing ahead of or behind her seat), so this adds only
//      the riders' own lean: slope_response of the slope forward uphill, downhill_response of it back
//      downhill (0: upright, as on the flat) (docs/paths-and-terrain.md);
//   3. band: their sum approaches band_forward_deg / band_back_deg softly (tanh), so small leans pass
//      as the channels make them and large ones saturate;
//   4. body limits, relative to the saddle: at most max_fold_deg forward (the chest stops short of the
//      horse's neck) and max_extension_deg back;
//   5. amount blends from the channels' pose (0) to this lean (1).
// Folded forward she stands in her stirrups: her seat is at least seat_rise_cm · (fold / max_fold_deg)²
// above where she sits (the square keeps the gaits' few degrees of fold seated); the channels' own
// lift (Eq 7) counts toward it, so she is lifted only where it falls short (a higher seat would
// straighten her legs and press her knees into the horse).
// The result is a turn of the trunk about her hips (the pelvis), which poseRider applies; the neck
// turns back head_counter of it so she keeps looking ahead. A rider on a hill meets the same stage: it
// measures the saddle in the world, whatever tilts it.
//
// Sideways, in a turn (poseMounted, before the steps above): the thesis's roll channels (Eq 2's
// counter-roll of the lower back, Eq 3, 6, 11, 17 and the hair's and cloth's swing) answer the horse's
// roll from the world's vertical (rearPivot.rx). That is right for the gait's sway, a roll about a
// vertical that stays put, which she rides out by keeping her trunk near the vertical. A turn is not
// sway: gravity and the centripetal acceleration a together make an apparent vertical tilted
// atan(a/g) into the turn, and the horse leans into it to balance (about 1° short of it: Brocklehurst,
// Weller and Pfau, Vet. J.). From the apparent vertical the horse in a steady turn is nearly upright,
// and so, sat in line with it, is she; the world's vertical has no claim on her, and counter-rolling
// against the horse's lean would put her outside the apparent vertical, off balance (0.65 of the
// horse's roll on the figure eight). So her roll channels answer the horse's roll from the apparent
// vertical: rearPivot.rx less the tilt turn_share · atan(a/g) (amount blends it like the rest). The
// channels' own response to the roll stays Appendix B's, the sway is answered as before, and a straight
// line (a = 0) is untouched. Why the channels and not a lean added about her hips: the pelvis follows
// them too (Eq 6), so in a steady turn she sits square in the saddle, in line with the horse, where a
// turn about the hips would tip her seat across the saddle while her lower back still counter-rolled.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "rig/channels.h"
#include "rig/character.h"
#include "rig/rig_profile.h"

namespace stirrup::rig {

struct BalanceInput {
  glm::mat4 saddle{1.0f};      // the posed saddle, world
  glm::vec3 seat{0.0f};        // the rider's pelvis joint, world, as the channels place it
  glm::vec3 stirrups{0.0f};    // the middle of the two stirrup treads (where the balls of her feet go), world
  glm::vec3 trunk{0.0f, 1.0f, 0.0f};  // pelvis joint -> neck joint as the channels pose it, world
  double com_height_cm = 26;   // the trunk's centre of mass above her hips (trunkComHeight)
  double fold_scale = 1;       // how many times larger the channels' fold is than the posing limit let through (>= 1)
  double seat_rise_cm = 0;     // how far the channels raise her pelvis joint above its rest place, in the saddle's frame
  double accel_cm_s2 = 0;      // the horse's travel acceleration along its heading (HorseFrame::travel_accel_cm_s2)
  double ground_pitch_deg = 0; // the ground's slope under the horse, + uphill (HorseFrame::ground_pitch_deg)
};

struct BalanceResult {
  double saddle_pitch_deg = 0;   // the saddle's upright from the vertical, + forward (a rear tips it back: negative)
  double pose_lean_deg = 0;      // the trunk's world lean as the channels pose it (within the posing limit)
  double channel_lean_deg = 0;   // 1. the lean the channels ask for
  double support_lean_deg = 0;   // 2.
  double inertia_lean_deg = 0;   // 2b.
  double slope_lean_deg = 0;     // 2c.
  double turn_tilt_deg = 0;      // sideways, in a turn: the tilt of the vertical her roll channels answer (turnTiltDegrees)
  double lean_deg = 0;           // the trunk's world lean after the stage
  double turn_deg = 0;           // lean_deg - pose_lean_deg: the turn about the hips, + forward
  double seat_lift_cm = 0;       // how far the stage raises her seat beyond the channels' (along the saddle's up)
  bool limited = false;          // a body limit (4.) held her
};

// Lean of `v` from the vertical toward `forward` (horizontal, unit), degrees.
double leanDegrees(glm::vec3 v, glm::vec3 forward);

// The saddle's heading: its +X axis laid flat (the horse's forward on the ground).
glm::vec3 saddleHeading(const glm::mat4& saddle);
// The horse's right on the ground, square to `heading` (saddleHeading): a sideways lean is
// leanDegrees(v, sideways(heading)), + toward the horse's right.
glm::vec3 sideways(glm::vec3 heading);

// The horse's roll, degrees, + toward its right (its right hip lower than its left): the line between
// its hip joints (the hind legs' pivots, else their upper joints) from level, in posed world matrices.
double horseRollDegrees(const Character& horse, std::span<const glm::mat4> world);

// The height of the rider's head, arms and trunk's centre of mass above her hips at rest (hipCentre
// where the seating marked it, else the pelvis joint), from
// her skeleton and the segment masses of Plagenhoef, Evans and Abdelnour 1983 (women): trunk 45.0% at
// the middle of hips to shoulders, head and neck 8.2% at the head joint, each arm 4.97% at its elbow.
double trunkComHeight(const Character& rider);

BalanceResult balanceTrunk(const BalanceInput& in, const RigProfile::Balance& params);

// The tilt (degrees, + toward the horse's right) of the vertical her roll channels answer: amount ·
// turn_share of the apparent vertical's, atan(side acceleration / g); 0 on a straight line.
double turnTiltDegrees(double side_accel_cm_s2, const RigProfile::Balance& params);

// The rider channels `r` as they answer the horse's roll from a vertical tilted `tilt_deg` toward its
// right: r plus what the thesis's expressions change when they read rearPivot.rx tilt_deg less. Only
// the channels that read the roll change (Eq 2, 3, 6, 11, 17 and 18, hair.side, cloth.side); r itself
// when tilt_deg is 0.
RiderChannels answerTiltedVertical(const RiderChannels& r, const HorseChannels& horse, const RigProfile& profile,
                                   double tilt_deg);

}  // namespace stirrup::rig
