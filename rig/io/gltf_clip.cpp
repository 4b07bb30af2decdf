#include "rig/io/gltf_clip.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <vector>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/euler_angles.hpp>
#include <tiny_gltf.h>

#include "rig/channel_rotation.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_nodes.h"
#include "rig/io/gltf_writer.h"
#include "rig/io/json_fields.h"
#include "rig/mapping/character_mapping.h"
#include "rig/motion/speed_profile.h"

namespace stirrup::rig {

namespace {

// The root node's extras: the clip's name, the channel contract, and what the horse must clear.
tinygltf::Value clipExtras(const Clip& clip) {
  tinygltf::Value::Object extras;
  extras["clip"] = tinygltf::Value(clip.name());
  extras["contract"] = tinygltf::Value(std::string("stirrup docs/channels.md: cm, Y up, +X travel, +Z right"));
  // What the horse must clear (the jump's fence), in the root's travel frame: a shot of the clip read
  // back shows it where the clip put it (GltfClip::obstacles).
  const std::vector<Obstacle> obstacles = clip.obstacles();
  if (!obstacles.empty()) {
    tinygltf::Value::Array list;
    for (const Obstacle& o : obstacles) {
      tinygltf::Value::Object fence;
      fence["travel_cm"] = tinygltf::Value(o.travel_cm);
      fence["height_cm"] = tinygltf::Value(o.height_cm);
      fence["width_cm"] = tinygltf::Value(o.width_cm);
      fence["depth_cm"] = tinygltf::Value(o.depth_cm);
      list.push_back(tinygltf::Value(fence));
    }
    extras["obstacles"] = tinygltf::Value(list);
  }
  return tinygltf::Value(extras);
}

}  // namespace

void writeClipGltf(const Clip& clip, const std::filesystem::path& file, const GltfWriteOptions& o) {
  if (!(o.fps > 0.0)) throw InputError(file.string() + ": fps must be > 0");
  const double end = o.end_s < 0.0 ? clip.duration() : o.end_s;
  const int frames = std::max(2, static_cast<int>(std::floor((end - o.start_s) * o.fps + 1e-9)) + 1);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "stirrup clip make";
  // Nodes: the root carries the travel; the controls are its children, at rest = identity.
  for (const char* n : kClipControlNames) {
    tinygltf::Node node;
    node.name = n;
    model.nodes.push_back(node);
  }
  for (int i = 1; i < static_cast<int>(kClipControlNames.size()); ++i) model.nodes[0].children.push_back(i);
  model.nodes[0].extras = clipExtras(clip);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  std::vector<float> times;
  std::vector<std::vector<float>> translations(kClipControlNames.size()), rotations(kClipControlNames.size());
  using H = HorseChannel;
  const auto pushT = [&](int node, double x, double y, double z) {
    translations[node].insert(translations[node].end(), {float(x), float(y), float(z)});
  };
  const auto pushR = [&](int node, const glm::dquat& q) {
    rotations[node].insert(rotations[node].end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
  };
  bool turns = false;
  for (int i = 0; i < frames; ++i) {
    const double t = o.start_s + i / o.fps;
    const HorseFrame f = clip.sample(t);
    const HorseChannels& c = f.controls;
    times.push_back(float(t - o.start_s));
    // The root carries the travel frame: along the ground (x, z) and, for a path, its heading (a
    // turn about -Y, rig::travelMatrix), so another tool sees the horse go round its turns.
    pushT(0, f.travel_cm, 0, f.travel_z_cm);
    pushR(0, glm::angleAxis(glm::radians(-f.heading_deg), glm::dvec3(0, 1, 0)));
    turns = turns || f.heading_deg != 0.0;
    pushT(1, c[H::lfHoofTx], c[H::lfHoofTy], c[H::lfHoofTz]);
    pushT(2, c[H::rfHoofTx], c[H::rfHoofTy], c[H::rfHoofTz]);
    pushT(3, c[H::lbHoofTx], c[H::lbHoofTy], c[H::lbHoofTz]);
    pushT(4, c[H::rbHoofTx], c[H::rbHoofTy], c[H::rbHoofTz]);
    pushT(5, c[H::rearPivotTx], c[H::rearPivotTy], c[H::rearPivotTz]);
    pushR(5, rotationFromChannels(c[H::rearPivotRx], c[H::rearPivotRy], c[H::rearPivotRz]));
    pushR(6, rotationFromChannels(c[H::backMidRx], c[H::backMidRy], c[H::backMidRz]));
    pushR(7, rotationFromChannels(0, 0, f.neck_rz));
    pushR(8, rotationFromChannels(0, 0, f.head_rz));
    pushR(9, rotationFromChannels(0, f.tail_ry, f.tail_rz));
  }
  if (!turns) rotations[0].clear();  // a straight clip's root only translates, as before paths
  std::vector<unsigned char> bin;
  const int input = appendFloatAccessor(model, bin, times, 1, true);
  tinygltf::Animation anim;
  anim.name = clip.name();
  for (int n = 0; n < static_cast<int>(kClipControlNames.size()); ++n) {
    if (!translations[n].empty()) appendLinearChannel(model, bin, anim, input, n, "translation", translations[n], 3);
    if (!rotations[n].empty()) appendLinearChannel(model, bin, anim, input, n, "rotation", rotations[n], 4);
  }
  model.animations.push_back(anim);
  writeFileAtomically(file, file.extension() == ".glb" ? glbBytes(model, std::move(bin)) : gltfTextBytes(model, std::move(bin)));
}

ClipMapping contractMapping() {
  ClipMapping m;
  for (const char* n : kClipControlNames) m.nodes[n] = n;
  return m;
}

ClipMapping loadClipMapping(const std::filesystem::path& file) {
  const nlohmann::json json = readJsonFile(file);
  JsonObjectReader r(file.string(), "", json);
  ClipMapping m;
  m.file = file;
  const std::string mode = r.string("mode", "controls");
  if (mode == "controls") m.mode = ClipMapping::Mode::Controls;
  else if (mode == "skeleton") m.mode = ClipMapping::Mode::Skeleton;
  else r.fail("mode", "expected \"controls\" or \"skeleton\", got \"" + mode + "\"");
  m.animation = r.string("animation", "");
  m.loop = r.boolean("loop", m.mode == ClipMapping::Mode::Skeleton);
  m.scale_cm = r.number("scale_cm", m.scale_cm, kMinMappingScaleCm, kMaxMappingScaleCm, "centimetres per file unit");
  m.forward = r.numbers<3>("forward", m.forward, -kMaxMappingAxis, kMaxMappingAxis);
  m.up = r.numbers<3>("up", m.up, -kMaxMappingAxis, kMaxMappingAxis);
  if (const auto [field, expected] = mappingAxesProblem(m.forward, m.up); !field.empty()) r.fail(field, expected);
  const std::string ground = r.string("ground", "lowest");
  if (ground != "lowest" && ground != "rest") r.fail("ground", "expected \"lowest\" or \"rest\", got \"" + ground + "\"");
  m.ground_at_lowest = ground == "lowest";
  if (const nlohmann::json* v = r.value("speed_cm_s")) {
    if (v->is_string() && v->get<std::string>() == "auto") m.speed_auto = true;
    else if (v->is_number()) m.speed_cm_s = r.number("speed_cm_s", 0.0, 0.0, SpeedProfile::kMaxSpeedCmS, "centimetres per second");
    else r.fail("speed_cm_s", "expected centimetres per second or \"auto\", got " + describeJson(*v));
  }
  r.string("comment", "");
  if (!r.has("nodes")) r.fail("nodes", "expected an object from control names to node names");
  const nlohmann::json* nodes = r.value("nodes");
  if (!nodes->is_object()) r.fail("nodes", "expected an object from control names to node names, got " + describeJson(*nodes));
  for (const auto& [control, node] : nodes->items()) {
    // (std::find, not a lambda: clang 14, the fuzz build's compiler, cannot capture a structured binding.)
    if (std::find(kClipControlNames.begin(), kClipControlNames.end(), std::string_view(control)) == kClipControlNames.end())
      r.fail("nodes." + control, "unknown control (expected horse, lfHoof, rfHoof, lbHoof, rbHoof, rearPivot, backMid, neck, head or tail)");
    if (!node.is_string()) r.fail("nodes." + control, "expected a node name, got " + describeJson(node));
    m.nodes[control] = node.get<std::string>();
  }
  for (const char* needed : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"})
    if (!m.nodes.count(needed)) r.fail("nodes", std::string("expected a node for ") + needed);
  r.finish();
  return m;
}

// ---- reading ----

struct GltfClip::Impl {
  std::unique_ptr<GltfAnimation> animation;
  ClipMapping mapping;
  std::string file;
  std::map<std::string, int> control_node;  // control name -> node index
  // Skeleton mode: the travel frame's axes in file space, and rest / ground values per control.
  glm::dmat3 to_travel{1.0};
  std::map<std::string, glm::dvec3> rest_position;
  std::map<std::string, glm::dquat> rest_rotation;
  std::map<std::string, double> ground;
  std::vector<Obstacle> obstacles;  // from the root control's extras (clips written by stirrup)

  // `extras.obstacles` of the node bound to the root control: an array of objects with travel_cm,
  // height_cm (> 0), and optionally width_cm and depth_cm (> 0). Absent: no obstacles.
  void readObstacles(const tinygltf::Model& model) {
    const int root = control_node.at("horse");
    const tinygltf::Value& extras = model.nodes[static_cast<std::size_t>(root)].extras;
    if (!extras.IsObject() || !extras.Has("obstacles")) return;
    const std::string where = file + ": node \"" + model.nodes[static_cast<std::size_t>(root)].name + "\": extras.obstacles";
    const tinygltf::Value& list = extras.Get("obstacles");
    if (!list.IsArray()) throw InputError(where + ": expected an array of obstacles");
    for (std::size_t i = 0; i < list.ArrayLen(); ++i) {
      const tinygltf::Value& o = list.Get(static_cast<int>(i));
      const std::string at = where + "[" + std::to_string(i) + "]";
      if (!o.IsObject()) throw InputError(at + ": expected an object");
      Obstacle fence;
      const auto number = [&](const char* key, double& out, bool required, bool positive) {
        if (!o.Has(key)) {
          if (required) throw InputError(at + "." + key + ": missing (expected a number)");
          return;
        }
        const tinygltf::Value& v = o.Get(key);
        if (!v.IsNumber()) throw InputError(at + "." + key + ": expected a number");
        out = v.GetNumberAsDouble();
        if (!std::isfinite(out) || (positive && !(out > 0.0)))
          throw InputError(at + "." + key + ": expected a " + (positive ? "number > 0" : "finite number") +
                           ", got " + std::to_string(out));
      };
      number("travel_cm", fence.travel_cm, true, false);
      number("height_cm", fence.height_cm, true, true);
      number("width_cm", fence.width_cm, false, true);
      number("depth_cm", fence.depth_cm, false, true);
      obstacles.push_back(fence);
    }
  }

  double duration() const { return animation->duration(); }
  GltfTrs local(int node, std::optional<double> t) const { return animation->localTrs(node, t); }
  glm::dmat4 world(int node, std::optional<double> t) const { return animation->world(node, t); }
};

GltfClip::GltfClip(const std::filesystem::path& file, const ClipMapping& mapping) try : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.file = file.string();
  m.mapping = mapping;
  const tinygltf::Model model = readGltfFile(file, m.file);
  const std::string where = mapping.file.empty() ? m.file : mapping.file.string();
  // Nodes by name.
  for (const auto& [control, node_name] : mapping.nodes) {
    int found = -1;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (model.nodes[i].name == node_name) found = static_cast<int>(i);
    if (found < 0) throw InputError(where + ": nodes." + control + ": no node named \"" + node_name + "\" in " + m.file);
    m.control_node[control] = found;
  }
  m.animation = std::make_unique<GltfAnimation>(model, m.file, mapping.animation);
  if (mapping.mode == ClipMapping::Mode::Controls && m.control_node.count("horse")) m.readObstacles(model);
  if (mapping.mode == ClipMapping::Mode::Skeleton) {
    const glm::dvec3 fwd = glm::normalize(glm::dvec3(mapping.forward[0], mapping.forward[1], mapping.forward[2]));
    const glm::dvec3 up = glm::normalize(glm::dvec3(mapping.up[0], mapping.up[1], mapping.up[2]));
    if (std::abs(glm::dot(fwd, up)) > 1e-3) throw InputError(where + ": forward and up must be perpendicular");
    const glm::dvec3 right = glm::cross(fwd, up);
    // Rows are the travel axes: file -> travel.
    m.to_travel = glm::transpose(glm::dmat3(fwd, up, right));
    for (const auto& [control, node] : m.control_node) {
      const glm::dmat4 w = m.world(node, std::nullopt);
      m.rest_position[control] = m.to_travel * glm::dvec3(w[3]);
      m.rest_rotation[control] = gltfRotationOf(w);
    }
    // Ground under each hoof: its rest height, or the lowest it reaches in the clip.
    for (const char* hoof : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"}) {
      double g = m.rest_position[hoof].y;
      if (mapping.ground_at_lowest) {
        g = 1e300;
        for (int i = 0; i <= 200; ++i) {
          const glm::dmat4 w = m.world(m.control_node[hoof], m.duration() * i / 200.0);
          g = std::min(g, (m.to_travel * glm::dvec3(w[3])).y);
        }
      }
      m.ground[hoof] = g;
    }
    if (mapping.speed_auto && m.duration() > 0.0) {
      // The hoof nearest the ground carries the horse: the travel that keeps it still in the world.
      constexpr int kSteps = 400;
      double back = 0.0;
      for (int i = 0; i < kSteps; ++i) {
        const double t0 = m.duration() * i / kSteps, t1 = m.duration() * (i + 1) / kSteps;
        double lowest = 1e300, dx = 0.0;
        for (const char* hoof : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"}) {
          const glm::dvec3 a = m.to_travel * glm::dvec3(m.world(m.control_node[hoof], t0)[3]);
          const glm::dvec3 b = m.to_travel * glm::dvec3(m.world(m.control_node[hoof], t1)[3]);
          if (a.y - m.ground[hoof] < lowest) {
            lowest = a.y - m.ground[hoof];
            dx = b.x - a.x;
          }
        }
        back -= dx;
      }
      m.mapping.speed_cm_s = std::max(0.0, back / m.duration() * mapping.scale_cm);
    }
  }
} catch (const std::out_of_range&) {
  // An index the checks above do not cover (an accessor, buffer view or node index past its array): the
  // .at() lookups throw, and the user gets one line naming the file (found by fuzzing).
  throw InputError(file.string() + ": not a valid glTF file (an index points past the end of its array)");
}

GltfClip::~GltfClip() = default;

std::string GltfClip::name() const {
  const std::string& a = impl_->animation->name();
  return a.empty() ? impl_->file : a;
}

double GltfClip::duration() const { return impl_->duration(); }

std::vector<Obstacle> GltfClip::obstacles() const { return impl_->obstacles; }

HorseFrame GltfClip::sample(double seconds) const {
  const Impl& m = *impl_;
  // Loop the file's animation (travel keeps accumulating) or hold its ends.
  const bool loop = m.mapping.loop && m.duration() > 0.0;
  const double t = loop ? seconds - m.duration() * std::floor(seconds / m.duration()) : std::clamp(seconds, 0.0, m.duration());
  const double cycles = loop ? std::floor(seconds / m.duration()) : 0.0;
  HorseFrame f;
  using H = HorseChannel;
  const auto hoofChannels = [](const std::string& c) -> std::array<H, 3> {
    if (c == "lfHoof") return {H::lfHoofTx, H::lfHoofTy, H::lfHoofTz};
    if (c == "rfHoof") return {H::rfHoofTx, H::rfHoofTy, H::rfHoofTz};
    if (c == "lbHoof") return {H::lbHoofTx, H::lbHoofTy, H::lbHoofTz};
    return {H::rbHoofTx, H::rbHoofTy, H::rbHoofTz};
  };
  const auto has = [&](const char* c) { return m.control_node.count(c) > 0; };
  if (m.mapping.mode == ClipMapping::Mode::Controls) {
    // Node-local values relative to the node's rest pose in the file are the channels.
    const auto trs = [&](const char* c) {
      const int node = m.control_node.at(c);
      const GltfTrs rest = m.local(node, std::nullopt);
      GltfTrs x = m.local(node, t);
      x.t -= rest.t;
      x.r = glm::inverse(rest.r) * x.r;
      return x;
    };
    if (has("horse")) {
      const int root = m.control_node.at("horse");
      const double per_cycle = m.local(root, m.duration()).t.x - m.local(root, 0.0).t.x;
      const auto root_trs = trs("horse");
      f.travel_cm = root_trs.t.x + cycles * per_cycle;
      // A root that moves sideways and turns drives the travel frame along its path (issue 15): its
      // heading is where it points +X, + from +X toward +Z.
      f.travel_z_cm = root_trs.t.z;
      const glm::dvec3 ahead = root_trs.r * glm::dvec3(1, 0, 0);
      if (std::abs(ahead.x) + std::abs(ahead.z) > 1e-9) f.heading_deg = glm::degrees(std::atan2(ahead.z, ahead.x));
    }
    for (const char* hoof : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"}) {
      const glm::dvec3 p = trs(hoof).t;
      const auto ch = hoofChannels(hoof);
      for (int i = 0; i < 3; ++i) f.controls[ch[i]] = p[i];
    }
    if (has("rearPivot")) {
      const auto x = trs("rearPivot");
      const auto r = channelsFromRotation(x.r);
      f.controls[H::rearPivotTx] = x.t.x, f.controls[H::rearPivotTy] = x.t.y, f.controls[H::rearPivotTz] = x.t.z;
      f.controls[H::rearPivotRx] = r[0], f.controls[H::rearPivotRy] = r[1], f.controls[H::rearPivotRz] = r[2];
    }
    if (has("backMid")) {
      const auto r = channelsFromRotation(trs("backMid").r);
      f.controls[H::backMidRx] = r[0], f.controls[H::backMidRy] = r[1], f.controls[H::backMidRz] = r[2];
    }
    if (has("neck")) f.neck_rz = channelsFromRotation(trs("neck").r)[2];
    if (has("head")) f.head_rz = channelsFromRotation(trs("head").r)[2];
    if (has("tail")) {
      const auto r = channelsFromRotation(trs("tail").r);
      f.tail_rz = r[2];
      f.tail_ry = r[1];
    }
    return f;
  }
  // Skeleton: world positions and rotations relative to rest, in the travel frame, scaled to the horse.
  const double s = m.mapping.scale_cm;
  f.travel_cm = m.mapping.speed_cm_s * (loop ? seconds : t);
  const auto position = [&](const std::string& c) {
    return m.to_travel * glm::dvec3(m.world(m.control_node.at(c), t)[3]);
  };
  const auto relativeRotation = [&](const std::string& c) {
    const glm::dquat q = gltfRotationOf(m.world(m.control_node.at(c), t)) * glm::inverse(m.rest_rotation.at(c));
    return channelsFromRotation(glm::quat_cast(m.to_travel * glm::mat3_cast(q) * glm::transpose(m.to_travel)));
  };
  for (const char* hoof : {"lfHoof", "rfHoof", "lbHoof", "rbHoof"}) {
    const glm::dvec3 p = position(hoof), rest = m.rest_position.at(hoof);
    const auto ch = hoofChannels(hoof);
    f.controls[ch[0]] = (p.x - rest.x) * s;
    f.controls[ch[1]] = std::max(0.0, (p.y - m.ground.at(hoof)) * s);
    f.controls[ch[2]] = (p.z - rest.z) * s;
  }
  if (has("rearPivot")) {
    const glm::dvec3 d = (position("rearPivot") - m.rest_position.at("rearPivot")) * s;
    const auto r = relativeRotation("rearPivot");
    f.controls[H::rearPivotTx] = d.x, f.controls[H::rearPivotTy] = d.y, f.controls[H::rearPivotTz] = d.z;
    f.controls[H::rearPivotRx] = r[0], f.controls[H::rearPivotRy] = r[1], f.controls[H::rearPivotRz] = r[2];
  }
  if (has("backMid")) {
    const auto r = relativeRotation("backMid");
    f.controls[H::backMidRx] = r[0], f.controls[H::backMidRy] = r[1], f.controls[H::backMidRz] = r[2];
  }
  if (has("neck")) f.neck_rz = relativeRotation("neck")[2];
  if (has("head")) f.head_rz = relativeRotation("head")[2];
  if (has("tail")) {
    const auto r = relativeRotation("tail");
    f.tail_rz = r[2];
    f.tail_ry = r[1];
  }
  return f;
}

}  // namespace stirrup::rig
