// The horse's trunk, neck and tail as posing reads them from its skeleton (docs/characters.md, "Your
// own horse"): which joint the back arches at, the neck's chain from neck1 up to the head and the
// tail's chain from tail1 down, whatever their lengths, so a user's quadruped with any number of back,
// neck and tail joints is posed by the same channels as the generated horse.
//
//  * Back: the backMid role when the horse names one. Without it, the joint of the back's chain (the
//    joints between the root and neck1) nearest the middle between the root and the withers (or neck1
//    without a withers role); the front half turns there as it does at backMid. A back with no joint
//    between the root and the neck does not arch.
//  * Neck: neck1 and every joint on the way from it to the head (the head excluded); the neck's turn
//    is spread over them in equal parts.
//  * Tail: tail1 and its descendants; the swing is spread over the longest line of joints from tail1
//    (a joint turns by the whole swing over that many), so a straight tail of any length bends by the
//    whole swing. A horse without tail1 has no tail to swing.
// Joints no role names and none of these chains hold (a user's extra toes, ears, jaw) are carried by
// their parents as they hang at rest.
#pragma once

#include <vector>

#include "rig/character.h"

namespace stirrup::rig {

struct HorseBody {
  int back_turn = -1;          // the joint the front half turns at (backMid or the one found), or -1
  bool back_from_role = false; // back_turn is the backMid role
  std::vector<int> neck;       // neck1 .. the joint the head hangs from, root first
  std::vector<int> tail;       // tail1 and its descendants, parents first
  int tail_length = 0;         // joints on the longest line from tail1 to a tip
};

HorseBody horseBody(const Character& horse);

}  // namespace stirrup::rig
