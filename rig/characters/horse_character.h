// The default horse: a bay of about 160 cm at the withers, 240 cm nose to tail, with a saddle,
// saddle pad, girth, stirrups, bridle and reins. Every proportion is a named parameter.
// Bind pose: ground at y = 0, mid-barrel at x = 0, travelling along +X, +Z = the horse's right.
//
// Roles: "root" (rear pivot at the hips), "backMid", "chest", "withers", "neck1", "neck2", "head",
// "saddle" (seat centre, the rider's attachment), "lStirrup", "rStirrup" (tread centres), "tail1".."tail3",
// "lRein", "rRein" (the hand ends of the reins, moved to the rider's hands by placeReins),
// per leg "<leg>Pivot" (where the limb swings: the scapula's pivot, the hip joint), "<leg>Upper" (two-bone chain root: elbow or stifle), "<leg>Middle" (knee or hock),
// "<leg>Fetlock", "<leg>Hoof" (ground contact), leg = lf, rf, lb, rb.
#pragma once

#include <glm/glm.hpp>

#include "rig/character.h"

namespace stirrup::rig {

// Where the rider meets the horse, in saddle space (the seat centre is the origin; left side, z < 0;
// mirrored for the right). The one source of truth for both characters: the horse hangs its stirrups
// and rein ends here, the rider is built with the balls of her feet on the treads and her hands
// closed on the reins.
struct MountParams {
  glm::vec3 stirrup{0.0f, -74.0f, -31.0f};   // left stirrup tread from the seat centre
  glm::vec3 rein_grip{34.0f, 16.0f, -6.0f};  // where the left rein meets the rider's hand
};

struct HorseParams {
  // Trunk (cm, bind pose).
  float withers_height = 160.0f;               // top of the withers
  float withers_x = 40.0f;
  glm::vec3 hips{-60.0f, 128.0f, 0.0f};        // rear pivot, the root
  glm::vec3 back_mid{-8.0f, 128.0f, 0.0f};
  glm::vec3 chest_joint{30.0f, 126.0f, 0.0f};
  glm::vec3 barrel_center{-2.0f, 121.0f, 0.0f};
  glm::vec3 barrel_radii{60.0f, 31.0f, 25.0f};
  glm::vec3 chest_center{48.0f, 118.0f, 0.0f};
  glm::vec3 chest_radii{26.0f, 32.0f, 22.0f};
  glm::vec3 croup_center{-62.0f, 132.0f, 0.0f};
  glm::vec3 croup_radii{32.0f, 24.0f, 24.0f};
  glm::vec3 buttock_center{-76.0f, 118.0f, 10.0f};  // z mirrored per side
  glm::vec3 buttock_radii{18.0f, 24.0f, 13.0f};
  glm::vec3 quarter_center{-60.0f, 102.0f, -16.0f};  // left side; the lateral thigh below the croup
  glm::vec3 quarter_radii{15.0f, 16.0f, 12.0f};
  // Neck and head.
  glm::vec3 neck_base{62.0f, 132.0f, 0.0f};
  glm::vec3 neck_mid{88.0f, 154.0f, 0.0f};
  glm::vec3 poll{108.0f, 174.0f, 0.0f};
  glm::vec3 muzzle{140.0f, 128.0f, 0.0f};
  float neck_base_radius = 24.0f;
  float neck_mid_radius = 15.0f;
  float throat_radius = 10.5f;
  float head_radius = 10.5f;    // at the jowl
  float muzzle_radius = 8.0f;
  float ear_length = 13.0f;
  float mane_radius = 3.5f;
  // Legs: joint positions of the left legs (z is mirrored for the right).
  glm::vec3 fore_scapula{40.0f, 138.0f, -13.0f};   // the scapula's pivot, a third down from its top
  glm::vec3 fore_shoulder{62.0f, 114.0f, -13.0f};  // point of the shoulder
  glm::vec3 fore_elbow{45.0f, 94.0f, -13.0f};
  glm::vec3 fore_knee{52.0f, 54.0f, -13.0f};       // carpus, slightly ahead of the line: bends forward
  glm::vec3 fore_fetlock{48.0f, 20.0f, -13.0f};
  glm::vec3 fore_hoof{52.0f, 0.0f, -13.0f};        // ground contact, the rest hoof place
  glm::vec3 hind_hip{-62.0f, 124.0f, -14.0f};
  glm::vec3 hind_stifle{-44.0f, 96.0f, -14.0f};
  glm::vec3 hind_hock{-78.0f, 52.0f, -14.0f};      // behind the line: bends backward
  glm::vec3 hind_fetlock{-72.0f, 20.0f, -14.0f};
  glm::vec3 hind_hoof{-69.0f, 0.0f, -14.0f};
  float forearm_radius = 8.5f, knee_radius = 5.5f, cannon_radius = 3.8f, fetlock_radius = 4.6f;
  float gaskin_radius = 10.0f, hock_radius = 5.5f;
  float hoof_radius = 6.0f, hoof_height = 8.0f;
  // Tail.
  glm::vec3 tail_root{-92.0f, 146.0f, 0.0f};
  float tail_length = 80.0f;
  // Tack: saddle seat centre ahead of the back-mid pivot, just behind the withers.
  float saddle_x = 10.0f;
  float saddle_seat_height = 6.0f;     // seat above the top of the back
  MountParams mount;
  // Without tack (false): no saddle, stirrups, bridle or reins, nor their joints and roles: a bare horse,
  // as a user's quadruped comes, for the rig's own tack (rig/characters/horse_tack.h).
  bool tack = true;
  float rein_radius = 0.7f, strap_radius = 0.8f;
  // Colours (linear).
  glm::vec3 coat{0.16f, 0.05f, 0.016f};      // bay
  glm::vec3 points{0.02f, 0.014f, 0.01f};    // black legs, mane and tail
  glm::vec3 hoof{0.012f, 0.011f, 0.01f};
  glm::vec3 leather{0.05f, 0.02f, 0.008f};
  glm::vec3 pad{0.02f, 0.03f, 0.09f};        // navy
  glm::vec3 metal{0.55f, 0.55f, 0.57f};
  glm::vec3 eye{0.005f, 0.004f, 0.004f};
  // Mesh.
  float cell = 1.6f;                   // polygonisation grid, cm
};

Character buildHorse(const HorseParams& params);
Character buildDefaultHorse();

}  // namespace stirrup::rig
