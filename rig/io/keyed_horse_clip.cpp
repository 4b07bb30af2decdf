#include "rig/io/keyed_horse_clip.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "rig/channel_rotation.h"
#include "rig/character.h"
#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_mapping.h"
#include "rig/io/gltf_skin_joints.h"
#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig {
namespace {

// The travel table's rate: the trunk is sampled this often, and the fitted travel read between samples.
constexpr double kTravelTableHz = 240.0;
constexpr std::array<std::array<HorseChannel, 3>, 4> kHoofChannels = {{
    {HorseChannel::lfHoofTx, HorseChannel::lfHoofTy, HorseChannel::lfHoofTz},
    {HorseChannel::rfHoofTx, HorseChannel::rfHoofTy, HorseChannel::rfHoofTz},
    {HorseChannel::lbHoofTx, HorseChannel::lbHoofTy, HorseChannel::lbHoofTz},
    {HorseChannel::rbHoofTx, HorseChannel::rbHoofTy, HorseChannel::rbHoofTz}}};

// The travel frame on flat ground: its origin (x, z) and heading (radians, + from +X toward +Z).
struct Travel {
  glm::dvec2 origin{0.0};
  double heading = 0.0;
  glm::dmat4 matrix() const {
    return glm::translate(glm::dmat4(1.0), glm::dvec3(origin.x, 0.0, origin.y)) *
           glm::rotate(glm::dmat4(1.0), -heading, glm::dvec3(0.0, 1.0, 0.0));
  }
};

// A uniform-weight straight-line fit of (t_i, y_i) over a window, read at t: a steady motion exactly.
double lineFitAt(const std::vector<double>& times, const std::vector<double>& ys, std::size_t lo, std::size_t hi, double t) {
  const double n = double(hi - lo);
  double st = 0, sy = 0;
  for (std::size_t i = lo; i < hi; ++i) st += times[i], sy += ys[i];
  const double mt = st / n, my = sy / n;
  double stt = 0, sty = 0;
  for (std::size_t i = lo; i < hi; ++i) stt += (times[i] - mt) * (times[i] - mt), sty += (times[i] - mt) * (ys[i] - my);
  return stt > 0.0 ? my + sty / stt * (t - mt) : my;
}

// A file's own animation (or every animation of it together) as the clip's node motion.
class FileMotion final : public NodeMotion {
 public:
  explicit FileMotion(GltfAnimation animation) : a_(std::move(animation)) {}
  std::string name() const override { return a_.name(); }
  double start() const override { return a_.start(); }
  double end() const override { return a_.duration(); }
  glm::dmat4 world(int node, double t) const override { return a_.world(node, t); }
  std::vector<glm::dmat4> worlds(double t) const override { return a_.worlds(t); }

 private:
  GltfAnimation a_;
};

}  // namespace

KeyedHorseMapping keyedHorseMapping(const Character& horse) {
  KeyedHorseMapping m;
  for (const auto& [role, j] : horse.roles)
    if (!horse.skeleton.joints[std::size_t(j)].rig_point) m.roles[role] = horse.skeleton.joints[std::size_t(j)].name;
  m.to_rig = horse.source.to_rig;
  m.where = horse.source.file;
  return m;
}

KeyedHorseMapping keyedHorseMapping(const CharacterMapping& mapping, const std::string& file) {
  KeyedHorseMapping m;
  m.roles = mapping.roles;
  m.to_rig = mappingToRig(mapping);
  m.where = mapping.file.empty() ? file : mapping.file.string();
  return m;
}

struct KeyedHorseClip::Impl {
  std::string file;
  std::shared_ptr<const NodeMotion> animation;
  // The file's joints in stirrup's world (rig/io/gltf_skin_joints.h).
  std::unique_ptr<GltfSkinJoints> skin;
  std::map<std::string, GltfFileJoint> role;  // the roles the controls read
  // The travel table: the fitted trunk at kTravelTableHz, and the trunk's rest.
  std::vector<Travel> travel;
  glm::dvec2 rest_trunk{0.0};
  double rest_heading = 0.0;
  double trunk_speed = 0.0;  // cm/s along the fitted path
  bool in_place = false;
  double added_speed = 0.0;  // in place: the travel added (cm/s)
  // The ridden horse's joints, when the frames key it (one per skeleton joint; node -1: not the file's).
  std::vector<GltfFileJoint> ridden;

  // The clip's time t is the animation's start() + t: its first key is the shot's first frame (Blender
  // keys its frame F at F / fps, so frames 1-48 play as the shot's 1-48).
  double start() const { return animation->start(); }
  double duration() const { return animation->end() - animation->start(); }
  glm::dmat4 posed(const GltfFileJoint& j, const std::vector<glm::dmat4>& worlds) const { return skin->posed(j, worlds[std::size_t(j.node)]); }
  // A joint's place at the animation's time t.
  glm::dvec3 placeAt(const GltfFileJoint& j, double t) const { return glm::dvec3(skin->posed(j, animation->world(j.node, t))[3]); }

  // The trunk's place on the ground and heading at t, unfitted.
  std::pair<glm::dvec2, double> trunkAt(double t) const {
    const glm::dvec3 back = placeAt(role.at("root"), t);
    const glm::dvec3 front = placeAt(role.at("neck1"), t);
    const glm::dvec3 mid = 0.5 * (back + front);
    return {{mid.x, mid.z}, std::atan2(front.z - back.z, front.x - back.x)};
  }

  void fitTravel();
  void findAddedSpeed();
  Travel travelAt(double t) const;
  // The animation's time that plays at the clip's `seconds`.
  double clipTime(double seconds) const {
    if (in_place && duration() > 0.0) return start() + seconds - duration() * std::floor(seconds / duration());
    return start() + std::clamp(seconds, 0.0, duration());
  }
  HorseFrame frameAt(double seconds, bool controls) const;
};

void KeyedHorseClip::Impl::fitTravel() {
  const std::size_t n = std::size_t(std::floor(duration() * kTravelTableHz)) + 2;
  std::vector<double> times(n), xs(n), zs(n), headings(n);
  for (std::size_t i = 0; i < n; ++i) {
    times[i] = start() + std::min(duration(), double(i) / kTravelTableHz);
    const auto [p, h] = trunkAt(times[i]);
    xs[i] = p.x, zs[i] = p.y;
    // Unwrapped, so a horse turning round keeps turning rather than jumping by a full turn.
    headings[i] = i == 0 ? h : headings[i - 1] + std::remainder(h - headings[i - 1], 2.0 * std::numbers::pi);
  }
  const std::size_t half = std::size_t(std::round(0.5 * kTravelWindowS * kTravelTableHz));
  travel.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t lo = i > half ? i - half : 0, hi = std::min(n, i + half + 1);
    travel[i].origin = {lineFitAt(times, xs, lo, hi, times[i]), lineFitAt(times, zs, lo, hi, times[i])};
    travel[i].heading = lineFitAt(times, headings, lo, hi, times[i]);
  }
  double path = 0.0;
  for (std::size_t i = 1; i < n; ++i) path += glm::length(travel[i].origin - travel[i - 1].origin);
  trunk_speed = duration() > 0.0 ? path / duration() : 0.0;
  in_place = trunk_speed < kInPlaceSpeedCmS;
  // Headings from the rest's, the first within half a turn of it (the unwrapping above kept the rest
  // continuous with the first).
  const double turns = std::round((travel[0].heading - rest_heading) / (2.0 * std::numbers::pi));
  rest_heading += turns * 2.0 * std::numbers::pi;
  // The table holds the trunk's fitted place; the travel frame's origin is where the rest pose's origin
  // goes when the rest trunk is moved there and turned by the heading gained since rest.
  for (Travel& tr : travel) {
    tr.heading -= rest_heading;
    const glm::dvec2 turned(std::cos(tr.heading) * rest_trunk.x - std::sin(tr.heading) * rest_trunk.y,
                            std::sin(tr.heading) * rest_trunk.x + std::cos(tr.heading) * rest_trunk.y);
    tr.origin -= turned;
  }
}

// An in-place cycle travels at the speed that keeps its lowest hoof still on average (as GltfClip's
// "speed_cm_s": "auto").
void KeyedHorseClip::Impl::findAddedSpeed() {
  constexpr int kSteps = 400;
  double back = 0.0;
  const auto hoofIn = [&](int k, double t) {
    const glm::dvec3 w = placeAt(role.at(kHoofRoles[std::size_t(k)]), t);
    return glm::dvec3(glm::inverse(travelAt(t).matrix()) * glm::dvec4(w, 1.0));
  };
  for (int i = 0; i < kSteps; ++i) {
    const double t0 = start() + duration() * i / kSteps, t1 = start() + duration() * (i + 1) / kSteps;
    double lowest = 1e300, dx = 0.0;
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 a = hoofIn(k, t0), b = hoofIn(k, t1);
      const double lift = a.y - role.at(kHoofRoles[std::size_t(k)]).rest.y;
      if (lift < lowest) lowest = lift, dx = b.x - a.x;
    }
    back -= dx;
  }
  added_speed = duration() > 0.0 ? std::max(0.0, back / duration()) : 0.0;
}

// The travel frame at the animation's time t.
Travel KeyedHorseClip::Impl::travelAt(double t) const {
  const double x = std::clamp(t - start(), 0.0, duration()) * kTravelTableHz;
  const std::size_t i = std::min(travel.size() - 1, std::size_t(x));
  const std::size_t j = std::min(travel.size() - 1, i + 1);
  const double u = std::clamp(x - double(i), 0.0, 1.0);
  Travel tr;
  tr.origin = travel[i].origin * (1.0 - u) + travel[j].origin * u;
  tr.heading = travel[i].heading * (1.0 - u) + travel[j].heading * u;
  return tr;
}

HorseFrame KeyedHorseClip::Impl::frameAt(double seconds, bool controls) const {
  const double t = clipTime(seconds);
  Travel tr = travelAt(t);
  HorseFrame f;
  const glm::dmat4 from_travel = glm::inverse(tr.matrix());
  if (in_place) tr.origin += glm::dvec2(std::cos(tr.heading), std::sin(tr.heading)) * (added_speed * seconds);
  f.travel_cm = tr.origin.x;
  f.travel_z_cm = tr.origin.y;
  f.heading_deg = glm::degrees(tr.heading);
  if (!controls) return f;

  const std::vector<glm::dmat4> worlds = animation->worlds(t);
  const auto inTravel = [&](const char* r) { return from_travel * posed(role.at(r), worlds); };
  for (std::size_t k = 0; k < 4; ++k) {
    const GltfFileJoint& j = role.at(kHoofRoles[k]);
    const glm::dvec3 p(inTravel(kHoofRoles[k])[3]);
    f.controls[kHoofChannels[k][0]] = p.x - j.rest.x;
    f.controls[kHoofChannels[k][1]] = std::max(0.0, p.y - j.rest.y);
    f.controls[kHoofChannels[k][2]] = p.z - j.rest.z;
  }
  // The body: the root's move and turn from rest; the back's, neck's, head's and tail's turns from the
  // joint they ride on (for re-posing another horse from these controls).
  const glm::dmat4 root = inTravel("root");
  const glm::dvec3 lift = glm::dvec3(root[3]) - role.at("root").rest;
  const auto rr = channelsFromRotation(gltfRotationOf(root));
  using H = HorseChannel;
  f.controls[H::rearPivotTx] = lift.x, f.controls[H::rearPivotTy] = lift.y, f.controls[H::rearPivotTz] = lift.z;
  f.controls[H::rearPivotRx] = rr[0], f.controls[H::rearPivotRy] = rr[1], f.controls[H::rearPivotRz] = rr[2];
  const auto turnFrom = [&](const glm::dmat4& base, const char* r) {
    return channelsFromRotation(glm::inverse(gltfRotationOf(base)) * gltfRotationOf(inTravel(r)));
  };
  glm::dmat4 front = root;
  if (role.count("backMid")) {
    const auto b = turnFrom(root, "backMid");
    f.controls[H::backMidRx] = b[0], f.controls[H::backMidRy] = b[1], f.controls[H::backMidRz] = b[2];
    front = inTravel("backMid");
  }
  f.neck_rz = turnFrom(front, "neck1")[2];
  if (role.count("head")) f.head_rz = turnFrom(inTravel("neck1"), "head")[2];
  if (role.count("tail1")) {
    const auto r = turnFrom(root, "tail1");
    f.tail_rz = r[2];
    f.tail_ry = r[1];
  }
  if (!ridden.empty()) {
    auto pose = std::make_shared<KeyedHorsePose>();
    pose->joint.assign(ridden.size(), glm::mat4(1.0f));
    pose->keyed.assign(ridden.size(), 0);
    for (std::size_t j = 0; j < ridden.size(); ++j) {
      if (ridden[j].node < 0) continue;
      pose->joint[j] = glm::mat4(from_travel * posed(ridden[j], worlds));
      pose->keyed[j] = 1;
    }
    f.keyed_pose = std::move(pose);
  }
  return f;
}

KeyedHorseClip::KeyedHorseClip(const std::filesystem::path& file, const std::string& animation, const KeyedHorseMapping& mapping,
                               const Character* ridden, const KeyedHorseOptions& options) try
    : KeyedHorseClip(std::filesystem::exists(file)
                         ? readGltfFile(file, file.string())
                         : throw InputError(file.string() + ": no such file (expected a glTF horse with an animation)"),
                     file.string(), animation, mapping, ridden, options) {
} catch (const std::out_of_range&) {
  throw InputError(file.string() + ": not a valid glTF file (an index points past the end of its array)");
}

KeyedHorseClip::KeyedHorseClip(const tinygltf::Model& model, const std::string& file, const std::string& animation,
                               const KeyedHorseMapping& mapping, const Character* ridden, const KeyedHorseOptions& options) try
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.file = file;
  checkedSkin(model, m.file, "horse", options.skin);
  // The file's own animation is read even when another motion stands in for it: its rest gives the units.
  const GltfAnimation own = options.every_animation || options.motion ? GltfAnimation::together(model, m.file)
                                                                      : GltfAnimation(model, m.file, animation);
  for (const char* needed : {"root", "neck1", "lfHoof", "rfHoof", "lbHoof", "rbHoof"})
    if (!mapping.roles.count(needed))
      throw InputError(mapping.where + ": roles." + needed + ": missing (expected the horse's " + needed + " joint to read its animation)");
  const std::vector<std::string> names = gltfJointNames(model, options.skin);
  // The file's units from the root joint's bind (gltfSkinUnits).
  const auto root = std::find(names.begin(), names.end(), mapping.roles.at("root"));
  if (root == names.end()) throw InputError(mapping.where + ": roles.root: no joint named \"" + mapping.roles.at("root") + "\" in " + m.file);
  const double units = gltfSkinUnits(model, m.file, options.skin, int(root - names.begin()), own);
  m.animation = options.motion ? options.motion : std::make_shared<FileMotion>(own);
  m.skin = std::make_unique<GltfSkinJoints>(model, m.file, options.skin, mapping.to_rig, units);
  for (const auto& [r, joint] : mapping.roles) {
    const std::optional<GltfFileJoint> j = m.skin->joint(joint);
    if (!j) throw InputError(mapping.where + ": roles." + r + ": no joint named \"" + joint + "\" in " + m.file);
    m.role[r] = *j;
  }
  m.rest_trunk = glm::dvec2(0.5 * (m.role["root"].rest.x + m.role["neck1"].rest.x), 0.5 * (m.role["root"].rest.z + m.role["neck1"].rest.z));
  m.rest_heading = std::atan2(m.role["neck1"].rest.z - m.role["root"].rest.z, m.role["neck1"].rest.x - m.role["root"].rest.x);
  m.fitTravel();
  if (options.keyed_travel_only) m.in_place = false;
  if (m.in_place) m.findAddedSpeed();
  if (ridden && !m.in_place) {
    const Skeleton& s = ridden->skeleton;
    m.ridden.resize(s.size());
    for (std::size_t j = 0; j < s.size(); ++j) {
      if (s.joints[j].rig_point) continue;
      const glm::dmat4 rest = glm::dmat4(s.restWorld(int(j)));
      const std::optional<GltfFileJoint> fj = m.skin->joint(s.joints[j].name, &rest);
      if (!fj)
        throw InputError(m.file + ": no joint named \"" + s.joints[j].name + "\" (the scene's horse has it: is its clip the horse's own file?)");
      m.ridden[j] = *fj;
    }
  }
} catch (const std::out_of_range&) {
  throw InputError(file + ": not a valid glTF file (an index points past the end of its array)");
}

KeyedHorseClip::~KeyedHorseClip() = default;

std::string KeyedHorseClip::name() const {
  const std::string& a = impl_->animation->name();
  return a.empty() ? std::filesystem::path(impl_->file).stem().string() : a;
}
double KeyedHorseClip::duration() const { return impl_->duration(); }
HorseFrame KeyedHorseClip::sample(double seconds) const { return impl_->frameAt(seconds, true); }
HorseFrame KeyedHorseClip::sampleTravel(double seconds) const { return impl_->frameAt(seconds, false); }
bool KeyedHorseClip::inPlace() const { return impl_->in_place; }
double KeyedHorseClip::trunkSpeedCmS() const { return impl_->trunk_speed; }
bool KeyedHorseClip::keysTheHorse() const { return !impl_->ridden.empty(); }

}  // namespace stirrup::rig
