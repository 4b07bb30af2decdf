// Tack for a horse that has none (offline, once at load): a user's quadruped read from a file names no
// saddle, stirrups or reins, so the rig adds them where a rider would put them (docs/characters.md,
// "Your own horse").
//
// Where the saddle sits: behind the shoulder blade, on the thoracic back. Saddle fitters place the
// front of the saddle's tree clear of the back edge of the scapula, never over it, so the shoulder moves
// freely, and keep its bearing surface in front of the last rib (T18), off the loins (Equine Therapy
// NZ, "Saddle Placement", equinetherapy.co.nz; N. Shedrick on saddle placement, meisterider.com). The
// deepest point of the seat, where the rider's seat bones rest, then lies about a third of the way
// from the withers back to the hip joints: 30 cm behind the withers over a 100 cm withers-to-hips span
// on the generated horse (HorseParams::saddle_x against withers_x and hips). Here the withers are the
// withers role, or without one the tops of the fore legs (where their chains leave the body's chain),
// the hips the root; the seat centre goes that fraction back from one to the other, on top of the back
// as the mesh's top surface has it there (a vertical line through the midline), raised by the saddle's
// seat height.
//
// Rig points (Joint::rig_point) under the back joint whose skin carries the back there: "saddle" (the
// seat centre), "lStirrup"/"rStirrup" (tread centres: the mount's drop below the seat, out from the
// barrel's widest there by as much as the generated horse's irons hang out from its barrel) and
// "lRein"/"rRein" (the rein hand ends, where the generated rider's hands close on them). The mesh
// gains the tack, bound to those points: a seat with pommel and cantle, pad and flaps as shells around
// the barrel as measured at the saddle (an ellipsoid fitted to its top, bottom and widest), stirrup
// leathers and irons as tubes (each its own piece bound to its stirrup joint, as horseLooseTack in
// rig/characters/seating.h expects), a bit through the mouth and reins from it past the neck to the
// hand ends.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rig/character.h"
#include "rig/characters/horse_character.h"

namespace stirrup::rig {

// The roles a horse's tack plays: all five are mapped, or none and the rig adds them.
inline constexpr const char* kHorseTackRoles[] = {"saddle", "lStirrup", "rStirrup", "lRein", "rRein"};

struct HorseTackParams {
  // The seat centre's place from the withers (0) back to the hips (1): the generated horse's
  // (withers_x 40 - saddle_x 10) / (withers_x 40 - hips.x -60); see the header comment for the sources.
  float seat_back_fraction = 0.30f;
  float seat_above_back_cm = HorseParams{}.saddle_seat_height;  // the seat above the top of the back
  MountParams mount;  // the treads' drop below the seat, the rein grips (the generated rider fits them)
  // How far the tread centres hang out from the barrel's widest: the generated horse's stirrup (31 cm
  // out) against its barrel's half-width (25 cm).
  float tread_out_of_barrel_cm = -MountParams{}.stirrup.z - HorseParams{}.barrel_radii.z;
  // The barrel's length (its ellipsoid's half-length) per withers-to-hips span: the generated horse's 60 / 100.
  float barrel_length_fraction = 0.6f;
  glm::vec3 leather = HorseParams{}.leather, pad = HorseParams{}.pad, metal = HorseParams{}.metal;
  float strap_radius = HorseParams{}.strap_radius, rein_radius = HorseParams{}.rein_radius;
  float cell = HorseParams{}.cell;  // polygonisation grid of the saddle, cm
};

// What the rig measured and placed, in the horse's rest space (cm).
struct HorseTackReport {
  bool added = false;          // false: the horse had its tack
  bool own_saddle = false;     // the horse's mesh has its own saddle: the seat is on it, no saddle added
  int back_joint = -1;         // the joint the saddle hangs from
  glm::vec3 withers{0.0f};     // the withers point used
  glm::vec3 seat{0.0f};        // the seat centre
  float back_top_y = 0.0f;     // the top of the back under it
  float barrel_bottom_y = 0.0f, barrel_half_width = 0.0f;  // the barrel there
  glm::vec3 bit{0.0f};         // the left end of the bit (the right is mirrored about the head's midline)
};

// Adds the tack to a horse without the tack roles (with all five it is left as it is). Throws
// InputError naming `file` (for messages) when the horse's mesh has no back over the saddle's place
// or no head to put a bit in. `own_saddle` flags, vertex by vertex, a saddle modelled with the horse
// (rig/io/gltf_character.h finds it by name): its seat is the saddle's seat (the deepest point along its
// middle), and only the stirrups, bridle and reins are added.
HorseTackReport addHorseTack(Character& horse, const std::string& file, const HorseTackParams& params = {},
                             const std::vector<char>* own_saddle = nullptr);

}  // namespace stirrup::rig
