#include "render/scene.h"

#include "rig/error.h"
#include "rig/frame_range.h"
#include "rig/json_fields.h"

namespace stirrup::render {
namespace {

// The scene's clip: {"generator": NAME, parameters...} or {"file": CLIP.glb, "mapping": MAP.json,
// "animation": NAME}; paths are relative to the scene file. Steady gaits also fill `gait`.
rig::ClipSpec parseClip(JsonObjectReader r, const std::filesystem::path& scene_dir, rig::GaitParams& gait) {
  rig::ClipSpec spec = rig::parseClipSpec(r, scene_dir);
  if (auto g = rig::steadyGaitParams(spec)) gait = *g;
  return spec;
}

CameraSpec parseCamera(JsonObjectReader r, int index) {
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
  c.fov_deg = r.number("fov", c.fov_deg);
  if (!(c.fov_deg > 0.0 && c.fov_deg < 180.0)) r.fail("fov", "expected degrees between 0 and 180");
  c.ortho_height_cm = r.number("ortho_height", c.ortho_height_cm);
  if (!(c.ortho_height_cm > 0.0)) r.fail("ortho_height", "expected centimetres > 0");
  c.position = r.numbers<3>("position", c.position);
  c.target = r.numbers<3>("target", c.target);
  c.follow = r.boolean("follow", c.follow);
  if (c.position == c.target) r.fail("target", "expected a point different from position");
  r.finish();
  return c;
}

}  // namespace

SceneSpec parseScene(const nlohmann::json& json, const std::string& file) {
  JsonObjectReader r(file, "", json);
  SceneSpec s;
  s.file = file;
  s.name = r.string("name", std::filesystem::path(file).stem().string());
  if (r.has("clip")) s.clip = parseClip(r.object("clip"), std::filesystem::path(file).parent_path(), s.gait);
  if (r.has("characters")) {
    JsonObjectReader c = r.object("characters");
    s.horse = c.string("horse", s.horse);
    s.rider = c.string("rider", s.rider);
    if (s.horse != "default") c.fail("horse", "expected \"default\", got \"" + s.horse + "\"");
    if (s.rider != "default") c.fail("rider", "expected \"default\", got \"" + s.rider + "\"");
    c.finish();
  }
  s.profile = r.string("profile", s.profile);
  if (const nlohmann::json* o = r.value("profile_overrides")) {
    if (!o->is_object()) r.fail("profile_overrides", "expected an object, got " + describeJson(*o));
    s.profile_overrides = *o;
  }
  s.fps = r.number("fps", s.fps);
  if (!(s.fps > 0.0 && s.fps <= 240.0)) r.fail("fps", "expected frames per second between 0 and 240");
  s.frames = r.string("frames", s.frames);
  rig::parseFrameList(s.frames, file + ": frames");
  if (const nlohmann::json* res = r.value("resolution")) {
    if (!res->is_array() || res->size() != 2 || !(*res)[0].is_number_integer() ||
        !(*res)[1].is_number_integer())
      r.fail("resolution", "expected [width, height] in whole pixels, got " + describeJson(*res));
    s.width = (*res)[0].get<int>();
    s.height = (*res)[1].get<int>();
    if (s.width < 8 || s.height < 8 || s.width > 8192 || s.height > 8192)
      r.fail("resolution", "expected a width and height between 8 and 8192");
  }
  if (r.has("quality")) {
    JsonObjectReader q = r.object("quality");
    s.samples = q.integer("samples", s.samples);
    s.light_samples = q.integer("light_samples", s.light_samples);
    s.ao_samples = q.integer("ao_samples", s.ao_samples);
    if (s.samples < 1 || s.samples > 4096) q.fail("samples", "expected a whole number from 1 to 4096");
    if (s.light_samples < 1 || s.light_samples > 256)
      q.fail("light_samples", "expected a whole number from 1 to 256");
    if (s.ao_samples < 0 || s.ao_samples > 256) q.fail("ao_samples", "expected a whole number from 0 to 256");
    q.finish();
  }
  if (r.has("sun")) {
    JsonObjectReader sun = r.object("sun");
    s.sun_direction = sun.numbers<3>("direction", s.sun_direction);
    if (s.sun_direction[1] <= 0.0) sun.fail("direction", "expected a direction toward the sun with y > 0");
    s.sun_angular_radius_deg = sun.number("angular_radius", s.sun_angular_radius_deg);
    if (!(s.sun_angular_radius_deg >= 0.0 && s.sun_angular_radius_deg <= 20.0))
      sun.fail("angular_radius", "expected degrees between 0 and 20");
    sun.finish();
  }
  if (const nlohmann::json* cams = r.value("cameras")) {
    if (!cams->is_array() || cams->empty())
      r.fail("cameras", "expected a non-empty array of cameras, got " + describeJson(*cams));
    s.cameras.clear();
    for (std::size_t i = 0; i < cams->size(); ++i) {
      const std::string path = "cameras[" + std::to_string(i) + "]";
      s.cameras.push_back(parseCamera(JsonObjectReader(file, path, (*cams)[i]), static_cast<int>(i)));
    }
  }
  s.output = r.string("output", "out/" + s.name);
  r.finish();
  return s;
}

SceneSpec loadScene(const std::filesystem::path& file) {
  return parseScene(readJsonFile(file), file.string());
}

const CameraSpec& findCamera(const SceneSpec& scene, const std::string& name) {
  if (name.empty()) return scene.cameras.front();
  for (const CameraSpec& c : scene.cameras)
    if (c.name == name) return c;
  std::string known;
  for (const CameraSpec& c : scene.cameras) known += (known.empty() ? "" : ", ") + c.name;
  throw InputError(scene.file.string() + ": cameras: no camera named \"" + name + "\" (the scene has " +
                   known + ")");
}

double frameTime(const SceneSpec& scene, int frame) { return (frame - 1) / scene.fps; }

}  // namespace stirrup::render

#include "rig/rig_profile.h"

namespace stirrup::render {

rig::RigProfile resolveProfile(const SceneSpec& scene) {
  const std::filesystem::path scene_dir = scene.file.parent_path();
  const bool is_path = std::filesystem::path(scene.profile).extension() == ".json";
  rig::RigProfile p = is_path ? rig::loadRigProfile((scene_dir / scene.profile).string(), scene_dir)
                              : rig::loadRigProfile(scene.profile, scene_dir / "profiles");
  rig::applyProfileOverrides(p, scene.profile_overrides, scene.file.string() + ": profile_overrides");
  return p;
}

}  // namespace stirrup::render
