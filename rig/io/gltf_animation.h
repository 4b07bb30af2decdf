// One animation of a glTF file, decoded once and sampled at any time: every node's local and world
// transform as the file's animation moves it (glTF 2.0, sections 3.11 and Appendix C). The readers of
// other tools' motion sit on it: a horse clip read through a mapping (rig/io/gltf_clip.h), a horse
// playing its own keyed animation (rig/io/keyed_horse_clip.h), and a baked shot read back for checking
// (rig/io/gltf_shot.h).
//
//   input:  a parsed glTF model, the file's name for messages, and which animation (by name, or the first)
//   output: node transforms at a time t; the model is not kept
//
// Samplers may be LINEAR (rotations by slerp), STEP or CUBICSPLINE (Hermite with tangents scaled by the key
// interval, rotations normalised), with float or normalised-integer data, dense or sparse. Past its last key
// a track holds its last value, before its first its first. Other interpolations, key times that do not
// increase, an output with the wrong number of elements or an index past its array are one-line
// InputErrors naming the file, the animation and the sampler.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

// A node's local transform as translation, rotation and scale (a node given as a matrix keeps it in
// `matrix` and is not animated: glTF forbids animating such a node).
struct GltfTrs {
  glm::dvec3 t{0.0};
  glm::dquat r{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 s{1.0};
  std::optional<glm::dmat4> matrix;
  glm::dmat4 toMatrix() const;
};

class GltfAnimation {
 public:
  // `animation`: the animation's name, or empty for the file's first. A file without animations, or
  // without one of that name, is an InputError naming the file (and the names it has).
  GltfAnimation(const tinygltf::Model& model, const std::string& file, const std::string& animation);
  // Every animation of the file played together, as one shot: Blender's exporter writes a shot as one
  // animation, or as one an armature (actions it finds off the NLA tracks), each keying its own nodes.
  // An animation that keys a node an earlier one keys is another take of it and is left out (leftOut());
  // a file without animations rests (duration 0). Its name joins the names played with " + ".
  static GltfAnimation together(const tinygltf::Model& model, const std::string& file);

  const std::string& name() const { return name_; }
  int index() const { return index_; }
  // The last key time of any of its tracks (seconds; 0 for an animation without keys).
  double duration() const { return duration_; }
  // The first key time of any of its tracks (0 for an animation without keys). Blender's exporter keys
  // its frame F at F / fps, so an animation of frames 1-48 starts at 1/24 s.
  double start() const { return start_; }
  int nodeCount() const { return static_cast<int>(rest_.size()); }
  const std::vector<int>& parents() const { return parent_; }
  // Whether any track moves the node.
  bool animates(int node) const;
  // together(): the animations played and those left out (by name, "animations[i]" when unnamed).
  const std::vector<std::string>& played() const { return played_; }
  const std::vector<std::string>& leftOut() const { return left_out_; }

  // The node's local transform at time t, or as the file rests it (t empty).
  GltfTrs localTrs(int node, std::optional<double> t) const;
  glm::dmat4 local(int node, std::optional<double> t) const { return localTrs(node, t).toMatrix(); }
  // Its world transform (the scene's space): the locals of it and every ancestor.
  glm::dmat4 world(int node, std::optional<double> t) const;
  // Every node's world transform at once (parents computed once for all their children).
  std::vector<glm::dmat4> worlds(std::optional<double> t) const;

 private:
  GltfAnimation() = default;
  // The nodes' rests and hierarchy; no tracks.
  void setUp(const tinygltf::Model& model, const std::string& file);
  // Animation `index`'s tracks (each checked: a one-line InputError naming the file, the animation and the sampler).
  void addTracks(const tinygltf::Model& model, const std::string& file, int index);

  struct Track {
    std::vector<float> times, values;
    int components = 3;
    bool step = false;
    bool cubic = false;  // values hold (in-tangent, value, out-tangent) per key
  };
  struct Drive {
    int translation = -1, rotation = -1, scale = -1;
  };
  std::vector<double> evaluate(const Track& track, double t) const;

  std::string name_;
  int index_ = 0;
  double duration_ = 0.0;
  double start_ = 0.0;
  std::vector<GltfTrs> rest_;
  std::vector<int> parent_;
  std::vector<int> order_;  // nodes, parents before children
  std::vector<Drive> drive_;
  std::vector<Track> tracks_;
  std::vector<std::string> played_, left_out_;
};

// A rotation's unit quaternion from a matrix whose columns may carry scale.
glm::dquat gltfRotationOf(const glm::dmat4& m);

}  // namespace stirrup::rig
