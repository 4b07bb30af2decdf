#include "rig/clip_factory.h"

#include <algorithm>
#include <functional>
#include <map>
#include <sstream>

#include "rig/error.h"
#include "rig/gltf_clip.h"
#include "rig/movement_clips.h"

namespace stirrup::rig {
namespace {

const std::vector<std::string> kCommon = {"duration_s", "variation", "seed", "lead"};
const std::vector<std::string> kSteady = {"speed_cm_s", "stride_hz", "hoof_lift_cm", "duty_factor", "trunk_bounce_cm",
                                          "pitch_deg", "roll_deg"};
const std::map<std::string, std::vector<std::string>> kParameters = {
    {"walk", kSteady},
    {"trot", kSteady},
    {"canter", kSteady},
    {"gallop", kSteady},
    {"sequence", {"gaits", "segment_s", "blend_s", "end_with_stop", "slide_s"}},
    {"stop", {"entry_speed_cm_s", "entry_s", "slide_s", "hind_under_cm", "croup_drop_cm", "pitch_deg", "fore_lift_cm",
              "settle_s"}},
    {"jump", {"fence_height_cm", "approach_speed_cm_s", "approach_strides", "recovery_strides", "takeoff_pitch_deg",
              "landing_pitch_deg", "fore_tuck_cm", "hind_tuck_cm", "clearance_cm"}},
    {"rear", {"angle_deg", "rise_s", "hold_s", "descend_s", "hind_under_cm", "paw_strokes", "paw_cm"}},
    {"buck", {"bucks", "period_s", "croup_deg", "kick_s", "kick_lift_cm", "twist_deg", "front_rise_deg", "leap_s"}},
};

// Reads a generator's parameters from a JSON object (already limited to known keys) into the
// builders' structs. Errors name the field through `fail`.
struct ParamReader {
  const nlohmann::json& p;
  std::function<void(const std::string&, const std::string&)> fail;

  double number(const std::string& key, double fallback, double lo, double hi) const {
    if (!p.contains(key)) return fallback;
    const nlohmann::json& v = p.at(key);
    if (!v.is_number()) fail(key, "expected a number, got " + describeJson(v));
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
    if (!p.at(key).is_boolean()) fail(key, "expected true or false, got " + describeJson(p.at(key)));
    return p.at(key).get<bool>();
  }
  Lead lead() const {
    if (!p.contains("lead")) return Lead::Right;
    const nlohmann::json& v = p.at("lead");
    if (v == "left") return Lead::Left;
    if (v == "right") return Lead::Right;
    fail("lead", "expected \"left\" or \"right\", got " + describeJson(v));
    return Lead::Right;
  }
  Variation variation(double fallback_amount) const {
    Variation v;
    v.amount = number("variation", fallback_amount, 0.0, 1.0);
    v.seed = static_cast<unsigned>(integer("seed", 1, 0, 2147483647));
    return v;
  }
};

GaitParams steadyFrom(const std::string& generator, const ParamReader& r) {
  const Lead lead = r.lead();
  GaitParams g = generator == "gallop" ? gallopParams(r.number("speed_cm_s", 900.0, 100.0, 2000.0), lead)
                                       : *gaitParamsByName(generator, lead);
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

std::vector<GaitParams> gaitList(const ParamReader& r, Lead lead) {
  std::vector<std::string> names = {"walk", "trot", "canter", "gallop"};
  if (r.p.contains("gaits")) {
    const nlohmann::json& v = r.p.at("gaits");
    names.clear();
    if (v.is_string()) {
      std::stringstream ss(v.get<std::string>());
      for (std::string n; std::getline(ss, n, ',');) names.push_back(n);
    } else if (v.is_array()) {
      for (const auto& n : v) {
        if (!n.is_string()) r.fail("gaits", "expected gait names, got " + describeJson(n));
        names.push_back(n.get<std::string>());
      }
    } else {
      r.fail("gaits", "expected \"walk,trot,...\" or an array of gait names, got " + describeJson(v));
    }
  }
  std::vector<GaitParams> out;
  for (const std::string& n : names) {
    const auto g = gaitParamsByName(n, lead);
    if (!g) r.fail("gaits", "expected walk, trot, canter or gallop, got \"" + n + "\"");
    out.push_back(*g);
  }
  if (out.empty()) r.fail("gaits", "expected at least one gait");
  return out;
}

std::unique_ptr<Clip> buildGenerator(const std::string& gen, const ParamReader& r) {
  const double duration = r.number("duration_s", 10.0, 0.1, 600.0);
  if (gen == "walk" || gen == "trot" || gen == "canter" || gen == "gallop") {
    const GaitParams g = steadyFrom(gen, r);
    const Variation v = r.variation(0.0);
    // Without variation the closed-form periodic gait (the trot the renderer's goldens were made with).
    if (v.amount == 0.0) return std::make_unique<ProceduralGait>(g, duration);
    Movement m = makeSteadyGait(g, duration, v);
    return std::make_unique<MovementClip>(std::move(m));
  }
  const Variation v = r.variation(0.1);
  if (gen == "sequence") {
    const Lead lead = r.lead();
    const std::vector<GaitParams> gaits = gaitList(r, lead);
    const double segment = r.number("segment_s", 3.0, 0.5, 120.0);
    const double blend = r.number("blend_s", 1.0, 0.1, segment - 0.1);
    if (r.boolean("end_with_stop", false)) {
      StopParams p;
      p.lead = lead;
      p.slide_s = r.number("slide_s", p.slide_s, 0.3, 5.0);
      return std::make_unique<MovementClip>(makeGaitSequenceToStop(gaits, segment, blend, p, v));
    }
    return std::make_unique<MovementClip>(makeGaitSequence(gaits, segment, blend, v));
  }
  if (gen == "stop") {
    StopParams p;
    p.lead = r.lead();
    p.entry_speed_cm_s = r.number("entry_speed_cm_s", p.entry_speed_cm_s, 300.0, 1700.0);
    p.entry_s = r.number("entry_s", p.entry_s, 0.5, 60.0);
    p.slide_s = r.number("slide_s", p.slide_s, 0.3, 5.0);
    p.hind_under_cm = r.number("hind_under_cm", p.hind_under_cm, 0.0, 80.0);
    p.croup_drop_cm = r.number("croup_drop_cm", p.croup_drop_cm, 0.0, 80.0);
    p.pitch_deg = r.number("pitch_deg", p.pitch_deg, 0.0, 30.0);
    p.fore_lift_cm = r.number("fore_lift_cm", p.fore_lift_cm, 0.0, 50.0);
    p.settle_s = r.number("settle_s", p.settle_s, 0.5, 30.0);
    return std::make_unique<MovementClip>(makeStop(p, v));
  }
  if (gen == "jump") {
    JumpParams p;
    p.lead = r.lead();
    p.fence_height_cm = r.number("fence_height_cm", p.fence_height_cm, 0.0, 200.0);
    p.approach_speed_cm_s = r.number("approach_speed_cm_s", p.approach_speed_cm_s, 300.0, 900.0);
    p.approach_strides = r.integer("approach_strides", p.approach_strides, 1, 20);
    p.recovery_strides = r.integer("recovery_strides", p.recovery_strides, 0, 20);
    p.takeoff_pitch_deg = r.number("takeoff_pitch_deg", p.takeoff_pitch_deg, 0.0, 45.0);
    p.landing_pitch_deg = r.number("landing_pitch_deg", p.landing_pitch_deg, -45.0, 0.0);
    p.fore_tuck_cm = r.number("fore_tuck_cm", p.fore_tuck_cm, 10.0, 120.0);
    p.hind_tuck_cm = r.number("hind_tuck_cm", p.hind_tuck_cm, 10.0, 120.0);
    p.clearance_cm = r.number("clearance_cm", p.clearance_cm, 0.0, 60.0);
    return std::make_unique<MovementClip>(makeJump(p, v));
  }
  if (gen == "rear") {
    RearParams p;
    p.angle_deg = r.number("angle_deg", p.angle_deg, 10.0, 80.0);
    p.rise_s = r.number("rise_s", p.rise_s, 0.2, 5.0);
    p.hold_s = r.number("hold_s", p.hold_s, 0.0, 10.0);
    p.descend_s = r.number("descend_s", p.descend_s, 0.2, 5.0);
    p.hind_under_cm = r.number("hind_under_cm", p.hind_under_cm, 0.0, 60.0);
    p.paw_strokes = r.integer("paw_strokes", p.paw_strokes, 0, 8);
    p.paw_cm = r.number("paw_cm", p.paw_cm, 0.0, 40.0);
    return std::make_unique<MovementClip>(makeRear(p, v));
  }
  if (gen == "buck") {
    BuckParams p;
    p.bucks = r.integer("bucks", p.bucks, 1, 50);
    p.period_s = r.number("period_s", p.period_s, 0.6, 5.0);
    p.croup_deg = r.number("croup_deg", p.croup_deg, -60.0, 0.0);
    p.kick_s = r.number("kick_s", p.kick_s, 0.15, 0.6 * p.period_s);
    p.kick_lift_cm = r.number("kick_lift_cm", p.kick_lift_cm, 0.0, 150.0);
    p.twist_deg = r.number("twist_deg", p.twist_deg, 0.0, 45.0);
    p.front_rise_deg = r.number("front_rise_deg", p.front_rise_deg, 0.0, 45.0);
    p.leap_s = r.number("leap_s", p.leap_s, 0.05, 0.3);
    return std::make_unique<MovementClip>(makeBuck(p, v));
  }
  r.fail("generator", "unknown generator \"" + gen + "\"");
  return nullptr;
}

}  // namespace

const std::vector<std::string>& clipGenerators() {
  static const std::vector<std::string> names = {"walk", "trot", "canter", "gallop", "sequence",
                                                 "stop", "jump", "rear", "buck"};
  return names;
}

std::vector<std::string> clipGeneratorParameters(const std::string& generator) {
  auto it = kParameters.find(generator);
  if (it == kParameters.end()) return {};
  std::vector<std::string> out = it->second;
  out.insert(out.end(), kCommon.begin(), kCommon.end());
  return out;
}

ClipSpec parseClipSpec(JsonObjectReader& r, const std::filesystem::path& base_dir) {
  ClipSpec spec;
  spec.source = r.file() + ": " + r.fieldPath("").substr(0, r.fieldPath("").size() ? r.fieldPath("").size() - 1 : 0);
  if (r.has("file")) {
    if (r.has("generator")) r.fail("generator", "expected either \"generator\" or \"file\", not both");
    spec.generator.clear();
    spec.file = base_dir / r.string("file", "");
    if (r.has("mapping")) spec.mapping = base_dir / r.string("mapping", "");
    spec.animation = r.string("animation", "");
    r.finish();
    // Open it now so a missing file, node or animation is reported at load time.
    ClipMapping m = spec.mapping.empty() ? contractMapping() : loadClipMapping(spec.mapping);
    if (!spec.animation.empty()) m.animation = spec.animation;
    if (!std::filesystem::exists(spec.file)) r.fail("file", "no such file: " + spec.file.string());
    GltfClip check(spec.file, m);
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
    buildGenerator(spec.generator, pr);
  } catch (const InputError& e) {
    if (std::string(e.what()).rfind(r.file() + ": ", 0) == 0) throw;  // already names file and field
    throw InputError(r.file() + ": " + r.fieldPath("generator") + ": " + e.what());
  }
  return spec;
}

std::optional<GaitParams> steadyGaitParams(const ClipSpec& spec) {
  const std::string& g = spec.generator;
  if (g != "walk" && g != "trot" && g != "canter" && g != "gallop") return std::nullopt;
  ParamReader pr{spec.params, [&spec](const std::string& key, const std::string& what) {
                   throw InputError(spec.source + "." + key + ": " + what);
                 }};
  return steadyFrom(g, pr);
}

std::unique_ptr<Clip> makeClip(const ClipSpec& spec) {
  if (!spec.file.empty()) {
    ClipMapping m = spec.mapping.empty() ? contractMapping() : loadClipMapping(spec.mapping);
    if (!spec.animation.empty()) m.animation = spec.animation;
    return std::make_unique<GltfClip>(spec.file, m);
  }
  ParamReader pr{spec.params, [&spec](const std::string& key, const std::string& what) {
                   throw InputError(spec.source + "." + key + ": " + what);
                 }};
  return buildGenerator(spec.generator, pr);
}

}  // namespace stirrup::rig
