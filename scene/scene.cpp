#include "scene/scene.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <system_error>

#include "scene/data_dir.h"
#include "scene/preset.h"
#include "scene/reference_spec.h"

#include "rig/error.h"
#include "rig/io/gltf_character.h"
#include "rig/io/json_fields.h"
#include "rig/parallel_first_error.h"
#include "scene/character_json.h"
#include "scene/crowd_characters.h"
#include "scene/crowd_json.h"
#include "scene/frame_range.h"
#include "scene/rig_profile_json.h"
#include "scene/terrain_json.h"

namespace stirrup::scene {
namespace {

// The ranges a scene's numbers must lie in (our choices: wide enough for any shot, narrow enough that
// no product or quotient of them overflows or underflows to NaN downstream). A frame rate from 1 fps (a
// slide show) to 240 (high-speed review); cameras within 100 km of the origin, the ground's own reach
// many times over; a field of view from 0.5 degrees (a 2750 mm lens) to 170.
constexpr double kMinFps = 1.0, kMaxFps = 240.0;
constexpr double kMaxSceneExtentCm = 1e7;
constexpr double kMinFovDeg = 0.5, kMaxFovDeg = 170.0;
// Frame numbers and counts: a million frames is 11.5 hours at 24 fps.
constexpr int kMaxFrame = 1000000;

// The scene's clip: {"generator": NAME, parameters...} or {"file": CLIP.glb, "mapping": MAP.json,
// "animation": NAME}; paths are relative to the scene file. Steady gaits also fill `gait`.
scene::ClipSpec parseClip(rig::JsonObjectReader r, const std::filesystem::path& scene_dir, rig::GaitParams& gait) {
  scene::ClipSpec spec = scene::parseClipSpec(r, scene_dir);
  if (auto g = scene::steadyGaitParams(spec)) gait = *g;
  return spec;
}

const QualityPreset& findQualityPreset(const std::string& name, const std::string& context) {
  for (const QualityPreset& p : qualityPresets())
    if (p.name == name) return p;
  throw rig::InputError(context + ": expected \"draft\", \"review\" or \"final\", got \"" + name + "\"");
}

CameraSpec parseCamera(rig::JsonObjectReader r, int index) {
  CameraSpec c;
  c.name = r.string("name", index == 0 ? "side" : "camera" + std::to_string(index));
  const std::string type = r.string("type", "orthographic");
  if (type == "orthographic") {
    c.orthographic = true;
  } else if (type == "perspective") {
    c.orthographic = false;
  } else {
    r.fail("type", "expected \"orthographic\" or \"perspective\", got \"" + type + "\"");
  }
  c.fov_deg = r.number("fov", c.fov_deg, kMinFovDeg, kMaxFovDeg, "degrees");
  c.ortho_height_cm = r.number("ortho_height", c.ortho_height_cm, 1.0, kMaxSceneExtentCm, "centimetres");
  c.position = r.numbers<3>("position", c.position, -kMaxSceneExtentCm, kMaxSceneExtentCm);
  c.target = r.numbers<3>("target", c.target, -kMaxSceneExtentCm, kMaxSceneExtentCm);
  c.follow = r.boolean("follow", c.follow);
  c.motion = c.follow ? "follow" : "fixed";
  c.motion = r.string("motion", c.motion);
  if (c.motion != "fixed" && c.motion != "follow" && c.motion != "orbit")
    r.fail("motion", "expected \"fixed\", \"follow\" or \"orbit\", got \"" + c.motion + "\"");
  c.follow = c.motion == "follow";
  c.follow_target = r.string("follow_target", c.follow_target);
  if (c.follow_target != "travel" && c.follow_target != "rider")
    r.fail("follow_target", "expected \"travel\" or \"rider\", got \"" + c.follow_target + "\"");
  c.damping_s = r.number("damping", c.damping_s, 0.0, 10.0, "seconds");
  c.orbit_deg_per_frame = r.number("orbit_deg_per_frame", c.orbit_deg_per_frame, -360.0, 360.0, "degrees");
  c.orbit_frames = r.integer("orbit_frames", c.orbit_frames, 0, kMaxFrame, "a frame count");
  c.focal_length_mm = r.number("focal_length", c.focal_length_mm, 1.0, 10000.0, "millimetres");
  if (r.has("focal_length")) {
    c.fov_deg = 2.0 * std::atan(12.0 / c.focal_length_mm) * 180.0 / 3.14159265358979323846;
  }
  c.view = r.string("view", c.view);
  if (!c.view.empty() && c.view != "side" && c.view != "persp" && c.view != "close" && c.view != "turntable" &&
      c.view != "top")
    r.fail("view", "expected \"side\", \"persp\", \"close\", \"turntable\" or \"top\", got \"" + c.view + "\"");
  c.frame_margin = r.number("frame_margin", c.frame_margin, 0.0, 0.44, "a fraction");
  c.treadmill = r.boolean("treadmill", c.treadmill);
  // Its upper bound is the crowd's size, checked once the pairs are read (parseScene).
  c.follow_pair = r.integer("follow_pair", c.follow_pair, 0, rig::kMaxCrowdPairs - 1, "a pair index");
  c.hold_frame = r.integer("hold_frame", c.hold_frame, 0, kMaxFrame, "a frame number (0: no hold)");
  // A camera on its target (or 1e-320 cm from it) looks nowhere: at least a centimetre between them.
  if (std::hypot(c.target[0] - c.position[0], c.target[1] - c.position[1], c.target[2] - c.position[2]) < 1.0)
    r.fail("target", "expected a point at least 1 cm from position");
  r.finish();
  return c;
}

// The suffix of every error refusing a scene beyond a horse's limits.
constexpr const char* kRendersAnyway = "allow_impossible or --allow-impossible renders it anyway";

// Every path of the scene against the limits a horse has, and the generated clip's gaits against their
// top speeds: the first breach is an error naming the path's source, field, segment and time, or the
// clip's field, the speed and its gait's limit, unless the scene allows the impossible.
void checkLimits(SceneSpec& s) {
  const std::string file = s.file.string();
  if (const auto params = scene::pathClipParams(s.clip))
    s.limits.push_back({std::make_shared<const rig::PathLimitCheck>(*params, s.terrain.get(), file, "clip"), 0.0, 0});
  // Each pair's path read in parallel (each check walks its whole path); kept in pair order.
  std::vector<SceneSpec::PathLimits> pairs(s.pairs.size());
  rig::parallelForFirstError(s.pairs.size(), [&](std::size_t i) {
    if (s.pairs[i].animation) return;  // it plays its horse's own animation, not its path
    const std::string field = (s.crowd ? "crowd.pairs[" : "riders[") + std::to_string(i) + "]";
    pairs[i] = {std::make_shared<const rig::PathLimitCheck>(s.pairs[i].path, s.terrain.get(), file, field),
                s.pairs[i].clip_offset_s, int(i)};
  });
  for (const SceneSpec::PathLimits& l : pairs)
    if (l.check) s.limits.push_back(l);
  // A crowd's pairs ride paths; the default trot in s.clip is no one's.
  if (s.pairs.empty())
    for (const rig::GaitSpeed& g : scene::generatedGaitSpeeds(s.clip))
      if (const auto b = rig::gaitSpeedBreach(g)) s.gait_breaches.push_back(*b);
  if (s.allow_impossible) return;
  for (const SceneSpec::PathLimits& l : s.limits)
    if (const std::string e = l.check->error(); !e.empty()) throw rig::InputError(e + " (" + kRendersAnyway + ")");
  if (!s.gait_breaches.empty()) {
    const rig::GaitSpeedBreach& b = s.gait_breaches.front();
    throw rig::InputError(s.clip.source + "." + b.speed.field + ": " + b.text(std::string("; ") + kRendersAnyway));
  }
}

}  // namespace

std::string impossibleFrameWarning(const SceneSpec& scene, int frame) {
  if (!scene.allow_impossible) return "";
  const double t = frameTime(scene, frame), half = 0.5 / scene.fps;
  std::string what;
  for (const SceneSpec::PathLimits& l : scene.limits) {
    const double at = t + l.clip_offset_s;
    for (const rig::LimitBreach& b : l.check->during(at - half, at + half)) {
      const std::string who = scene.limits.size() > 1 ? l.check->clipField() + " " : "";
      what += std::string(what.empty() ? "" : "; ") + who + rig::horseLimitName(b.limit) + ": " +
              b.text.substr(b.text.find(": ") + 2);
    }
  }
  // A gait too fast is the clip's whole (or its approach): every frame is warned of it.
  for (const rig::GaitSpeedBreach& b : scene.gait_breaches)
    what += std::string(what.empty() ? "" : "; ") + "gait speed: clip." + b.speed.field + ": " + b.text();
  if (what.empty()) return "";
  char when[64];
  std::snprintf(when, sizeof when, "frame %d (%.3f s)", frame, t);
  return scene.file.string() + ": " + when + ": beyond a horse's limits (allowed): " + what;
}

void warnImpossibleFrame(const SceneSpec& scene, int frame) {
  if (const std::string w = impossibleFrameWarning(scene, frame); !w.empty()) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

std::unique_ptr<rig::Clip> makeSceneClip(const SceneSpec& scene) {
  // A crowd's pairs ride their own clips; the default trot in scene.clip is no one's.
  if (!scene.pairs.empty())
    throw rig::InputError(scene.file.string() + ": " + (scene.crowd ? "crowd" : "riders") +
                     ": expected a scene of one horse and rider here (each pair of a crowd rides its own clip)");
  // A path turns its hooves about the horse's rest places, and a horse's own file plays on it as keyed:
  // both need the horse.
  if (scene.horse == "default" || (scene.clip.generator != "path" && scene.clip.file.empty())) return scene::makeClip(scene.clip);
  return scene::makeClip(scene.clip, rig::resolveCharacter(rig::CharacterKind::Horse, scene.horse, scene.horse_mapping));
}

namespace {

// The scene's "characters": "default", a glTF file (relative to the scene file) carrying its role table,
// or {"file": ..., "mapping": ...} for a user's character (docs/characters.md, scene/character_json.h).
void parseCharacters(rig::JsonObjectReader& r, const std::string& file, SceneSpec& s) {
  if (!r.has("characters")) return;
  rig::JsonObjectReader c = r.object("characters");
  const std::filesystem::path dir = std::filesystem::path(file).parent_path();
  const CharacterEntry horse = parseCharacterEntry(c, "horse", dir, {s.horse, s.horse_mapping});
  const CharacterEntry rider = parseCharacterEntry(c, "rider", dir, {s.rider, s.rider_mapping});
  s.horse = horse.file, s.horse_mapping = horse.mapping;
  s.rider = rider.file, s.rider_mapping = rider.mapping;
  c.finish();
}

// The look: "quality" (a preset's name, or {"preset": "draft", "samples": 8} where explicit fields override
// the preset), "sun" and "haze".
void parseLook(rig::JsonObjectReader& r, const std::string& file, SceneSpec& s) {
  if (const nlohmann::json* qv = r.value("quality"); qv && qv->is_string()) {
    applyPreset(s, findQualityPreset(qv->get<std::string>(), file + ": quality"));
  } else if (r.has("quality")) {
    rig::JsonObjectReader q = r.object("quality");
    if (q.has("preset")) applyPreset(s, findQualityPreset(q.string("preset", ""), file + ": quality.preset"));
    s.samples = q.integer("samples", s.samples, 1, 4096);
    s.light_samples = q.integer("light_samples", s.light_samples, 1, 256);
    s.ao_samples = q.integer("ao_samples", s.ao_samples, 0, 256);
    q.finish();
  }
  if (r.has("sun")) {
    rig::JsonObjectReader sun = r.object("sun");
    s.sun_direction = sun.numbers<3>("direction", s.sun_direction, -1000.0, 1000.0);
    // Above the horizon by a tenth of a degree at least: a sun at it (or a y of 1e-320) lights nothing.
    const double length = std::hypot(s.sun_direction[0], s.sun_direction[1], s.sun_direction[2]);
    if (!(s.sun_direction[1] >= std::sin(0.1 * 3.14159265358979323846 / 180.0) * length))
      sun.fail("direction", "expected a direction toward the sun at least 0.1 degrees above the horizon (y > 0)");
    s.sun_angular_radius_deg = sun.number("angular_radius", s.sun_angular_radius_deg, 0.0, 20.0, "degrees");
    sun.finish();
  }
  if (r.has("haze")) {
    // At most the ground's 1 km extent: farther, its edge would show before the haze hides it.
    rig::JsonObjectReader haze = r.object("haze");
    s.haze_visibility_cm = haze.number("visibility_cm", s.haze_visibility_cm);
    if (!(s.haze_visibility_cm >= 100.0 && s.haze_visibility_cm <= 100000.0))
      haze.fail("visibility_cm", "expected centimetres from 100 to 100000 (the ground ends 1 km out), got " + rig::numberText(s.haze_visibility_cm));
    s.haze_ortho_depth_cm = haze.number("ortho_depth_cm", s.haze_ortho_depth_cm, 100.0, 100000.0, "centimetres");
    haze.finish();
  }
}

// A crowd or a list of riders: each pair rides its own path, so the scene's one clip has no place beside it.
void parsePairs(rig::JsonObjectReader& r, const std::string& file, SceneSpec& s) {
  if (r.has("crowd") || r.has("riders")) {
    const char* key = r.has("crowd") ? "crowd" : "riders";
    if (r.has("crowd") && r.has("riders")) r.fail("riders", "expected either \"crowd\" or \"riders\", not both");
    if (r.has("clip")) r.fail("clip", std::string("expected no clip beside \"") + key + "\" (each pair rides its own path)");
  }
  if (r.has("crowd")) {
    rig::JsonObjectReader c = r.object("crowd");
    s.crowd = scene::parseCrowdSpec(c);
    s.pairs = rig::generateCrowd(*s.crowd, s.terrain, s.fps, file, &s.pair_clips,
                                 [&s](std::vector<rig::PairSpec>& pairs) { resolvePairCharacters(pairs, s, "crowd.characters"); });
  } else if (const nlohmann::json* riders = r.value("riders")) {
    if (!riders->is_array() || riders->empty())
      r.fail("riders", "expected a non-empty array of riders, got " + rig::describeJson(*riders));
    for (std::size_t i = 0; i < riders->size(); ++i) {
      rig::JsonObjectReader p(file, "riders[" + std::to_string(i) + "]", (*riders)[i]);
      s.pairs.push_back(scene::parsePairSpec(p));
    }
    resolvePairCharacters(s.pairs, s, "riders");
    s.pair_clips = rig::validatePairs(s.pairs, s.terrain, s.fps, 0, file, "riders");
  }
}

// Cameras that follow a pair name one the scene has.
void checkCameraPairs(const std::string& file, const SceneSpec& s) {
  for (std::size_t i = 0; i < s.cameras.size(); ++i) {
    const CameraSpec& c = s.cameras[i];
    const std::string at = file + ": cameras[" + std::to_string(i) + "].";
    if (c.follow_pair >= 0 && s.pairs.empty())
      throw rig::InputError(at + "follow_pair: expected no follow_pair in a scene without a \"crowd\" or \"riders\"");
    if (c.follow_pair >= int(s.pairs.size()))
      throw rig::InputError(at + "follow_pair: expected a pair index from 0 to " + std::to_string(s.pairs.size() - 1) +
                       " (the crowd has " + std::to_string(s.pairs.size()) + " pairs), got " + std::to_string(c.follow_pair));
    // On a treadmill every pair would ride in place, through the others.
    if (c.treadmill && !s.pairs.empty()) throw rig::InputError(at + "treadmill: expected false in a crowd scene");
  }
}

}  // namespace

SceneSpec parseScene(const nlohmann::json& json, const std::string& file, const SceneLoadOptions& options) {
  rig::JsonObjectReader r(file, "", json);
  SceneSpec s;
  s.file = file;
  s.allow_impossible = r.boolean("allow_impossible", false) || options.allow_impossible;
  s.name = r.string("name", std::filesystem::path(file).stem().string());
  if (r.has("clip")) s.clip = parseClip(r.object("clip"), std::filesystem::path(file).parent_path(), s.gait);
  if (r.has("terrain")) {
    rig::JsonObjectReader t = r.object("terrain");
    s.terrain = scene::parseTerrain(t, std::filesystem::path(file).parent_path());
  }
  s.clip.terrain = s.terrain;
  parseCharacters(r, file, s);
  s.profile = r.string("profile", s.profile);
  if (const nlohmann::json* o = r.value("profile_overrides")) {
    if (!o->is_object()) r.fail("profile_overrides", "expected an object, got " + rig::describeJson(*o));
    s.profile_overrides = *o;
    // Checked now, each against its parameter's range, as they will apply to whichever profile is named.
    rig::RigProfile checked = rig::RigProfile::thesis();
    scene::applyProfileOverrides(checked, s.profile_overrides, file + ": profile_overrides");
  }
  s.fps = r.number("fps", s.fps, kMinFps, kMaxFps, "frames per second");
  // A horse's own animation (or another horse's, read through its roles) plays whole unless the scene
  // says which frames.
  if (!s.clip.file.empty() && !r.has("frames") && !scene::readsControlNodes(s.clip))
    s.frames = "1-" + std::to_string(std::max(1, int(std::lround(scene::fileClipDuration(s.clip) * s.fps)) + 1));
  s.frames = r.string("frames", s.frames);
  scene::parseFrameList(s.frames, file + ": frames");
  if (const nlohmann::json* res = r.value("resolution")) {
    if (!res->is_array() || res->size() != 2 || !(*res)[0].is_number_integer() ||
        !(*res)[1].is_number_integer())
      r.fail("resolution", "expected [width, height] in whole pixels, got " + rig::describeJson(*res));
    s.width = (*res)[0].get<int>();
    s.height = (*res)[1].get<int>();
    if (s.width < 8 || s.height < 8 || s.width > 8192 || s.height > 8192)
      r.fail("resolution", "expected a width and height between 8 and 8192");
  }
  parseLook(r, file, s);
  if (const nlohmann::json* cams = r.value("cameras")) {
    if (!cams->is_array() || cams->empty())
      r.fail("cameras", "expected a non-empty array of cameras, got " + rig::describeJson(*cams));
    s.cameras.clear();
    for (std::size_t i = 0; i < cams->size(); ++i) {
      const std::string path = "cameras[" + std::to_string(i) + "]";
      s.cameras.push_back(parseCamera(rig::JsonObjectReader(file, path, (*cams)[i]), static_cast<int>(i)));
    }
  }
  s.output = r.string("output", "out/" + s.name);
  if (r.has("reference")) s.reference = parseReferenceSpec(r.object("reference"), std::filesystem::path(file).parent_path());
  parsePairs(r, file, s);
  s.pair_clips_terrain = s.terrain;
  if (s.crowd && !r.has("frames")) s.frames = "1-" + std::to_string(rig::crowdFrames(*s.crowd, s.terrain, s.fps, file));
  checkCameraPairs(file, s);
  r.finish();
  checkLimits(s);
  return s;
}

std::filesystem::path findSceneFile(const std::filesystem::path& file) {
  // `stirrup render scenes/trot.json` from any folder: a relative path that is not there is looked up in
  // the data folder (scene/data_dir.h), which holds the default scenes.
  std::error_code ec;
  if (file.is_relative() && !std::filesystem::exists(file, ec))
    if (const std::optional<std::filesystem::path> data = findDataDir(); data && std::filesystem::exists(*data / file, ec))
      return *data / file;
  return file;
}

SceneSpec loadScene(const std::filesystem::path& file, const SceneLoadOptions& options) {
  const std::filesystem::path f = findSceneFile(file);
  return parseScene(rig::readJsonFile(f), f.string(), options);
}

const CameraSpec& findCamera(const SceneSpec& scene, const std::string& name) {
  if (name.empty()) return scene.cameras.front();
  for (const CameraSpec& c : scene.cameras)
    if (c.name == name) return c;
  std::string known;
  for (const CameraSpec& c : scene.cameras) known += (known.empty() ? "" : ", ") + c.name;
  throw rig::InputError(scene.file.string() + ": cameras: no camera named \"" + name + "\" (the scene has " +
                   known + ")");
}

double frameTime(const SceneSpec& scene, int frame) { return (frame - 1) / scene.fps; }

}  // namespace stirrup::scene
