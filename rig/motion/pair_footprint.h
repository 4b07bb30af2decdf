// The ground a horse and its rider cover at one frame (issue 19: no two horses' bodies intersect at
// any frame of a crowd), and the check over a whole crowd.
//
// The bounding volume. At rest the pair lies inside a box in the horse's bind frame (+X forward, +Y
// up, +Z right, the root at the hips): from the tail's reach to the head's reach, from the ground to
// the rider's crown, as wide as the widest of barrel, quarters and the rider's boots in the stirrups.
// The head and tail are bounded by spheres about the joints they turn from (the neck's base, the tail's
// root), so no neck or tail angle takes them out of the box. At a frame the box's corners are moved as
// poseHorse moves the body (rig/horse_pose.h: rearPivot's translation and its yaw, pitch and roll about the
// hips, then the ground's pitch), the hooves are added where their channels put them, and the tail is
// swung sideways by its own angle; the footprint is the rectangle, square to the travel heading, that
// holds all of those points seen from above, grown by kPoseMarginCm for what the frame's horse channels
// do not say (the back's arch and turn at backMid, the rider's own channels and balance, her braid and
// coat tail). tests/rig/motion/pair_footprint_test.cpp checks that every vertex of the skinned horse and
// rider stays inside it over a path that canters and gallops through turns.
//
// Why a rectangle on the ground: two bodies whose ground shadows do not meet cannot meet, whatever
// their heights, and a rectangle keeps the test cheap (separating axes, four of them).
#pragma once

#include <array>
#include <optional>
#include <span>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "rig/characters/horse_character.h"
#include "rig/character.h"
#include "rig/characters/rider_character.h"
#include "rig/clip.h"

namespace stirrup::rig {

struct PairExtent {
  double back_cm = 0, front_cm = 0;  // bind-frame x of the tail's and the head's reach
  double half_width_cm = 0;          // ± z
  double top_cm = 0;                 // the rider's crown (or the horse's ears), cm above the ground
  glm::dvec3 pivot{0.0};             // the root's rest place (hips): rearPivot turns about it
  glm::dvec3 tail_root{0.0};
  double tail_reach_cm = 0;          // tail length and its hair
  std::array<glm::dvec2, 4> hoof_rest{};  // (x, z), lf rf lb rb
  double hoof_radius_cm = 0;
};

// Grows every footprint on each side (cm), for what the box does not follow: the back's arch and turn at
// backMid, the rider's own channels and balance, her braid and coat tail. Our choice: over a canter and
// gallop through turns the unpadded box already holds the default, largest and smallest pairs' skinned
// meshes, some vertex within a centimetre of its side, so this is headroom for what that ride
// does not do (tests/rig/motion/pair_footprint_test.cpp).
inline constexpr double kPoseMarginCm = 12.0;

PairExtent pairExtent(const HorseParams& horse, const RiderParams& rider);
// A user's pair (issue 60: a crowd pair riding a horse from a file, or a rider from one): the same box,
// measured on both characters' skinned meshes at rest, the rider as seated on this horse (her rest in
// its saddle's space, as the rig poses her). The head's
// reach is a sphere about neck1 holding every horse vertex ahead of it, the tail's one about tail1
// holding every vertex behind it (without a tail1 the body's own end), so no neck or tail angle takes
// them out of the box; width and top from every vertex of both.
PairExtent pairExtent(const Character& horse, const Character& rider);

// A rectangle on the ground, (world x, world z) cm.
struct GroundRect {
  glm::dvec2 center{0.0};
  glm::dvec2 axis{1.0, 0.0};  // unit, along the travel heading
  double half_length = 0, half_width = 0;
};

GroundRect pairFootprint(const PairExtent& extent, const HorseFrame& frame);
// True when the rectangles share any point (separating axes: the two rectangles' four edge directions).
bool overlaps(const GroundRect& a, const GroundRect& b);

// Two pairs whose footprints meet, at the first frame they do. Pairs are indices into the lists given.
struct FootprintOverlap {
  std::size_t a = 0, b = 0;  // a < b
  int frame = 1;             // 1 at t = 0
  double seconds = 0;
};

// Samples every pair's clip at every frame (frame f at (f - 1) / fps seconds, pair i's clip at that
// time plus clip_offsets_s[i]) for `frames` frames and tests every two footprints that could meet (a
// sweep along world x, so a hundred pairs stay cheap). The first overlap found, or nullopt.
std::optional<FootprintOverlap> firstOverlap(std::span<const Clip* const> clips, std::span<const double> clip_offsets_s,
                                             std::span<const PairExtent> extents, double fps, int frames);

}  // namespace stirrup::rig
