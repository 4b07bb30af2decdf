#include "scene/crowd_json.h"

#include <cmath>
#include <filesystem>

#include "scene/character_json.h"
#include "scene/frame_range.h"

namespace stirrup::scene {
namespace {

std::vector<glm::dvec2> points(rig::JsonObjectReader& r, const std::string& key) {
  const nlohmann::json* v = r.value(key);
  if (!v) r.fail(key, "expected the path's points [[x, z], ...] (cm)");
  if (!v->is_array()) r.fail(key, "expected an array of points [x, z] (cm), got " + rig::describeJson(*v));
  std::vector<glm::dvec2> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const nlohmann::json& q = (*v)[i];
    if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
      r.fail(key + "[" + std::to_string(i) + "]", "expected a point [x, z] (cm), got " + rig::describeJson(q));
    out.push_back({q[0].get<double>(), q[1].get<double>()});
  }
  return out;
}

std::vector<rig::SpeedProfile::Key> speedKeys(rig::JsonObjectReader& r, const std::string& key, const char* at) {
  const nlohmann::json* v = r.value(key);
  if (!v) r.fail(key, std::string("expected speed keys [[") + at + ", cm/s], ...]");
  if (!v->is_array()) r.fail(key, std::string("expected speed keys [[") + at + ", cm/s], ...], got " + rig::describeJson(*v));
  std::vector<rig::SpeedProfile::Key> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    const nlohmann::json& q = (*v)[i];
    if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
      r.fail(key + "[" + std::to_string(i) + "]", std::string("expected a key [") + at + ", cm/s], got " + rig::describeJson(q));
    out.push_back({q[0].get<double>(), q[1].get<double>()});
  }
  return out;
}

// [low, high]: two numbers.
rig::ProportionRange range(rig::JsonObjectReader& r, const std::string& key, rig::ProportionRange fallback) {
  const auto a = r.numbers<2>(key, {fallback.lo, fallback.hi});
  return {a[0], a[1]};
}

unsigned seedOf(rig::JsonObjectReader& r, const std::string& key, unsigned fallback) {
  const nlohmann::json* v = r.value(key);
  if (!v) return fallback;
  if (!v->is_number_integer() || v->get<std::int64_t>() < 0 || v->get<std::int64_t>() > 2147483647)
    r.fail(key, "expected a whole number from 0 to 2147483647, got " + rig::describeJson(*v));
  return static_cast<unsigned>(v->get<std::int64_t>());
}

// A pair's own characters and motion (issue 60), as the scene's "characters" name them: "horse" and
// "rider" entries (scene/character_json.h), and "animation" for the horse's own.
template <class T>
void readOwnCharacters(rig::JsonObjectReader& r, T& out) {
  const std::filesystem::path dir = std::filesystem::path(r.file()).parent_path();
  const scene::CharacterEntry horse = scene::parseCharacterEntry(r, "horse", dir);
  const scene::CharacterEntry rider = scene::parseCharacterEntry(r, "rider", dir);
  out.horse_file = horse.file, out.horse_mapping = horse.mapping;
  out.rider_file = rider.file, out.rider_mapping = rider.mapping;
  if (r.has("animation")) out.animation = r.string("animation", "");
  if (out.animation && out.horse_file == "default")
    r.fail("animation", "expected a horse file beside it (\"horse\": its own animation is the file's)");
}

// "characters": [{"pairs": "0-3", "horse": ..., "rider": ..., "animation": ...}, ...]
std::vector<rig::CrowdSpec::Characters> crowdCharacters(rig::JsonObjectReader& r) {
  const nlohmann::json* v = r.value("characters");
  if (!v) return {};
  if (!v->is_array()) r.fail("characters", "expected a list of {\"pairs\", \"horse\", \"rider\", \"animation\"}, got " + rig::describeJson(*v));
  std::vector<rig::CrowdSpec::Characters> out;
  for (std::size_t i = 0; i < v->size(); ++i) {
    rig::JsonObjectReader e(r.file(), r.fieldPath("characters[" + std::to_string(i) + "]"), (*v)[i]);
    rig::CrowdSpec::Characters c;
    if (e.has("pairs")) {
      const std::string list = e.string("pairs", "");
      c.pairs = parseFrameList(list, r.file() + ": " + e.fieldPath("pairs"));
    }
    readOwnCharacters(e, c);
    if (c.horse_file == "default" && c.rider_file == "default") e.fail("horse", "expected a \"horse\" or \"rider\" file for these pairs");
    e.finish();
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

rig::CrowdSpec parseCrowdSpec(rig::JsonObjectReader& r) {
  rig::CrowdSpec s;
  s.pairs = r.integer("pairs", s.pairs);
  s.seed = seedOf(r, "seed", 1);
  rig::JsonObjectReader lead = r.object("lead");
  s.lead_points = points(lead, "points");
  s.lead_speed = speedKeys(lead, "speed", "seconds");
  lead.finish();
  if (r.has("formation")) {
    rig::JsonObjectReader f = r.object("formation");
    s.formation.files = f.integer("files", s.formation.files);
    s.formation.file_spacing_cm = f.number("file_spacing_cm", s.formation.file_spacing_cm);
    s.formation.rank_spacing_cm = f.number("rank_spacing_cm", s.formation.rank_spacing_cm);
    s.formation.jitter_cm = f.number("jitter_cm", s.formation.jitter_cm);
    f.finish();
  }
  s.speed_variation = r.number("speed_variation", s.speed_variation);
  s.start_offset_max_s = r.number("start_offset_max_s", s.start_offset_max_s);
  s.gait_variation = r.number("gait_variation", s.gait_variation);
  if (const nlohmann::json* p = r.value("profiles")) {
    if (!p->is_object() || p->empty())
      r.fail("profiles", "expected {\"thesis\": weight, ...}, got " + rig::describeJson(*p));
    s.profile_mix.clear();
    for (const auto& [name, w] : p->items()) {
      if (!w.is_number()) r.fail("profiles." + name, "expected a weight (a number >= 0), got " + rig::describeJson(w));
      s.profile_mix.emplace_back(name, w.get<double>());
    }
  }
  s.withers_height_cm = range(r, "withers_height_cm", s.withers_height_cm);
  s.rider_height_cm = range(r, "rider_height_cm", s.rider_height_cm);
  s.rider_build = range(r, "rider_build", s.rider_build);
  s.characters = crowdCharacters(r);
  r.finish();
  return s;
}

rig::PairSpec parsePairSpec(rig::JsonObjectReader& r) {
  rig::PairSpec p;
  p.path.points = points(r, "points");
  const std::string over = r.string("speed_over", "time");
  if (over != "time" && over != "distance") r.fail("speed_over", "expected \"time\" or \"distance\", got \"" + over + "\"");
  p.path.over = over == "time" ? rig::SpeedProfile::Over::Time : rig::SpeedProfile::Over::Distance;
  p.path.speed = speedKeys(r, "speed", over == "time" ? "seconds" : "cm");
  p.path.variation = r.number("variation", p.path.variation);
  if (!(p.path.variation >= 0.0 && p.path.variation <= 1.0)) r.fail("variation", "expected a fraction from 0 to 1");
  p.path.seed = seedOf(r, "seed", p.path.seed);
  p.clip_offset_s = r.number("start_offset_s", p.clip_offset_s);
  p.profile = r.string("profile", p.profile);
  p.withers_height_cm = r.number("withers_height_cm", p.withers_height_cm);
  p.rider_height_cm = r.number("rider_height_cm", p.rider_height_cm);
  p.rider_build = r.number("rider_build", p.rider_build);
  p.coat = r.string("coat", p.coat);
  p.jacket = r.string("jacket", p.jacket);
  p.hair = r.string("hair", p.hair);
  p.skin = r.string("skin", p.skin);
  readOwnCharacters(r, p);
  // An own animation starts where the path does, facing along it (the path's first segment).
  if (p.path.points.size() >= 2) {
    const glm::dvec2 d = p.path.points[1] - p.path.points[0];
    p.slot_cm = p.path.points[0];
    p.slot_heading_deg = std::atan2(d.y, d.x) * 180.0 / 3.14159265358979323846;
  }
  r.finish();
  return p;
}

}  // namespace stirrup::scene
