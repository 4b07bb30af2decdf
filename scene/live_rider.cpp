#include "scene/live_rider.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include <tiny_gltf.h>

#include "rig/bake.h"
#include "rig/characters/horse_tack.h"
#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_mapping.h"
#include "rig/io/gltf_skin_joints.h"
#include "rig/mapping/mapping_skeleton.h"
#include "rig/pose.h"

namespace stirrup::scene {
namespace {

// At most this many frames of the horse's motion (10 minutes at 24 fps): the table holds every node of
// every frame.
constexpr int kMaxLiveFrames = 14400;

// The horse's joints frame by frame, linear between frames: the motion the live clip reads. A copy is
// taken for each clip, so a clip never sees the table change under it.
class TableMotion final : public rig::NodeMotion {
 public:
  TableMotion(std::vector<std::vector<glm::dmat4>> frames, int first, double fps) : frames_(std::move(frames)), first_(first), fps_(fps) {}
  std::string name() const override { return "live"; }
  double start() const override { return first_ / fps_; }
  double end() const override { return (first_ + int(frames_.size()) - 1) / fps_; }
  glm::dmat4 world(int node, double t) const override {
    const auto [i, j, u] = at(t);
    return frames_[i][std::size_t(node)] * (1.0 - u) + frames_[j][std::size_t(node)] * u;
  }
  std::vector<glm::dmat4> worlds(double t) const override {
    const auto [i, j, u] = at(t);
    if (u == 0.0) return frames_[i];
    std::vector<glm::dmat4> out(frames_[i].size());
    for (std::size_t n = 0; n < out.size(); ++n) out[n] = frames_[i][n] * (1.0 - u) + frames_[j][n] * u;
    return out;
  }

 private:
  // The frames either side of time t and how far between them (a time within a millionth of a frame of a
  // frame is that frame).
  std::tuple<std::size_t, std::size_t, double> at(double t) const {
    const double x = std::clamp(t * fps_ - first_, 0.0, double(frames_.size() - 1));
    const double i = std::floor(x + 1e-6);
    const std::size_t a = std::min(std::size_t(i), frames_.size() - 1), b = std::min(a + 1, frames_.size() - 1);
    const double u = std::max(0.0, x - i);
    return {a, b, u < 1e-6 ? 0.0 : u};
  }
  std::vector<std::vector<glm::dmat4>> frames_;
  int first_;
  double fps_;
};

}  // namespace

struct LiveRider::Impl {
  LiveRiderSetup setup;
  tinygltf::Model model;
  rig::KeyedHorseMapping mapping;
  std::vector<std::string> horse_joints, rider_joints;
  std::vector<int> horse_nodes;           // each horse joint's node
  std::vector<glm::dmat4> bind;           // each horse joint's world at bind (its inverse bind inverted)
  std::vector<int> rider_index;           // each rider joint's index in the rider's skeleton
  std::vector<std::string> tack_joints;
  std::vector<int> tack_index;            // each tack joint's index in the horse's skeleton
  std::vector<std::vector<glm::dmat4>> table;  // node worlds, frame by frame from first_frame
  std::unique_ptr<rig::KeyedHorseClip> clip;   // null after a frame changed
  glm::dmat4 from_horse_rig{1.0}, rider_to_rig{1.0};

  void makeClip() {
    rig::KeyedHorseOptions options;
    options.motion = std::make_shared<TableMotion>(table, setup.first_frame, setup.fps);
    clip = std::make_unique<rig::KeyedHorseClip>(model, setup.horse_file.string(), "", mapping, setup.horse.get(), options);
  }
};

LiveRider::LiveRider(const LiveRiderSetup& setup) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.setup = setup;
  const std::string file = setup.horse_file.string();
  if (!setup.horse || !setup.rider) throw std::invalid_argument("LiveRider: expected a horse and a rider");
  const int frames = setup.last_frame - setup.first_frame + 1;
  if (frames < 1 || frames > kMaxLiveFrames)
    throw rig::InputError("live: frames " + std::to_string(setup.first_frame) + " to " + std::to_string(setup.last_frame) +
                     ": expected 1 to " + std::to_string(kMaxLiveFrames) + " frames");
  m.model = rig::readGltfFile(setup.horse_file, file);
  m.mapping = rig::keyedHorseMapping(*setup.horse);
  m.horse_joints = rig::gltfJointNames(m.model, 0);
  m.horse_nodes = rig::checkedSkin(m.model, file, "horse").joints;
  for (const glm::mat4& ibm : rig::gltfInverseBinds(m.model, file, 0)) m.bind.push_back(glm::inverse(glm::dmat4(ibm)));
  const rig::Skeleton& rs = setup.rider->skeleton;
  for (std::size_t j = 0; j < rs.size(); ++j)
    if (!rs.joints[j].rig_point) m.rider_joints.push_back(rs.joints[j].name), m.rider_index.push_back(int(j));
  const rig::Skeleton& hs = setup.horse->skeleton;
  for (const char* role : rig::kHorseTackRoles)
    if (const auto it = setup.horse->roles.find(role); it != setup.horse->roles.end())
      m.tack_joints.push_back(hs.joints[std::size_t(it->second)].name), m.tack_index.push_back(it->second);
  // The horse's own animation (every animation of the file together; none: its rest) until frames come in.
  const rig::GltfAnimation own = rig::GltfAnimation::together(m.model, file);
  for (int f = setup.first_frame; f <= setup.last_frame; ++f) m.table.push_back(own.worlds(f / setup.fps));
  // Her joints go out in the horse's file's world: stirrup's world taken back through the horse's mapping
  // and the units of the file's world against its mesh's (gltfSkinUnits: 1 for Blender's metres, 0.01
  // for a bake's joints bound in centimetres under its metre world), as KeyedHorseClip reads it in.
  const auto root = std::find(m.horse_joints.begin(), m.horse_joints.end(), m.mapping.roles.count("root") ? m.mapping.roles.at("root") : "");
  const double units = root == m.horse_joints.end() ? 1.0 : rig::gltfSkinUnits(m.model, file, 0, int(root - m.horse_joints.begin()), own);
  m.from_horse_rig = glm::scale(glm::dmat4(1.0), glm::dvec3(units)) * glm::inverse(m.mapping.to_rig);
  m.rider_to_rig = setup.rider->source.to_rig;
}

LiveRider::~LiveRider() = default;

const std::vector<std::string>& LiveRider::horseJoints() const { return impl_->horse_joints; }
const std::vector<std::string>& LiveRider::riderJoints() const { return impl_->rider_joints; }
const std::vector<std::string>& LiveRider::tackJoints() const { return impl_->tack_joints; }
int LiveRider::firstFrame() const { return impl_->setup.first_frame; }
int LiveRider::lastFrame() const { return impl_->setup.last_frame; }

void LiveRider::setHorse(int frame, const std::vector<glm::dmat4>& deformations) {
  Impl& m = *impl_;
  if (frame < firstFrame() || frame > lastFrame())
    throw rig::InputError("live: frame " + std::to_string(frame) + ": expected a frame from " + std::to_string(firstFrame()) + " to " +
                     std::to_string(lastFrame()));
  if (deformations.size() != m.horse_joints.size())
    throw rig::InputError("live: frame " + std::to_string(frame) + ": expected " + std::to_string(m.horse_joints.size()) +
                     " horse joints, got " + std::to_string(deformations.size()));
  std::vector<glm::dmat4>& worlds = m.table[std::size_t(frame - firstFrame())];
  for (std::size_t k = 0; k < deformations.size(); ++k) worlds[std::size_t(m.horse_nodes[k])] = deformations[k] * m.bind[k];
  m.clip.reset();
}

std::vector<glm::dmat4> LiveRider::rider(int frame, std::vector<glm::dmat4>* tack) {
  Impl& m = *impl_;
  if (!m.clip) m.makeClip();
  // The tool's frame F plays the clip at F / fps, its first frame at the clip's start.
  const double seconds = (frame - firstFrame()) / m.setup.fps;
  const rig::BakedFrame baked = rig::bakeFrame(*m.clip, m.setup.profile, frame, seconds);
  const rig::MountedPose pose = rig::poseMounted(*m.setup.horse, *m.setup.rider, baked.horse, baked.rider, m.setup.profile);
  std::vector<glm::dmat4> out;
  out.reserve(m.rider_index.size());
  for (const int j : m.rider_index)
    out.push_back(m.from_horse_rig * glm::dmat4(pose.rider[std::size_t(j)]) * glm::dmat4(m.setup.rider->skeleton.skinBind(j)) * m.rider_to_rig);
  if (tack) {
    // The tack as poseMounted leaves it: the stirrups at her feet, the rein ends in her hands.
    tack->clear();
    for (const int j : m.tack_index)
      tack->push_back(m.from_horse_rig * glm::dmat4(pose.horse[std::size_t(j)]) * glm::dmat4(m.setup.horse->skeleton.skinBind(j)) *
                      m.setup.horse->source.to_rig);
  }
  return out;
}

}  // namespace stirrup::scene
