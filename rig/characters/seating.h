// Seating a user's rider on a horse (offline, once a shot): a character that stands in its own rest
// pose (T-pose, A-pose, arms relaxed) is put in the saddle by the rig, not by its modeller, the way a
// rider mounts: hips flexed into the seat, thighs around the horse's barrel at the saddle, knees bent so
// the ball of each foot rests on its stirrup tread, hands closed on the reins in front of the body, the
// trunk upright and the head up (docs/characters.md, "Seating").
//
// The result is the rider's rest for the rig: every joint at its seated place with a translation-only
// rest (what the posing jobs work from, as for the generated rider, which is built seated), and the
// mesh left exactly as the file bound it, the seating kept per joint in Joint::bind_offset. The stirrup
// leathers are set from the rider's own leg as riders set them: with the leg hanging long beside the
// horse the tread is at the ankle bone, then the leathers are taken up by the seat's style (a few holes
// shorter for jumping than for dressage); the horse's stirrup joints move to the new tread.
//
// A rider whose rest is already seated (the generated rider, its file read back, a user's rider
// modelled sitting) is left as it is; only the points the rig needs and the file does not name (the
// hand's grip, the sole's contact with the tread) are added (Joint::rig_point).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"

namespace stirrup::rig {

// Leathers are taken up from the hanging-leg length (tread at the ankle bone) in holes about 1 in
// (2.5 cm) apart (Dover Saddlery's leathers). Dressage rides long, the iron at the ankle bone with the
// leg hanging (the riding-school rule; the ground check: stirrup to the fingertips); a general-purpose
// (hunt) seat two holes shorter (stirrup to the second finger joint); jumping four holes shorter (two
// holes from 90 cm fences, up to four for 1.20 m: HQ Magazine; Micklem, Complete Horse Riding Manual).
// The rig profile's seat.stirrup_holes_up says how many.
inline constexpr float kLeatherHoleCm = 2.5f;
inline constexpr float kHolesUpDressage = 0.0f, kHolesUpGeneral = 2.0f, kHolesUpJumping = 4.0f;

// The generated rider's balance proportions (rig/characters/rider_character.h with the default
// RiderParams, on the generated horse's mount): her trunk's centre of mass 23.6 cm above her hips
// (trunkComHeight; checked by a test), her hips 10 cm above the seat centre and the treads 74 cm below
// it (MountParams::stirrup). A seated rider's support lean uses a centre-of-mass height in this
// proportion to her own hips-to-tread drop, so she balances over her stirrups as the generated rider
// does: measured from their own skeletons, riders of Winter's proportions (hips to shoulders 0.288 of
// their height, the generated rider 0.235) would lean about a quarter less than the default rider
// as the horse pitches, 3-4 degrees at a jump's landing.
inline constexpr float kReferenceComHeightCm = 23.6f, kReferenceHipsToTreadCm = 84.0f;

struct SeatParams {
  float stirrup_holes_up = kHolesUpGeneral;  // RigProfile::seat.stirrup_holes_up
  // Where the hip joints sit over the seat: 2 cm behind the seat centre, as the generated rider is
  // built (RiderParams::hip.x), her seat bones in the deepest part of the seat.
  float hip_behind_seat_centre_cm = 2.0f;
  // The knee's bend points forward and out around the barrel (RiderParams::knee_pole_dir); the
  // seating turns it further out only as far as the horse's width needs.
  glm::vec3 knee_pole_dir{1.0f, 0.0f, -1.0f};
  float knee_clearance_cm = 1.5f;  // room left between the knee's and calf's surface and the horse's at rest
  float thigh_clearance_cm = 1.0f;  // and between the thigh's and the saddle's (the pelvis rolls at the trot)
  // Elbows hang back, down and a little out (RiderParams::elbow_pole_dir).
  glm::vec3 elbow_pole_dir{-0.5f, -1.0f, -0.45f};
  // The hand's direction on the rein, wrist to grip, left side (the generated rider's
  // -RiderParams::wrist_from_grip): forward, a little down and in toward the withers.
  glm::vec3 hand_dir{6.0f, -1.0f, 1.0f};
  // Heel down: advanced riders hold the ankle at 83.9 ± 5.3° at the trot against a neutral 90° (Kang et
  // al. 2010, Human Movement Science), so the foot turns about 6° toe-up from its standing rest.
  float heel_down_deg = 6.0f;
  float limb_soften_cm = 0.5f;  // as RiderPoseParams::limb_soften
};

// What the seating decided, for the bake's record and `stirrup character map`'s report.
struct SeatReport {
  bool seated_by_rig = false;     // false: the rider's rest was already seated
  // A rider modelled seated (the generated one among them) on a horse whose treads and reins are not
  // where her feet and hands are: her legs and arms fitted to it as a standing rider's, her trunk kept.
  bool fitted_to_horse = false;
  float stirrup_holes_up = 0;     // the leathers taken up this many holes from the hanging-leg length
  float stature_cm = 0;           // the rider's height, crown to sole, standing
  float leg_cm = 0;               // hip joint to ankle, straight
  float seat_depth_cm = 0;        // hip joints above the seat bones (the seat centre)
  float tread_below_seat_cm = 0;  // the stirrup treads below the seat centre after the leathers are set
  float leather_change_cm = 0;    // how much longer (+) or shorter (-) than the horse's leathers as built
  float knee_turn_out_deg = 0;    // how far the knees were turned out beyond knee_pole_dir to clear the barrel
  float tread_out_cm = 0;         // how far the treads moved out from the horse's (her legs clear its sides)
  float hand_shortfall_cm = 0;    // how far short of the rein grips her hands stayed (arms too short), 0 = on them
  float spine_bend_gain = 1;      // Character::spine_bend_gain: her spine bends this much more for the same channels
  float balance_com_height_cm = 0;  // Character::balance_com_height_cm: the support lean's centre-of-mass height
  std::vector<std::string> added_points;  // rig points added (the grips, the sole contacts)
  std::vector<std::string> notes;
};

struct SeatedRider {
  Character rider;
  Character horse;  // the horse with its stirrup joints at the rider's leathers
  SeatReport report;
};

// horseLooseTack (the tack a rider's legs may touch) is in rig/loose_tack.h.

// The points Character::FoldGuard keeps apart, from both at rest (the rider seated in saddle space): her
// head, neck and trunk without her arms below the elbows and her legs, and the horse's neck and head
// (all its first neck joint carries) without the reins, each thinned to one point per kFoldGuardCellCm
// cube and bound rigidly to the joint that moves it most.
inline constexpr float kFoldGuardCellCm = 3.0f;
Character::FoldGuard foldGuard(const Character& rider, const Character& horse);

// True when the rider's rest is standing: both thighs hang within 30° of straight down.
bool restIsStanding(const Character& rider);

// A seated rider fits a horse as she is when the ball of each foot is on its stirrup tread and each hand
// on its rein's grip, within this (cm) at rest: the generated rider on the horse she was built for
// (0 cm; docs/characters.md, "Contact") [E].
inline constexpr float kSeatedFitCm = 1.0f;
// Why a seated rider does not fit `horse` as she is ("l foot 6.2 cm off its tread; ..."), or "" when she
// does (or lacks the ball and hand roles to tell).
std::string seatedMisfit(const Character& rider, const Character& horse);

// A rider modelled seated who does not fit the horse (seatedMisfit) keeps her trunk and has her legs and
// arms fitted as below, the leathers set to her leg (SeatReport::fitted_to_horse).
// Seats `rider` on `horse` (both at rest; the rider in stirrup's axes, +X the way she faces, +Y up,
// cm, anywhere in space). The horse needs its saddle, stirrup and rein roles; the rider her roles
// (rig/mapping/character_mapping.h). Throws InputError naming the role and joint when the rider's geometry
// cannot be seated (a limb of no length, feet above the hips).
SeatedRider seatRider(const Character& rider, const Character& horse, const SeatParams& params = {});

// The contact points seatRider adds to a rider as it finds her at rest (a grip where her file names no
// hand joint or names the wrist; for a standing rider, the sole under the ball of each foot, where the
// tread carries her), and only those: what a shot from another tool needs for its rider to be measured as
// the same rider is in a scene (rig/io/gltf_shot.h; docs/check.md, "One truth"). Returns the points added.
std::vector<std::string> addContactPoints(Character& rider);

}  // namespace stirrup::rig
