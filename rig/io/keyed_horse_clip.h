// A horse's animation keyed in another tool (Blender, say), read through the horse's roles
// (docs/horse-clips.md, "Your own horse's animation"): the clip block of a scene names the horse's
// own file, or a file with the mapping `stirrup character map` wrote for it, and the animation by name
// (or the first).
//
//   input:  the glTF file and animation; how its joints play the horse roles and its space becomes
//           stirrup's (KeyedHorseMapping); the scene's horse when it is that file's own character
//   output: HorseFrames. The controls of the channel contract are measured from the file's joints in a
//           travel frame that follows the trunk (below), so the rider rig reads the horse's own motion.
//           When the scene's horse is the file's character and the animation travels, every frame also
//           carries the joints exactly as keyed (HorseFrame::keyed_pose), the armature's own motion
//           included: the horse is posed as the animator keyed it, not re-posed from its hoof tracks.
//
// The travel frame: the trunk's place on the ground (the middle of the root and neck1 joints) and its
// heading (root toward neck1), each fitted by a straight line over kTravelWindowS around the time (a
// local linear fit: a steady walk's travel exactly, the stride's surge and sway left in the controls,
// as a rider feels them). An animation whose trunk moves less than kInPlaceSpeedCmS on average is a
// cycle animated in place: it travels at the speed that keeps the lowest hoof still (as a skeleton clip
// mapping's "speed_cm_s": "auto") and is posed from its controls, like any other horse's clip.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

#include <glm/mat4x4.hpp>

#include "rig/character.h"
#include "rig/clip.h"
#include "rig/mapping/character_mapping.h"

namespace stirrup::rig {

// The window (seconds) the travel frame is fitted over: about one stride of a walk, 0.95-1.05 s
// (docs/gait-reference.md), so a stride's own surge and sway average out [E].
inline constexpr double kTravelWindowS = 1.0;
// Below this mean trunk speed (cm/s) an animation is in place: a horse's slowest walk is about 100 cm/s
// (docs/gait-reference.md: 1.6-1.9 m/s typical) [E].
inline constexpr double kInPlaceSpeedCmS = 20.0;

// How a file's joints play the horse roles: role -> joint name (as the importer names them,
// rig/mapping/mapping_skeleton.h gltfJointNames), and the file's space to stirrup's (mappingToRig).
struct KeyedHorseMapping {
  std::map<std::string, std::string> roles;
  glm::dmat4 to_rig{1.0};
  std::string where;  // the mapping file, or the character's file, for messages
};
// The mapping a loaded horse was read with: its roles by its joints' names, its source's space.
KeyedHorseMapping keyedHorseMapping(const Character& horse);
KeyedHorseMapping keyedHorseMapping(const CharacterMapping& mapping, const std::string& file);

// The world transforms of a file's nodes over time, in the file's space: what a keyed horse clip reads
// its joints from. The file's own animation, or motion handed in from elsewhere (`stirrup live`:
// Blender's evaluation of the horse frame by frame, scene/live_rider.h).
class NodeMotion {
 public:
  virtual ~NodeMotion() = default;
  virtual std::string name() const = 0;
  // The first and last key times (seconds, the file's own time: Blender keys its frame F at F / fps).
  virtual double start() const = 0;
  virtual double end() const = 0;
  // A node's world transform at time t, and every node's (entries of nodes nothing moves may be left
  // identity: only the skin's joints are read).
  virtual glm::dmat4 world(int node, double t) const = 0;
  virtual std::vector<glm::dmat4> worlds(double t) const = 0;
};

struct KeyedHorseOptions {
  int skin = 0;  // the horse's skin in the file (a shot holds the rider's too)
  // Every animation of the file played together (GltfAnimation::together: Blender may write a shot as
  // one animation an armature) instead of the one named.
  bool every_animation = false;
  // The travel as keyed, never added: a shot's horse stands where the file keys it, even in place.
  bool keyed_travel_only = false;
  // The nodes' motion in place of the file's animation (the file is still read for the skin).
  std::shared_ptr<const NodeMotion> motion;
};

class KeyedHorseClip final : public Clip {
 public:
  // `ridden`: the scene's horse when it was loaded from `file` (its joints are then keyed exactly); null
  // for another horse's animation played on the scene's horse. Errors are one-line InputErrors naming the
  // file (a role's joint missing, no animation of that name, a bad accessor).
  KeyedHorseClip(const std::filesystem::path& file, const std::string& animation, const KeyedHorseMapping& mapping,
                 const Character* ridden, const KeyedHorseOptions& options = {});
  // The same from a file already read (`file` names it in messages).
  KeyedHorseClip(const tinygltf::Model& model, const std::string& file, const std::string& animation,
                 const KeyedHorseMapping& mapping, const Character* ridden, const KeyedHorseOptions& options = {});
  ~KeyedHorseClip() override;
  KeyedHorseClip(const KeyedHorseClip&) = delete;
  KeyedHorseClip& operator=(const KeyedHorseClip&) = delete;

  std::string name() const override;
  double duration() const override;
  HorseFrame sample(double seconds) const override;
  HorseFrame sampleTravel(double seconds) const override;

  // The animation travels (its trunk's mean speed, cm/s) or is in place (travel added).
  bool inPlace() const;
  double trunkSpeedCmS() const;
  // Whether frames carry the keyed joints (KeyedHorsePose): the scene's own horse, travelling.
  bool keysTheHorse() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stirrup::rig
