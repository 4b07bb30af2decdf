#include "scene/clip_factory.h"

#include <algorithm>
#include <functional>
#include <map>
#include <span>
#include <sstream>
#include <variant>

#include "rig/error.h"
#include "rig/io/character_mapping_json.h"
#include "rig/io/gltf_mapping.h"
#include "rig/pose.h"
#include <tiny_gltf.h>

#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_animation.h"
#include "rig/io/gltf_clip.h"
#include "rig/io/keyed_horse_clip.h"
#include "rig/mapping/auto_mapping.h"
#include "rig/mapping/character_mapping.h"
#include "rig/motion/movement_clips.h"
#include "rig/motion/path_clip.h"

namespace stirrup::scene {
namespace {

const std::vector<std::string> kCommon = {"duration_s", "variation", "seed", "lead"};

// Reads a generator's parameters from a JSON object (already limited to known keys) into the
// builders' structs. Errors name the field through `fail`.
struct ParamReader {
  const nlohmann::json& p;
  std::function<void(const std::string&, const std::string&)> fail;

  double number(const std::string& key, double fallback, double lo, double hi) const {
    if (!p.contains(key)) return fallback;
    const nlohmann::json& v = p.at(key);
    if (!v.is_number()) fail(key, "expected a number, got " + rig::describeJson(v));
    const double x = v.get<double>();
    if (!(x >= lo && x <= hi)) {
      std::ostringstream s;
      s << "expected a number from " << lo << " to " << hi << ", got " << x;
      fail(key, s.str());
    }
    return x;
  }
  int integer(const std::string& key, int fallback, int lo, int hi) const {
    const double x = number(key, fallback, lo, hi);
    if (x != static_cast<int>(x)) fail(key, "expected a whole number");
    return static_cast<int>(x);
  }
  bool boolean(const std::string& key, bool fallback) const {
    if (!p.contains(key)) return fallback;
    if (!p.at(key).is_boolean()) fail(key, "expected true or false, got " + rig::describeJson(p.at(key)));
    return p.at(key).get<bool>();
  }
  rig::Lead lead() const {
    if (!p.contains("lead")) return rig::Lead::Right;
    const nlohmann::json& v = p.at("lead");
    if (v == "left") return rig::Lead::Left;
    if (v == "right") return rig::Lead::Right;
    fail("lead", "expected \"left\" or \"right\", got " + rig::describeJson(v));
    return rig::Lead::Right;
  }
  rig::Variation variation(double fallback_amount) const {
    rig::Variation v;
    v.amount = number("variation", fallback_amount, 0.0, 1.0);
    v.seed = static_cast<unsigned>(integer("seed", 1, 0, 2147483647));
    return v;
  }
};

// One numeric parameter of a movement: its key, the field of the builder's struct it sets and its
// valid range. A table of these both reads the parameters and lists them (clipGeneratorParameters), so
// the two cannot drift.
template <class P>
struct Field {
  const char* key;
  std::variant<double P::*, int P::*> member;
  double lo, hi;
  double (*hi_of)(const P&) = nullptr;  // an upper bound that depends on a field read before this one
};

// Reads every field of the table that the JSON names, in table order, over the struct's defaults.
template <class P>
P readFields(P p, std::span<const Field<P>> fields, const ParamReader& r) {
  for (const Field<P>& f : fields) {
    const double hi = f.hi_of ? f.hi_of(p) : f.hi;
    if (const auto* d = std::get_if<double P::*>(&f.member)) p.*(*d) = r.number(f.key, p.*(*d), f.lo, hi);
    else {
      int P::*i = std::get<int P::*>(f.member);
      p.*i = r.integer(f.key, p.*i, static_cast<int>(f.lo), static_cast<int>(hi));
    }
  }
  return p;
}

template <class P>
std::vector<std::string> keysOf(std::span<const Field<P>> fields) {
  std::vector<std::string> keys;
  for (const Field<P>& f : fields) keys.push_back(f.key);
  return keys;
}

const Field<rig::StopParams> kStopFields[] = {
    {"entry_speed_cm_s", &rig::StopParams::entry_speed_cm_s, 300.0, 1700.0},
    {"entry_s", &rig::StopParams::entry_s, 0.5, 60.0},
    {"slide_s", &rig::StopParams::slide_s, 0.3, 5.0},
    {"hind_under_cm", &rig::StopParams::hind_under_cm, 0.0, 80.0},
    {"croup_drop_cm", &rig::StopParams::croup_drop_cm, 0.0, 80.0},
    {"pitch_deg", &rig::StopParams::pitch_deg, 0.0, 30.0},
    {"fore_lift_cm", &rig::StopParams::fore_lift_cm, 0.0, 50.0},
    {"settle_s", &rig::StopParams::settle_s, 0.5, 30.0},
};
const Field<rig::JumpParams> kJumpFields[] = {
    {"fence_height_cm", &rig::JumpParams::fence_height_cm, 0.0, 200.0},
    {"approach_speed_cm_s", &rig::JumpParams::approach_speed_cm_s, 300.0, 900.0},
    {"approach_strides", &rig::JumpParams::approach_strides, 1, 20},
    {"recovery_strides", &rig::JumpParams::recovery_strides, 0, 20},
    {"takeoff_pitch_deg", &rig::JumpParams::takeoff_pitch_deg, 0.0, 45.0},
    {"landing_pitch_deg", &rig::JumpParams::landing_pitch_deg, -45.0, 0.0},
    {"fore_tuck_cm", &rig::JumpParams::fore_tuck_cm, 10.0, 120.0},
    {"hind_tuck_cm", &rig::JumpParams::hind_tuck_cm, 10.0, 120.0},
    {"clearance_cm", &rig::JumpParams::clearance_cm, 0.0, 60.0},
};
const Field<rig::RearParams> kRearFields[] = {
    {"angle_deg", &rig::RearParams::angle_deg, 10.0, 80.0},
    {"rise_s", &rig::RearParams::rise_s, 0.2, 5.0},
    {"hold_s", &rig::RearParams::hold_s, 0.0, 10.0},
    {"descend_s", &rig::RearParams::descend_s, 0.2, 5.0},
    {"hind_under_cm", &rig::RearParams::hind_under_cm, 0.0, 60.0},
    {"paw_strokes", &rig::RearParams::paw_strokes, 0, 8},
    {"paw_cm", &rig::RearParams::paw_cm, 0.0, 40.0},
};
const Field<rig::BuckParams> kBuckFields[] = {
    {"bucks", &rig::BuckParams::bucks, 1, 50},
    {"period_s", &rig::BuckParams::period_s, 0.6, 5.0},
    {"croup_deg", &rig::BuckParams::croup_deg, -60.0, 0.0},
    // A kick takes at most 60% of its buck, so the forehand has time to come down before the next.
    {"kick_s", &rig::BuckParams::kick_s, 0.15, 0.0, [](const rig::BuckParams& b) { return 0.6 * b.period_s; }},
    {"kick_lift_cm", &rig::BuckParams::kick_lift_cm, 0.0, 150.0},
    {"twist_deg", &rig::BuckParams::twist_deg, 0.0, 45.0},
    {"front_rise_deg", &rig::BuckParams::front_rise_deg, 0.0, 45.0},
    {"leap_s", &rig::BuckParams::leap_s, 0.05, 0.3},
};

const std::vector<std::string> kSteady = {"speed_cm_s", "stride_hz", "hoof_lift_cm", "duty_factor", "trunk_bounce_cm",
                                          "pitch_deg", "roll_deg"};
const std::map<std::string, std::vector<std::string>> kParameters = {
    {"walk", kSteady},
    {"trot", kSteady},
    {"canter", kSteady},
    {"gallop", kSteady},
    {"sequence", {"gaits", "segment_s", "blend_s", "end_with_stop", "slide_s"}},
    {"stop", keysOf<rig::StopParams>(kStopFields)},
    {"jump", keysOf<rig::JumpParams>(kJumpFields)},
    {"rear", keysOf<rig::RearParams>(kRearFields)},
    {"buck", keysOf<rig::BuckParams>(kBuckFields)},
    {"path", {"points", "speed", "speed_over", "segment_gaits", "roll_limit_deg"}},
};

rig::GaitParams steadyFrom(const std::string& generator, const ParamReader& r) {
  const rig::Lead lead = r.lead();
  rig::GaitParams g = generator == "gallop" ? rig::gallopParams(r.number("speed_cm_s", 900.0, 100.0, 2000.0), lead)
                                       : *rig::gaitParamsByName(generator, lead);
  g.speed_cm_s = r.number("speed_cm_s", g.speed_cm_s, 0.0, 2000.0);
  g.stride_hz = r.number("stride_hz", g.stride_hz, 0.1, 5.0);
  g.hoof_lift_cm = r.number("hoof_lift_cm", g.hoof_lift_cm, 0.0, 100.0);
  if (r.p.contains("duty_factor")) {
    const double d = r.number("duty_factor", 0.4, 0.01, 0.99);
    g.duty_factor = {d, d, d, d};
  }
  g.trunk_bounce_cm = r.number("trunk_bounce_cm", g.trunk_bounce_cm, 0.0, 50.0);
  g.pitch_deg = r.number("pitch_deg", g.pitch_deg, 0.0, 30.0);
  g.roll_deg = r.number("roll_deg", g.roll_deg, 0.0, 30.0);
  return g;
}

std::vector<rig::GaitParams> gaitList(const ParamReader& r, rig::Lead lead) {
  std::vector<std::string> names = {"walk", "trot", "canter", "gallop"};
  if (r.p.contains("gaits")) {
    const nlohmann::json& v = r.p.at("gaits");
    names.clear();
    if (v.is_string()) {
      std::stringstream ss(v.get<std::string>());
      for (std::string n; std::getline(ss, n, ',');) names.push_back(n);
    } else if (v.is_array()) {
      for (const auto& n : v) {
        if (!n.is_string()) r.fail("gaits", "expected gait names, got " + rig::describeJson(n));
        names.push_back(n.get<std::string>());
      }
    } else {
      r.fail("gaits", "expected \"walk,trot,...\" or an array of gait names, got " + rig::describeJson(v));
    }
  }
  std::vector<rig::GaitParams> out;
  for (const std::string& n : names) {
    const auto g = rig::gaitParamsByName(n, lead);
    if (!g) r.fail("gaits", "expected walk, trot, canter or gallop, got \"" + n + "\"");
    out.push_back(*g);
  }
  if (out.empty()) r.fail("gaits", "expected at least one gait");
  return out;
}

// A path's points: [[x, z], ...] in cm.
std::vector<glm::dvec2> pathPoints(const ParamReader& r) {
  if (!r.p.contains("points")) r.fail("points", "expected the path's points [[x, z], ...] (cm)");
  const nlohmann::json& v = r.p.at("points");
  if (!v.is_array()) r.fail("points", "expected an array of points [x, z] (cm), got " + rig::describeJson(v));
  std::vector<glm::dvec2> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const nlohmann::json& q = v[i];
    if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
      r.fail("points[" + std::to_string(i) + "]", "expected a point [x, z] (cm), got " + rig::describeJson(q));
    out.push_back({q[0].get<double>(), q[1].get<double>()});
  }
  return out;
}

// The path's speed: "speed": [[time s or distance cm, cm/s], ...] with "speed_over": "time" (default)
// or "distance"; or "segment_gaits": one gait name per segment between points, each at its gait's
// reference speed over the middle half of its segment.
void pathSpeed(const ParamReader& r, rig::PathClipParams& p) {
  const bool keys = r.p.contains("speed"), gaits = r.p.contains("segment_gaits");
  if (keys == gaits) r.fail("speed", "expected either \"speed\" keys or \"segment_gaits\", one of the two");
  const std::string over = r.p.value("speed_over", std::string("time"));
  if (r.p.contains("speed_over") && !r.p.at("speed_over").is_string())
    r.fail("speed_over", "expected \"time\" or \"distance\", got " + rig::describeJson(r.p.at("speed_over")));
  if (over != "time" && over != "distance") r.fail("speed_over", "expected \"time\" or \"distance\", got \"" + over + "\"");
  p.over = over == "time" ? rig::SpeedProfile::Over::Time : rig::SpeedProfile::Over::Distance;
  if (keys) {
    const nlohmann::json& v = r.p.at("speed");
    if (!v.is_array()) r.fail("speed", "expected speed keys [[at, cm/s], ...], got " + rig::describeJson(v));
    for (std::size_t i = 0; i < v.size(); ++i) {
      const nlohmann::json& q = v[i];
      if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
        r.fail("speed[" + std::to_string(i) + "]", "expected a key [" + std::string(over == "time" ? "seconds" : "cm") +
                                                       ", cm/s], got " + rig::describeJson(q));
      p.speed.push_back({q[0].get<double>(), q[1].get<double>()});
    }
    return;
  }
  const nlohmann::json& v = r.p.at("segment_gaits");
  if (!v.is_array() || v.size() + 1 != p.points.size())
    r.fail("segment_gaits", "expected one gait name per segment (" + std::to_string(p.points.size() - 1) + "), got " +
                                rig::describeJson(v));
  const rig::GroundPath path(p.points, "");
  p.over = rig::SpeedProfile::Over::Distance;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto g = v[i].is_string() ? rig::gaitParamsByName(v[i].get<std::string>()) : std::nullopt;
    if (!g) r.fail("segment_gaits[" + std::to_string(i) + "]", "expected walk, trot, canter or gallop, got " + rig::describeJson(v[i]));
    const double a = path.distanceAtPoint(i), b = path.distanceAtPoint(i + 1);
    p.speed.push_back({a + 0.25 * (b - a), g->speed_cm_s});
    p.speed.push_back({a + 0.75 * (b - a), g->speed_cm_s});
  }
}

rig::PathClipParams pathParams(const ParamReader& r, const ClipSpec& spec) {
  rig::PathClipParams p;
  p.points = pathPoints(r);
  if (r.p.contains("duration_s")) p.max_duration_s = r.number("duration_s", 600.0, 0.1, 600.0);
  p.first_lead = r.lead();
  p.roll_limit_deg = r.number("roll_limit_deg", p.roll_limit_deg, 0.0, 45.0);
  const rig::Variation v = r.variation(0.0);
  p.variation = v.amount;
  p.seed = v.seed;
  if (spec.hoof_rest) p.hoof_rest = *spec.hoof_rest;
  // Points first: the segment gaits need a valid path to place their speeds.
  (void)rig::GroundPath(p.points, spec.source);
  pathSpeed(r, p);
  return p;
}

std::unique_ptr<rig::Clip> buildPath(const ParamReader& r, const ClipSpec& spec) {
  return std::make_unique<rig::PathClip>(pathParams(r, spec), spec.terrain, spec.source);
}

std::unique_ptr<rig::Clip> buildGenerator(const std::string& gen, const ParamReader& r, const ClipSpec& spec) {
  if (gen == "path") return buildPath(r, spec);
  const double duration = r.number("duration_s", 10.0, 0.1, 600.0);
  if (gen == "walk" || gen == "trot" || gen == "canter" || gen == "gallop") {
    const rig::GaitParams g = steadyFrom(gen, r);
    const rig::Variation v = r.variation(0.0);
    // Without variation the closed-form periodic gait (the trot the renderer's goldens were made with).
    if (v.amount == 0.0) return std::make_unique<rig::ProceduralGait>(g, duration);
    rig::Movement m = rig::makeSteadyGait(g, duration, v);
    return std::make_unique<rig::MovementClip>(std::move(m));
  }
  const rig::Variation v = r.variation(0.1);
  if (gen == "sequence") {
    const rig::Lead lead = r.lead();
    const std::vector<rig::GaitParams> gaits = gaitList(r, lead);
    const double segment = r.number("segment_s", 3.0, 0.5, 120.0);
    const double blend = r.number("blend_s", 1.0, 0.1, segment - 0.1);
    rig::StopParams p;
    p.lead = lead;
    p.slide_s = r.number("slide_s", p.slide_s, 0.3, 5.0);  // checked whenever given, used with end_with_stop
    if (r.boolean("end_with_stop", false)) return std::make_unique<rig::MovementClip>(rig::makeGaitSequenceToStop(gaits, segment, blend, p, v));
    return std::make_unique<rig::MovementClip>(rig::makeGaitSequence(gaits, segment, blend, v));
  }
  if (gen == "stop") {
    rig::StopParams p;
    p.lead = r.lead();
    return std::make_unique<rig::MovementClip>(rig::makeStop(readFields<rig::StopParams>(p, kStopFields, r), v));
  }
  if (gen == "jump") {
    rig::JumpParams p;
    p.lead = r.lead();
    return std::make_unique<rig::MovementClip>(rig::makeJump(readFields<rig::JumpParams>(p, kJumpFields, r), v));
  }
  if (gen == "rear") return std::make_unique<rig::MovementClip>(rig::makeRear(readFields<rig::RearParams>({}, kRearFields, r), v));
  if (gen == "buck") return std::make_unique<rig::MovementClip>(rig::makeBuck(readFields<rig::BuckParams>({}, kBuckFields, r), v));
  r.fail("generator", "unknown generator \"" + gen + "\"");
  return nullptr;
}

}  // namespace

const std::vector<std::string>& clipGenerators() {
  static const std::vector<std::string> names = {"walk", "trot", "canter", "gallop", "sequence",
                                                 "stop", "jump", "rear", "buck", "path"};
  return names;
}

std::vector<std::string> clipGeneratorParameters(const std::string& generator) {
  auto it = kParameters.find(generator);
  if (it == kParameters.end()) return {};
  std::vector<std::string> out = it->second;
  out.insert(out.end(), kCommon.begin(), kCommon.end());
  return out;
}

namespace {

// Whether a mapping file maps a character's roles ("roles") rather than a clip's controls ("nodes").
bool isCharacterMapping(const std::filesystem::path& file) {
  const nlohmann::json json = rig::readJsonFile(file);
  return json.is_object() && json.contains("roles");
}

// Every node a clip written by stirrup has (kClipControlNames) is a node of the file.
bool hasControlNodes(const std::filesystem::path& file) {
  const tinygltf::Model model = rig::readGltfFile(file, file.string());
  for (const char* control : rig::kClipControlNames)
    if (std::none_of(model.nodes.begin(), model.nodes.end(), [&](const tinygltf::Node& n) { return n.name == control; }))
      return false;
  return true;
}

// A horse's animation read through its roles: the spec's character mapping, or the file mapped by
// itself as a horse; `ridden` is the scene's horse when the file is its own.
std::unique_ptr<rig::Clip> keyedClip(const ClipSpec& spec, const rig::Character* ridden) {
  if (spec.terrain)
    throw rig::InputError(spec.source + ".file: " + spec.file.string() +
                     ": a horse's animation read from its file rides on flat ground (its hooves are where they were keyed); "
                     "remove the scene's \"terrain\"");
  if (ridden) return std::make_unique<rig::KeyedHorseClip>(spec.file, spec.animation, rig::keyedHorseMapping(*ridden), ridden);
  if (spec.character_mapping) {
    const rig::CharacterMapping m = rig::loadCharacterMapping(spec.mapping, rig::CharacterKind::Horse);
    return std::make_unique<rig::KeyedHorseClip>(spec.file, spec.animation, rig::keyedHorseMapping(m, spec.file.string()), nullptr);
  }
  const rig::AutoMapping m = rig::autoMapCharacterFile(spec.file, rig::CharacterKind::Horse);
  return std::make_unique<rig::KeyedHorseClip>(spec.file, spec.animation, rig::keyedHorseMapping(m.mapping, spec.file.string()), nullptr);
}

bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec);
}

}  // namespace

bool readsControlNodes(const ClipSpec& spec) {
  if (spec.file.empty() || spec.character_mapping) return false;
  if (spec.control_nodes) return *spec.control_nodes;
  return !spec.mapping.empty() || hasControlNodes(spec.file);
}

double fileClipDuration(const ClipSpec& spec) {
  rig::ClipMapping m = spec.mapping.empty() || spec.character_mapping ? rig::ClipMapping{} : rig::loadClipMapping(spec.mapping);
  const std::string animation = spec.animation.empty() ? m.animation : spec.animation;
  const rig::GltfAnimation a(rig::readGltfFile(spec.file, spec.file.string()), spec.file.string(), animation);
  // A horse's own animation plays from its first key (rig/io/keyed_horse_clip.h); a clip of controls from 0.
  return readsControlNodes(spec) ? a.duration() : a.duration() - a.start();
}

ClipSpec parseClipSpec(rig::JsonObjectReader& r, const std::filesystem::path& base_dir) {
  ClipSpec spec;
  spec.source = r.file() + ": " + r.fieldPath("").substr(0, r.fieldPath("").size() ? r.fieldPath("").size() - 1 : 0);
  if (r.has("file")) {
    if (r.has("generator")) r.fail("generator", "expected either \"generator\" or \"file\", not both");
    spec.generator.clear();
    spec.file = base_dir / r.string("file", "");
    if (r.has("mapping")) spec.mapping = base_dir / r.string("mapping", "");
    spec.animation = r.string("animation", "");
    r.finish();
    // Open it now so a missing file, mapping, node, role or animation is reported at load time.
    if (!std::filesystem::exists(spec.file)) r.fail("file", "no such file: " + spec.file.string());
    if (!spec.mapping.empty() && !std::filesystem::exists(spec.mapping)) r.fail("mapping", "no such file: " + spec.mapping.string());
    spec.character_mapping = !spec.mapping.empty() && isCharacterMapping(spec.mapping);
    spec.control_nodes = readsControlNodes(spec);
    if (*spec.control_nodes) {
      rig::ClipMapping m = spec.mapping.empty() ? rig::contractMapping() : rig::loadClipMapping(spec.mapping);
      if (!spec.animation.empty()) m.animation = spec.animation;
      rig::GltfClip check(spec.file, m);
    } else if (spec.character_mapping) {
      keyedClip(spec, nullptr);
    } else {
      // A horse's own animation: its roles come with the scene's horse; the animation is checked now.
      rig::GltfAnimation check(rig::readGltfFile(spec.file, spec.file.string()), spec.file.string(), spec.animation);
    }
    return spec;
  }
  spec.generator = r.string("generator", "trot");
  const auto known = clipGeneratorParameters(spec.generator);
  if (known.empty()) {
    std::string list;
    for (const auto& g : clipGenerators()) list += (list.empty() ? "" : ", ") + g;
    r.fail("generator", "expected one of " + list + ", got \"" + spec.generator + "\"");
  }
  for (const std::string& k : known)
    if (const nlohmann::json* v = r.value(k)) spec.params[k] = *v;
  r.finish();  // anything else is an unknown parameter
  // Check the values now by building once (cheap), with errors naming the field.
  ParamReader pr{spec.params, [&r](const std::string& key, const std::string& what) { r.fail(key, what); }};
  try {
    buildGenerator(spec.generator, pr, spec);
  } catch (const rig::InputError& e) {
    if (std::string(e.what()).rfind(r.file() + ": ", 0) == 0) throw;  // already names file and field
    throw rig::InputError(r.file() + ": " + r.fieldPath("generator") + ": " + e.what());
  }
  return spec;
}

namespace {

// A parsed spec's parameters read again: errors name the spec's source and the field.
ParamReader specReader(const ClipSpec& spec) {
  return {spec.params, [&spec](const std::string& key, const std::string& what) { throw rig::InputError(spec.source + "." + key + ": " + what); }};
}

}  // namespace

std::vector<rig::GaitSpeed> generatedGaitSpeeds(const ClipSpec& spec) {
  const std::string& g = spec.generator;
  const ParamReader pr = specReader(spec);
  if (g == "walk" || g == "trot" || g == "canter" || g == "gallop") return {{"speed_cm_s", g, steadyFrom(g, pr).speed_cm_s}};
  // The stop enters at a gallop (makeStop), the jump approaches at a canter (makeJump).
  if (g == "stop") return {{"entry_speed_cm_s", "gallop", readFields<rig::StopParams>({}, kStopFields, pr).entry_speed_cm_s}};
  if (g == "jump") return {{"approach_speed_cm_s", "canter", readFields<rig::JumpParams>({}, kJumpFields, pr).approach_speed_cm_s}};
  std::vector<rig::GaitSpeed> out;
  if (g == "sequence") {
    const std::vector<rig::GaitParams> gaits = gaitList(pr, rig::Lead::Right);
    for (std::size_t i = 0; i < gaits.size(); ++i) out.push_back({"gaits[" + std::to_string(i) + "]", gaits[i].name, gaits[i].speed_cm_s});
  }
  return out;
}

std::optional<rig::GaitParams> steadyGaitParams(const ClipSpec& spec) {
  const std::string& g = spec.generator;
  if (g != "walk" && g != "trot" && g != "canter" && g != "gallop") return std::nullopt;
  const ParamReader pr = specReader(spec);
  return steadyFrom(g, pr);
}

std::unique_ptr<rig::Clip> makeClip(const ClipSpec& spec) {
  if (!spec.file.empty()) {
    if (!readsControlNodes(spec)) return keyedClip(spec, nullptr);
    rig::ClipMapping m = spec.mapping.empty() ? rig::contractMapping() : rig::loadClipMapping(spec.mapping);
    if (!spec.animation.empty()) m.animation = spec.animation;
    return std::make_unique<rig::GltfClip>(spec.file, m);
  }
  const ParamReader pr = specReader(spec);
  return buildGenerator(spec.generator, pr, spec);
}

std::optional<rig::PathClipParams> pathClipParams(const ClipSpec& spec) {
  if (spec.generator != "path") return std::nullopt;
  const ParamReader pr = specReader(spec);
  return pathParams(pr, spec);
}

std::unique_ptr<rig::Clip> makeClip(const ClipSpec& spec, const rig::Character& horse) {
  if (!spec.file.empty() && !horse.source.file.empty() && sameFile(spec.file, horse.source.file) && !readsControlNodes(spec))
    return keyedClip(spec, &horse);
  ClipSpec own = spec;
  own.hoof_rest = rig::restHoofPlaces(horse);
  return makeClip(own);
}

}  // namespace stirrup::scene
