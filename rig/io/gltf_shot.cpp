#include "rig/io/gltf_shot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <regex>

#include <tiny_gltf.h>

#include "rig/character.h"
#include "rig/characters/seating.h"
#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_mapping.h"
#include "rig/io/gltf_nodes.h"
#include "rig/io/gltf_skin_joints.h"
#include "rig/io/gltf_terrain.h"
#include "rig/mapping/auto_mapping.h"
#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig {
namespace {

// Whether `node` is one of the skin's joints.
bool isJointOf(const tinygltf::Skin& skin, int node) { return std::find(skin.joints.begin(), skin.joints.end(), node) != skin.joints.end(); }

// The skin's top joint (index into its joints): the first with no joint of the skin above it.
int topJoint(const tinygltf::Skin& skin, const std::vector<int>& parent) {
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    bool top = true;
    for (int n = parent[std::size_t(skin.joints[j])]; n >= 0 && top; n = parent[std::size_t(n)]) top = !isJointOf(skin, n);
    if (top) return int(j);
  }
  return 0;
}

// The armature's node: the skin's `skeleton` node where that is not one of its joints (stirrup's bake),
// else the node its top joint hangs from (Blender's exporter: the armature object); -1 for neither (and
// for a skin with no joints or a joint that is no node, which the skin's own checks report later).
int armatureNode(const tinygltf::Model& model, const std::vector<int>& parent, int k) {
  const tinygltf::Skin& skin = model.skins[std::size_t(k)];
  if (skin.skeleton >= 0 && skin.skeleton < int(model.nodes.size()) && !isJointOf(skin, skin.skeleton)) return skin.skeleton;
  const bool joints_are_nodes = std::all_of(skin.joints.begin(), skin.joints.end(),
                                            [&](int j) { return j >= 0 && std::size_t(j) < parent.size(); });
  if (skin.joints.empty() || !joints_are_nodes) return -1;
  return parent[std::size_t(skin.joints[std::size_t(topJoint(skin, parent))])];
}

// The armature's name: its node's (above), else the skin's own.
std::string armatureName(const tinygltf::Model& model, const std::vector<int>& parent, int k) {
  const int node = armatureNode(model, parent, k);
  return node >= 0 ? model.nodes[std::size_t(node)].name : model.skins[std::size_t(k)].name;
}

// The seconds of the frames each hoof slides on purpose, as the bake records them on the horse's
// armature ("stirrup_hoof_sliding", rig/io/gltf_bake.h); none where the file does not say.
std::array<std::vector<double>, 4> hoofSlidingTimes(const tinygltf::Model& model, const std::vector<int>& parent, int horse_skin) {
  static constexpr std::array<const char*, 4> kHooves = {"lf", "rf", "lb", "rb"};
  std::array<std::vector<double>, 4> out;
  const int node = armatureNode(model, parent, horse_skin);
  if (node < 0) return out;
  const tinygltf::Value& extras = model.nodes[std::size_t(node)].extras;
  if (!extras.IsObject() || !extras.Has("stirrup_hoof_sliding") || !extras.Get("stirrup_hoof_sliding").IsObject()) return out;
  const tinygltf::Value& sliding = extras.Get("stirrup_hoof_sliding");
  for (std::size_t leg = 0; leg < 4; ++leg) {
    const tinygltf::Value& times = sliding.Get(kHooves[leg]);
    if (!times.IsArray()) continue;
    for (std::size_t i = 0; i < times.ArrayLen(); ++i)
      if (times.Get(int(i)).IsNumber() && std::isfinite(times.Get(int(i)).GetNumberAsDouble()))
        out[leg].push_back(times.Get(int(i)).GetNumberAsDouble());
  }
  return out;
}

// One pair's skins as the file casts them.
struct Cast {
  std::string name;  // "" or "pairNN"
  int index = 0;
  int skin[2] = {-1, -1};  // horse, rider
  std::string armature[2];
};

// The pairs the armatures' names make: "horse"/"rider", "pairNN_horse"/"pairNN_rider"; in pair order.
std::vector<Cast> castByNames(const tinygltf::Model& model, const std::vector<int>& parent) {
  static const std::regex kName("(pair([0-9]+)_)?(horse|rider)");
  std::map<std::pair<int, std::string>, Cast> cast;
  for (int k = 0; k < int(model.skins.size()); ++k) {
    const std::string name = armatureName(model, parent, k);
    std::smatch m;
    if (!std::regex_match(name, m, kName)) continue;
    const std::string pair = m[2].matched ? "pair" + m[2].str() : "";
    const int index = m[2].matched ? std::stoi(m[2].str()) : 0;
    Cast& c = cast[{index, pair}];
    c.name = pair;
    c.index = index;
    const int which = m[3].str() == "horse" ? 0 : 1;
    c.skin[which] = k;
    c.armature[which] = name;
  }
  std::vector<Cast> out;
  for (auto& [key, c] : cast) out.push_back(c);
  return out;
}

// The file's role table for skin k where it can be trusted: one naming the joints, or one of indices in
// a file stirrup wrote. Another tool keeping extras may list the joints in another order (Blender's
// exporter lists them depth first), so its indices would point at other joints: nullopt.
std::optional<std::map<std::string, int>> trustedRoleTable(const tinygltf::Model& model, const std::string& f, int k, CharacterKind kind) {
  if (model.asset.generator.rfind("stirrup", 0) == 0) return gltfRoleTable(model, f, k, kind);
  try {
    bool named = false;
    std::optional<std::map<std::string, int>> table = gltfRoleTable(model, f, k, kind, &named, true);
    return named ? table : std::nullopt;
  } catch (const InputError&) {
    return std::nullopt;  // a table the tool left out of step with the joints: the file maps by itself
  }
}

// Whether skin k holds a character of `kind`: its role table says so, or the automatic mapping finds every role.
bool castsAs(const tinygltf::Model& model, const std::string& f, int k, CharacterKind kind) {
  try {
    if (trustedRoleTable(model, f, k, kind)) return true;
    return autoMapCharacter(mappingSkeletonFromGltf(model, f, k), kind).report.not_mapped.empty();
  } catch (const InputError&) {
    return false;
  }
}

// A file of two skins under other names: a shot when one maps as a horse and the other as a rider.
std::optional<Cast> castByMapping(const tinygltf::Model& model, const std::string& f, const std::vector<int>& parent) {
  if (model.skins.size() != 2) return std::nullopt;
  for (const int horse : {0, 1}) {
    const int rider = 1 - horse;
    if (!castsAs(model, f, horse, CharacterKind::Horse) || !castsAs(model, f, rider, CharacterKind::Rider)) continue;
    Cast c;
    c.skin[0] = horse, c.skin[1] = rider;
    c.armature[0] = armatureName(model, parent, horse), c.armature[1] = armatureName(model, parent, rider);
    return c;
  }
  return std::nullopt;
}

// A character of the shot: loaded from its skin into the file's world (cm), and its joints' nodes.
struct ShotCharacter {
  Character character;
  std::unique_ptr<GltfSkinJoints> skin;
  std::vector<GltfFileJoint> joints;  // one per skeleton joint; node -1: a point the rig added
};

// The file's world in stirrup's: its scene's extras "stirrup_world" ({"scale_cm", "forward", "up",
// "offset_cm"}, a mapping's, rig/mapping/character_mapping.h), which a tool writes when its world is not
// stirrup's (the Blender add-on: the horse's mapping); else metres with stirrup's axes, a bake's world.
CharacterMapping worldMapping(const tinygltf::Model& model, const std::string& f) {
  CharacterMapping world;
  world.scale_cm = 100.0;
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (scene >= int(model.scenes.size())) return world;
  const tinygltf::Value& extras = model.scenes[std::size_t(scene)].extras;
  if (!extras.IsObject() || !extras.Has("stirrup_world")) return world;
  const tinygltf::Value& w = extras.Get("stirrup_world");
  const std::string at = f + ": scenes[" + std::to_string(scene) + "].extras.stirrup_world";
  const auto vec = [&](const char* key, std::array<double, 3>& out, bool unit) {
    const tinygltf::Value& v = w.Get(key);
    bool ok = v.IsArray() && v.ArrayLen() == 3;
    for (int i = 0; ok && i < 3; ++i) {
      ok = v.Get(i).IsNumber() && std::abs(v.Get(i).GetNumberAsDouble()) <= (unit ? kMaxMappingAxis : kMaxMappingOffsetCm);
      out[std::size_t(i)] = ok ? v.Get(i).GetNumberAsDouble() : 0.0;
    }
    if (!ok || (unit && std::hypot(out[0], out[1], out[2]) < 1e-9))
      throw InputError(at + "." + key + ": expected three numbers" + (unit ? ", not all zero" : ""));
  };
  if (!w.IsObject() || !w.Has("scale_cm") || !w.Get("scale_cm").IsNumber() || !(w.Get("scale_cm").GetNumberAsDouble() >= kMinMappingScaleCm) ||
      !(w.Get("scale_cm").GetNumberAsDouble() <= kMaxMappingScaleCm))
    throw InputError(at + ".scale_cm: expected centimetres a unit from 0.001 to 100000");
  world.scale_cm = w.Get("scale_cm").GetNumberAsDouble();
  vec("forward", world.forward, true);
  vec("up", world.up, true);
  vec("offset_cm", world.offset_cm, false);
  const glm::dvec3 fw(world.forward[0], world.forward[1], world.forward[2]), up(world.up[0], world.up[1], world.up[2]);
  if (glm::length(glm::cross(glm::normalize(fw), glm::normalize(up))) < 1e-3) throw InputError(at + ".up: expected a direction across forward");
  return world;
}

ShotCharacter readCharacter(const tinygltf::Model& model, const GltfImageBytes& images, const std::string& f, int k, CharacterKind kind,
                            const std::string& armature, const GltfAnimation& animation, const std::vector<int>& parent,
                            const CharacterMapping& world) {
  const std::string kind_name(characterKindName(kind));
  const std::string where = f + ": the " + kind_name + " \"" + armature + "\" (skins[" + std::to_string(k) + "])";
  const tinygltf::Skin& skin = checkedSkin(model, where, kind_name, k);
  const double units = gltfSkinUnits(model, where, k, topJoint(skin, parent), animation);
  const std::vector<std::string> names = gltfJointNames(model, k);
  CharacterMapping mapping;
  if (const auto table = trustedRoleTable(model, where, k, kind)) {
    for (const auto& [role, j] : *table) mapping.roles[role] = names[std::size_t(j)];
  } else {
    const AutoMapping automatic = autoMapCharacter(mappingSkeletonFromGltf(model, where, k), kind);
    if (!automatic.report.not_mapped.empty()) {
      std::string missing;
      for (const std::string& r : automatic.report.not_mapped) missing += (missing.empty() ? "" : ", ") + r;
      throw InputError(where + ": no joint found for " + missing + " (the automatic mapping read it by " + automatic.report.method +
                       "; expected the " + kind_name + "'s joints named as stirrup bake names them, or a role table)");
    }
    mapping.roles = automatic.mapping.roles;
  }
  // One world for every character, the file's taken to stirrup's (worldMapping), the mesh in its own
  // units against that world (100 cm a unit for Blender's metres, 1 for a bake's centimetres).
  mapping.scale_cm = world.scale_cm * units;
  mapping.forward = world.forward, mapping.up = world.up, mapping.offset_cm = world.offset_cm;
  ShotCharacter out;
  out.character = loadCharacterGltf(GltfSkinSource{&model, &images, where, k}, kind, &mapping);
  // A rider from another tool (a Blender export) gets the contact points a scene's seating gives her (the
  // sole under the ball of each foot...), so her feet are measured where the bake of the same rider
  // measures them; a bake's rider has them as joints of its own.
  if (kind == CharacterKind::Rider && model.asset.generator.rfind("stirrup", 0) != 0) addContactPoints(out.character);
  out.skin = std::make_unique<GltfSkinJoints>(model, where, k, mappingToRig(mapping), units);
  const Skeleton& s = out.character.skeleton;
  out.joints.resize(s.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (s.joints[j].rig_point) continue;
    const glm::dmat4 rest(s.restWorld(int(j)));
    if (const std::optional<GltfFileJoint> fj = out.skin->joint(s.joints[j].name, &rest)) out.joints[j] = *fj;
  }
  return out;
}

// Whether the animation moves any of the characters' joints (or the nodes above them: an armature moved
// as an object).
bool keys(const GltfAnimation& animation, const std::vector<int>& parent, const ShotCharacter& c) {
  for (const GltfFileJoint& j : c.joints)
    for (int n = j.node; n >= 0; n = parent[std::size_t(n)])
      if (animation.animates(n)) return true;
  return false;
}

}  // namespace

struct GltfShot::Impl {
  std::string file;
  std::unique_ptr<GltfAnimation> animation;
  double fps = 24.0, start = 0.0;
  int frames = 1;
  std::vector<Pair> pairs;
  std::vector<std::array<ShotCharacter, 2>> characters;  // horse, rider: their skins and joints
  std::vector<std::array<std::vector<double>, 4>> sliding_s;  // a pair's hooves sliding on purpose, at these seconds
  std::shared_ptr<const TerrainMesh> ground;

  void readPairs(const tinygltf::Model& model, const GltfImageBytes& images, const std::vector<Cast>& cast, const std::vector<int>& parent);
  void readTimes(const tinygltf::Model& model, double default_fps);
};

void GltfShot::Impl::readPairs(const tinygltf::Model& model, const GltfImageBytes& images, const std::vector<Cast>& cast,
                               const std::vector<int>& parent) {
  for (const Cast& c : cast) {
    const std::string prefix = c.name.empty() ? "" : c.name + "_";
    for (int which = 0; which < 2; ++which)
      if (c.skin[which] < 0) {
        const char* has = which == 0 ? "rider" : "horse";
        throw InputError(file + ": the " + has + " \"" + c.armature[1 - which] + "\" has no " + (which == 0 ? "horse" : "rider") +
                         " (expected a skinned armature \"" + prefix + (which == 0 ? "horse" : "rider") + "\" beside it)");
      }
    std::array<ShotCharacter, 2> pc;
    const CharacterMapping world = worldMapping(model, file);
    pc[0] = readCharacter(model, images, file, c.skin[0], CharacterKind::Horse, c.armature[0], *animation, parent, world);
    pc[1] = readCharacter(model, images, file, c.skin[1], CharacterKind::Rider, c.armature[1], *animation, parent, world);
    if (!model.animations.empty() && !keys(*animation, parent, pc[0]) && !keys(*animation, parent, pc[1]))
      throw InputError(file + ": the animation \"" + animation->name() + "\" keys no joint of the horse \"" + c.armature[0] + "\" or the rider \"" +
                       c.armature[1] + "\" (expected the shot's motion keyed on their joints)");
    Pair p;
    p.name = c.name;
    p.index = c.index;
    p.horse_armature = c.armature[0];
    p.rider_armature = c.armature[1];
    p.horse_skin = c.skin[0];
    p.rider_skin = c.skin[1];
    p.horse = pc[0].character;
    p.rider = pc[1].character;
    pairs.push_back(std::move(p));
    characters.push_back(std::move(pc));
    sliding_s.push_back(hoofSlidingTimes(model, parent, c.skin[0]));
  }
}

// Frame 1 at the first key, one a 1/fps to the last: the bake keys its first frame at 0, Blender its
// frame F at F / fps (so a shot it keys from frame 1 starts at 1/fps).
void GltfShot::Impl::readTimes(const tinygltf::Model& model, double default_fps) {
  fps = default_fps;
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (scene < int(model.scenes.size())) {
    const tinygltf::Value& extras = model.scenes[std::size_t(scene)].extras;
    if (extras.IsObject() && extras.Has("fps") && extras.Get("fps").IsNumber() && extras.Get("fps").GetNumberAsDouble() > 0.0)
      fps = extras.Get("fps").GetNumberAsDouble();
  }
  start = animation->start();
  // Key times are floats: a frame within a thousandth of a frame of the last key is keyed.
  frames = 1 + int(std::floor(std::max(0.0, animation->duration() - start) * fps + 1e-3));
}

GltfShot::GltfShot() : impl_(std::make_unique<Impl>()) {}
GltfShot::~GltfShot() = default;

std::unique_ptr<GltfShot> GltfShot::read(const std::filesystem::path& file, const GltfShotOptions& options) try {
  const std::string f = file.string();
  if (!std::filesystem::exists(file)) throw InputError(f + ": no such file (expected a glTF file)");
  GltfImageBytes images;
  const tinygltf::Model model = readGltfFile(file, f, &images);
  const std::vector<int> parent = gltfNodeParents(model, f);
  std::vector<Cast> cast = castByNames(model, parent);
  if (cast.empty())
    if (const std::optional<Cast> c = castByMapping(model, f, parent)) cast.push_back(*c);
  if (cast.empty()) return nullptr;

  std::unique_ptr<GltfShot> shot(new GltfShot());
  Impl& m = *shot->impl_;
  m.file = f;
  m.animation = std::make_unique<GltfAnimation>(options.animation.empty() ? GltfAnimation::together(model, f)
                                                                          : GltfAnimation(model, f, options.animation));
  m.readPairs(model, images, cast, parent);
  m.readTimes(model, options.fps);
  m.ground = gltfGroundMesh(model, f, mappingToRig(worldMapping(model, f)));
  return shot;
} catch (const std::out_of_range&) {
  throw InputError(file.string() + ": not a valid glTF file (an index points past the end of its array)");
}

const std::vector<GltfShot::Pair>& GltfShot::pairs() const { return impl_->pairs; }
int GltfShot::frameCount() const { return impl_->frames; }
double GltfShot::fps() const { return impl_->fps; }
std::string GltfShot::animationName() const { return impl_->animation->name(); }
const std::vector<std::string>& GltfShot::leftOut() const { return impl_->animation->leftOut(); }
std::shared_ptr<const TerrainMesh> GltfShot::ground() const { return impl_->ground; }

std::array<bool, 4> GltfShot::hoofSliding(std::size_t pair, int frame) const {
  const Impl& m = *impl_;
  // The bake's seconds are (frame - 1) / fps from its first key; a frame slides within half a frame of one.
  const double t = double(frame - 1) / m.fps, half = 0.5 / m.fps;
  std::array<bool, 4> out{};
  for (std::size_t leg = 0; leg < 4; ++leg)
    for (const double s : m.sliding_s.at(pair)[leg]) out[leg] = out[leg] || std::abs(s - m.start - t) < half;
  return out;
}

MountedPose GltfShot::pose(std::size_t pair, int frame) const {
  const Impl& m = *impl_;
  const std::vector<glm::dmat4> worlds = m.animation->worlds(m.start + double(frame - 1) / m.fps);
  const Pair& p = m.pairs.at(pair);
  const auto& [horse, rider] = m.characters.at(pair);
  const auto posed = [&](const ShotCharacter& c, const GltfFileJoint& j) { return glm::mat4(c.skin->posed(j, worlds[std::size_t(j.node)])); };
  // The horse as keyed (rig/horse_pose.h poseHorse: points the rig added hang from their parents).
  auto keyed = std::make_shared<KeyedHorsePose>();
  keyed->joint.assign(horse.joints.size(), glm::mat4(1.0f));
  keyed->keyed.assign(horse.joints.size(), 0);
  for (std::size_t j = 0; j < horse.joints.size(); ++j)
    if (horse.joints[j].node >= 0) keyed->joint[j] = posed(horse, horse.joints[j]), keyed->keyed[j] = 1;
  HorseFrame f;
  f.keyed_pose = std::move(keyed);
  MountedPose out;
  out.horse = poseHorse(p.horse, f);
  // The rider as keyed (the loader adds her no points; one would hang from its parent as at rest).
  const Skeleton& rs = p.rider.skeleton;
  out.rider.resize(rider.joints.size());
  for (std::size_t j = 0; j < rider.joints.size(); ++j) {
    const int up = rs.joints[j].parent;
    if (rider.joints[j].node >= 0) out.rider[j] = posed(rider, rider.joints[j]);
    else out.rider[j] = up < 0 ? rs.joints[j].rest_local : out.rider[std::size_t(up)] * rs.joints[j].rest_local;
  }
  return out;
}

}  // namespace stirrup::rig
