// A horse clip: something that, sampled at a time, gives the horse controls of the contract plus
// what the horse's body needs to be posed. Clips are sampled, never stepped: no hidden state, so any
// frame can be evaluated alone (a farm renders frames out of order).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "rig/channels.h"

namespace stirrup::rig {

// The default horse's rest hoof places in its travel frame, (x forward, z right) cm, indexed lf, rf,
// lb, rb (rig/characters/horse_character.cpp; tests/rig/motion/path_clip_test.cpp checks them against
// the built horse). A path clip needs its horse's rest places: a planted hoof stays put only if the
// clip turns it about the same place the horse's skeleton does.
inline constexpr std::array<glm::dvec2, 4> kDefaultHoofRest = {
    glm::dvec2{52.0, -13.0}, glm::dvec2{52.0, 13.0}, glm::dvec2{-69.0, -14.0}, glm::dvec2{-69.0, 14.0}};

// A horse playing its own keyed animation (rig/io/keyed_horse_clip.h) is posed as the file keys it, not
// from its controls: each joint's matrix in the travel frame (travelMatrix takes it to the world), one per
// joint of the horse the clip was made for. `keyed` marks the file's joints; the others (points the rig
// added: tack, grips) hang from their parents as they do at rest.
struct KeyedHorsePose {
  std::vector<glm::mat4> joint;
  std::vector<char> keyed;
};

struct HorseFrame {
  HorseChannels controls;   // contract channels (cm, degrees), offsets from rest in the travel frame
  // The travel frame: its origin on the ground at world (travel_cm, 0, travel_z_cm) and its heading,
  // degrees from +X toward +Z (+ turns right, the sense of rearPivot.ry). Straight clips move along
  // +X only; a path clip (issue 15) moves in both and turns.
  double travel_cm = 0.0;
  double travel_z_cm = 0.0;
  double heading_deg = 0.0;
  // The travel frame's acceleration along its heading (cm/s²), for the balance stage (rig/balance.h:
  // the rider leans against it). Clips leave it 0; bakeFrame measures it from the travel.
  double travel_accel_cm_s2 = 0.0;
  // Its sideways part (cm/s², + toward the horse's right): in a turn the centripetal acceleration,
  // toward the turn's centre, which tilts the apparent vertical the rider balances against (a right
  // turn: +). Measured with travel_accel_cm_s2, the same way; 0 on a straight line.
  double travel_side_accel_cm_s2 = 0.0;
  // Uneven ground (issue 15): the travel frame's origin stands at height ground_y_cm and pitches by
  // ground_pitch_deg (+ nose up, the sense of rearPivot.rz) with the ground under the hooves, and
  // hoof_ground_cm holds the ground under each hoof (indexed lf, rf, lb, rb) as a height above that
  // pitched frame. The channels stay relative to the ground: a hoof's ty is its lift above the ground
  // under it, so a horse standing on a slope does not make the rider bounce. Flat ground: all zero.
  double ground_y_cm = 0.0;
  double ground_pitch_deg = 0.0;
  std::array<double, 4> hoof_ground_cm{};
  // A down hoof the clip slides on purpose (the sliding stop's hind hooves, Kuhnel 5.5), lf rf lb rb:
  // `stirrup check` does not count its slide as a fault.
  std::array<bool, 4> hoof_sliding{};
  // Body follow-through beyond the contract (degrees, + = up / to the right), for posing only.
  double neck_rz = 0.0;
  double head_rz = 0.0;
  double tail_rz = 0.0;
  double tail_ry = 0.0;
  // Set when the clip keys the horse's joints itself (KeyedHorsePose): posing takes them as they are, and
  // the controls above are measured from them (the rider rig reads those).
  std::shared_ptr<const KeyedHorsePose> keyed_pose;
};

// Something the horse moves over that a review shot must show: the fence of a jump. Placed in the
// travel frame: it stands under the middle of the horse (halfway between its rest fore and hind
// hooves) when the horse has travelled `travel_cm`, square across the direction of travel.
struct Obstacle {
  double travel_cm = 0.0;
  double height_cm = 0.0;   // top of the top rail
  double width_cm = 320.0;  // between the wings, across the travel direction
  double depth_cm = 12.0;   // of the rails, along the travel direction
};

class Clip {
 public:
  virtual ~Clip() = default;
  virtual std::string name() const = 0;
  // Seconds; sample() accepts any t and is periodic or clamped as the clip defines.
  virtual double duration() const = 0;
  virtual HorseFrame sample(double seconds) const = 0;
  // The travel frame alone: travel_cm, travel_z_cm, ground_y_cm, heading_deg and ground_pitch_deg to
  // the bit as sample() gives them, the other fields unspecified. A follow camera's filter and the
  // travel's acceleration sample the travel hundreds of times a frame; a clip that can find it
  // without the legs and the trunk (a path clip) says so. By default, sample().
  virtual HorseFrame sampleTravel(double seconds) const { return sample(seconds); }
  // What the clip's horse must clear (empty for most clips).
  virtual std::vector<Obstacle> obstacles() const { return {}; }
};

}  // namespace stirrup::rig
