// The rider kept on a horse keyed live in another tool (`stirrup live`; the Blender add-on's Live toggle,
// docs/blender.md): the characters read and seated once, then, frame by frame, the horse's pose in and
// the rider's out.
//
//   input:  the horse's glTF file as the tool exported it, with its mapping (its animation, if any, is the
//           horse's motion until frames are handed in); the pair as the scene resolved it (the horse from
//           that file, the rider seated: scene/ridden_pair.h); the rig profile; the frame rate and the
//           tool's frames (its frame F at F / fps of the file's time, as Blender's exporter keys it).
//   a frame in:  every joint of the horse's skin as a deformation in the file's space (the tool's pose of
//           it: the joint's world times its inverse bind, the matrix skinning applies), replacing that
//           frame of the horse's motion.
//   a frame out: every joint of the rider's file (the rig's own points left out) as a deformation from her
//           rest in her file to where she sits, in the horse's file's space: H^-1 S R, S stirrup's skin
//           matrix, H and R the horse's and her mapping's to_rig. It is what `stirrup bake --rider-only`
//           keys (R^-1 S R, rig/io/gltf_rider_motion.h) taken from her file to the horse's, which is the
//           tool's world: it poses her bones there whatever either armature's object transform.
//
//   and with it the horse's tack (kHorseTackRoles: the saddle, the stirrup treads, the rein hand ends) as
//           stirrup poses it under her (rig::placeStirrups, rig::placeReins): each tack joint as a
//           deformation from its rest in the horse's file to where it is, in the horse's file's space:
//           H^-1 T H, T stirrup's skin matrix of the joint, H the horse's to_rig (what a mesh bound to the
//           joint at rest in the horse's file needs to follow it, as her joints are handed out).
//
// The rider's motion at a frame reads the horse over about a second around it (the travel frame fitted
// to its trunk, rig/io/keyed_horse_clip.h): the frames handed in make a table of the horse's joints, its
// motion linear between frames, and the clip is made again from the table when a frame of it has changed
// since a rider was last asked for (a few milliseconds: tests/bench/live_rider_bench.cpp).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "rig/character.h"
#include "rig/io/keyed_horse_clip.h"
#include "rig/rig_profile.h"

namespace stirrup::scene {

struct LiveRiderSetup {
  std::filesystem::path horse_file;
  std::shared_ptr<const rig::Character> horse, rider;  // the horse read from horse_file, the rider seated on it
  rig::RigProfile profile;
  double fps = 24.0;
  int first_frame = 1, last_frame = 1;  // the tool's frames the horse's motion spans
};

class LiveRider {
 public:
  // Errors are one-line InputErrors naming the file (see KeyedHorseClip) or the frames (none, or too many).
  explicit LiveRider(const LiveRiderSetup& setup);
  ~LiveRider();
  LiveRider(const LiveRider&) = delete;
  LiveRider& operator=(const LiveRider&) = delete;

  // The horse's skin joints, in the order a frame hands them in; the rider's joints, in the order they come out.
  const std::vector<std::string>& horseJoints() const;
  const std::vector<std::string>& riderJoints() const;
  // The horse's tack joints (the joints of its tack roles, kHorseTackRoles order: saddle, lStirrup,
  // rStirrup, lRein, rRein; its own where it names them, else the rig's points), in the order they come out.
  const std::vector<std::string>& tackJoints() const;
  int firstFrame() const;
  int lastFrame() const;

  // The horse at the tool's frame `frame` (first..last): one deformation per horseJoints(). A frame outside
  // the range or another count is an InputError.
  void setHorse(int frame, const std::vector<glm::dmat4>& deformations);
  // The rider at the tool's frame `frame` (any: the horse holds its first and last frames beyond them),
  // and, when `tack` is given, the horse's tack there: one deformation per tackJoints().
  std::vector<glm::dmat4> rider(int frame, std::vector<glm::dmat4>* tack = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stirrup::scene
