// stirrup clip make GAIT [--param value ...] -o CLIP.glb: writes a generated horse clip as glTF 2.0.
// stirrup clip info CLIP [--json]: measures a clip (a .glb/.gltf file, a generator name, or a scene's
// clip; a path clip section by section) and prints it beside the ranges of docs/gait-reference.md.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/options.h"
#include "rig/error.h"
#include "rig/io/gltf_clip.h"
#include "rig/io/json_fields.h"
#include "rig/io/keyed_horse_clip.h"
#include "rig/motion/clip_report.h"
#include "rig/motion/crowd.h"
#include "rig/motion/path_clip.h"
#include "scene/clip_factory.h"
#include "scene/file_shot.h"
#include "scene/scene.h"
#include "scene/shot_evaluator.h"

namespace stirrup::cli {
namespace {

struct ClipOptions {
  std::string clip;
  std::string output;
  double fps = 30.0;
  bool json = false;
  std::string mapping;
  std::string animation;
  std::string reference;
  int loops = 0;  // 0: 1 for a contract clip, 4 for a skeleton clip (a cycle)
  double ground_cm = -1.0;
  int pair = -1;  // a crowd scene's pair to measure (-1: every pair)
  bool allow_impossible = false;  // a scene beyond a horse's limits is measured anyway
  std::vector<std::string> params;  // the --name value pairs after the gait
};

// "--fence-height-cm 90 --lead left" -> {"fence_height_cm": 90, "lead": "left"}.
nlohmann::json paramsJson(const std::string& command, const std::vector<std::string>& args) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, value] : namedParameters(command, args)) {
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    if (!value.empty() && end && *end == '\0') j[key] = number;
    else if (value == "true" || value == "false") j[key] = value == "true";
    else j[key] = value;
  }
  return j;
}

scene::ClipSpec generatorSpec(const std::string& command, const std::string& gait, const std::vector<std::string>& args) {
  nlohmann::json j = paramsJson(command, args);
  j["generator"] = gait;
  rig::JsonObjectReader r(command, "", j);
  return scene::parseClipSpec(r, std::filesystem::current_path());
}

void runMake(const ClipOptions& o) {
  if (scene::isGltfFile(o.clip)) throw rig::InputError("clip make: expected a generator name, got the file " + o.clip);
  const scene::ClipSpec spec = generatorSpec("clip make", o.clip, o.params);
  const std::unique_ptr<rig::Clip> clip = scene::makeClip(spec);
  rig::GltfWriteOptions w;
  w.fps = o.fps;
  rig::writeClipGltf(*clip, o.output, w);
  std::printf("wrote %s: %s, %.2f s at %g fps\n", o.output.c_str(), clip->name().c_str(), clip->duration(), o.fps);
}

// A path clip measured section by section: each stretch of steady gait (between its blends) against
// that gait's reference, measured on the path's straight form (gait timing does not depend on the
// bends), then the whole clip on the path for slides, which are measured in the world.
// The measures as JSON ({"sections": [...], "path": {...}}) and as text, headed by `who`.
struct PathInfo {
  nlohmann::json json;
  std::string text;
};
PathInfo pathInfo(const std::string& who, const rig::PathClip& clip, const ClipOptions& o) {
  const rig::MovementClip straight(clip.movement());
  nlohmann::json sections = nlohmann::json::array();
  std::string text;
  int index = 0;
  for (const rig::PathClip::Section& sec : clip.sections()) {
    ++index;
    const double from = sec.start_s + 0.5 * sec.blend_in_s, to = sec.end_s - 0.5 * sec.blend_out_s;
    const std::string gait = rig::pathGaitName(sec.gait);
    const bool leads = sec.gait == rig::PathGait::Canter || sec.gait == rig::PathGait::Gallop;
    const std::string lead = leads ? (sec.lead == rig::Lead::Right ? "right" : "left") : "";
    char head[160];
    std::snprintf(head, sizeof head, "section %d: %s%s%s, %.2f-%.2f s (steady %.2f-%.2f s)%s\n", index, gait.c_str(),
                  leads ? ", " : "", leads ? (lead + " lead").c_str() : "", sec.start_s, sec.end_s, from, to,
                  leads && sec.lead == rig::Lead::Left ? ", measured mirrored (the reference is the right lead)" : "");
    nlohmann::json j = {{"gait", gait}, {"start_s", sec.start_s}, {"end_s", sec.end_s}, {"steady_from_s", from},
                        {"steady_to_s", to}};
    if (leads) j["lead"] = lead;
    if (leads && sec.lead == rig::Lead::Left) j["measured_mirrored"] = true;
    const auto ref = rig::gaitReference(gait);
    rig::ClipInfoOptions io;
    io.start_s = from;
    io.end_s = to;
    // The reference gives right-lead footfalls: a left lead is measured mirrored.
    io.mirror = leads && sec.lead == rig::Lead::Left;
    if (o.ground_cm >= 0.0) io.ground_cm = o.ground_cm;
    // Two strides at least, or the stride measures mean nothing.
    const double stride_s = 1.0 / clip.movement().stride_hz.at(0.5 * (from + to));
    text += head;
    if (to - from >= 2.0 * stride_s) {
      const rig::ClipInfo info = rig::measureClip(straight, io);
      j["info"] = rig::clipInfoJson(info, ref ? &*ref : nullptr);
      text += rig::formatClipInfo(info, ref ? &*ref : nullptr);
    } else {
      j["info"] = nullptr;
      text += "  (shorter than two strides: not measured)\n";
    }
    text += "\n";
    sections.push_back(j);
  }
  rig::ClipInfoOptions whole_options;
  if (o.ground_cm >= 0.0) whole_options.ground_cm = o.ground_cm;
  const rig::ClipInfo whole = rig::measureClip(clip, whole_options);
  char head[256];
  std::snprintf(head, sizeof head, "%s: path, %.2f s, %zu sections\n\n", who.c_str(), clip.duration(), clip.sections().size());
  return {{{"sections", sections}, {"path", rig::clipInfoJson(whole, nullptr)}},
          head + text + "whole path, on the ground:\n" + rig::formatClipInfo(whole, nullptr)};
}

void runPathInfo(const std::string& scene_file, const rig::PathClip& clip, const ClipOptions& o) {
  PathInfo info = pathInfo(scene_file, clip, o);
  if (o.json) {
    nlohmann::json out = {{"scene", scene_file}};
    out.update(info.json);
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::printf("%s", info.text.c_str());
}

// A crowd's pairs each ride their own path clip (rig::makePairClip, from the ride's start: a pair's start
// phase only shifts it in the shot): each measured as one path is, every pair or only --pair's.
void runCrowdInfo(const scene::SceneSpec& scene, const ClipOptions& o) {
  const int count = int(scene.pairs.size());
  if (o.pair >= count)
    throw rig::InputError("clip info: --pair: expected a pair index from 0 to " + std::to_string(count - 1) + ", got " + std::to_string(o.pair));
  const std::string source = scene.file.string();
  nlohmann::json pairs = nlohmann::json::array();
  std::string text;
  for (int i = o.pair >= 0 ? o.pair : 0; i < (o.pair >= 0 ? o.pair + 1 : count); ++i) {
    const rig::PairSpec& spec = scene.pairs[std::size_t(i)];
    const std::string name = scene::crowdPairName(i, count);
    if (spec.animation) {
      // A pair playing its horse's own animation rides no path: `clip info` of the horse's file measures it.
      const std::string what = source + " " + name + ": plays its horse's own animation" +
                               (spec.animation->empty() ? "" : " \"" + *spec.animation + "\"") + " from " + spec.horse_file + " (no path)\n";
      pairs.push_back({{"pair", i}, {"name", name}, {"own_animation", *spec.animation}, {"file", spec.horse_file}});
      text += (text.empty() ? "" : "\n") + what;
      continue;
    }
    const auto clip = rig::makePairClip(spec, scene.terrain, source + ": pairs[" + std::to_string(i) + "]");
    PathInfo info = pathInfo(source + " " + name, *clip, o);
    nlohmann::json j = {{"pair", i}, {"name", name}, {"start_offset_s", spec.clip_offset_s}};
    j.update(info.json);
    pairs.push_back(j);
    text += (text.empty() ? "" : "\n") + info.text;
  }
  if (o.json) std::printf("%s\n", nlohmann::json{{"scene", source}, {"pairs", pairs}}.dump(2).c_str());
  else std::printf("%s", text.c_str());
}

void runInfo(const ClipOptions& o) {
  std::unique_ptr<rig::Clip> clip;
  rig::ClipInfoOptions io;
  std::string reference = o.reference;
  if (std::filesystem::path(o.clip).extension() == ".json") {
    // A scene: its clip, over its terrain. A path clip is measured section by section.
    if (!o.params.empty()) throw rig::InputError("clip info: generator parameters do not apply to a scene: " + o.params[0]);
    const scene::SceneSpec scene = scene::loadScene(o.clip, {o.allow_impossible});
    if (!scene.pairs.empty()) return runCrowdInfo(scene, o);
    if (o.pair >= 0) throw rig::InputError("clip info: --pair: expected a crowd scene (\"crowd\" or \"riders\"), got one horse and rider in " + o.clip);
    clip = scene::makeSceneClip(scene);
    if (const auto* path = dynamic_cast<const rig::PathClip*>(clip.get())) return runPathInfo(o.clip, *path, o);
    if (reference.empty()) reference = scene.clip.generator;  // empty for a glTF clip
  } else if (scene::isGltfFile(o.clip)) {
    if (!o.params.empty()) throw rig::InputError("clip info: generator parameters do not apply to a file: " + o.params[0]);
    if (!std::filesystem::exists(o.clip)) throw rig::InputError(o.clip + ": no such file");
    // Read as a scene's clip block reads it: a stirrup clip, a clip mapping, or a horse through its roles.
    nlohmann::json block = {{"file", std::filesystem::absolute(o.clip).string()}};
    if (!o.mapping.empty()) block["mapping"] = std::filesystem::absolute(o.mapping).string();
    if (!o.animation.empty()) block["animation"] = o.animation;
    rig::JsonObjectReader r(o.clip, "", block);
    const scene::ClipSpec spec = scene::parseClipSpec(r, "");
    clip = scene::makeClip(spec);
    // Another tool's animation: its stance hooves are rarely exactly down; a cycle (a skeleton mapping's,
    // or a horse's animated in place) is measured over several loops.
    const auto* keyed = dynamic_cast<const rig::KeyedHorseClip*>(clip.get());
    const bool skeleton = keyed || (!spec.mapping.empty() && !spec.character_mapping &&
                                    rig::loadClipMapping(spec.mapping).mode == rig::ClipMapping::Mode::Skeleton);
    const bool cycle = keyed ? keyed->inPlace() : skeleton;
    io.end_s = clip->duration() * (o.loops > 0 ? o.loops : cycle ? 4 : 1);
    if (skeleton) io.ground_cm = 0.5;
  } else {
    clip = scene::makeClip(generatorSpec("clip info", o.clip, o.params));
    if (reference.empty()) reference = o.clip;
  }
  if (o.ground_cm >= 0.0) io.ground_cm = o.ground_cm;
  const rig::ClipInfo info = rig::measureClip(*clip, io);
  const auto ref = rig::gaitReference(reference);
  if (!reference.empty() && !ref && !o.reference.empty())
    throw rig::InputError("clip info: --reference: expected walk, trot, canter, gallop, stop, jump, rear or buck, got \"" + reference + "\"");
  if (o.json) std::printf("%s\n", rig::clipInfoJson(info, ref ? &*ref : nullptr).dump(2).c_str());
  else std::printf("%s", rig::formatClipInfo(info, ref ? &*ref : nullptr).c_str());
}

}  // namespace

void addClipCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("clip", "Make horse clips as glTF and measure clips against gait-reference");
  cmd->require_subcommand(1);
  std::string generators;
  for (const auto& g : scene::clipGenerators()) generators += (generators.empty() ? "" : ", ") + g;

  auto make = std::make_shared<ClipOptions>();
  CLI::App* mk = cmd->add_subcommand("make", "Write a generated clip as glTF 2.0 (control nodes + one animation)");
  std::string footer = "Generators: " + generators + ".\nParameters per generator:\n";
  for (const auto& g : scene::clipGenerators()) {
    footer += "  " + g + ":";
    for (const auto& p : scene::clipGeneratorParameters(g)) footer += " --" + p;
    footer += "\n";
  }
  footer += "Example: stirrup clip make jump --fence_height_cm 110 --seed 7 -o out/jump.glb";
  mk->footer(footer);
  mk->add_option("gait", make->clip, "Generator: " + generators)->required();
  mk->add_option("-o,--output", make->output, "Output file (.glb binary or .gltf JSON)")->required();
  mk->add_option("--fps", make->fps, "Samples per second of the animation (default 30)");
  mk->allow_extras();
  mk->callback([make, mk] {
    make->params = mk->remaining();
    runMake(*make);
  });

  auto info = std::make_shared<ClipOptions>();
  CLI::App* in = cmd->add_subcommand("info", "Measure a clip: footfalls, duty factors, stride, bounce, slides");
  in->footer(
      "CLIP is a .glb/.gltf file or a generator name (" + generators + ") with its --parameters.\n"
      "A crowd scene's pairs are measured one by one, each its own path (--pair N: only pair N); --json\n"
      "  then gives {\"scene\", \"pairs\": [{\"pair\", \"name\", \"start_offset_s\", \"sections\", \"path\"}]}.\n"
      "Example: stirrup clip info gallop --speed_cm_s 1200\n"
      "         stirrup clip info ../shared/assets/fox/Fox.glb --mapping scenes/fox/fox-mapping.json --animation Run");
  in->add_option("clip", info->clip, "A .glb/.gltf file, a generator name, or a scene (.json: its clip; a path section by section)")->required();
  in->add_flag("--json", info->json, "Print JSON instead of a table");
  in->add_option("--mapping", info->mapping,
                 "Mapping file: a clip mapping (the file's nodes to the contract's controls) or a horse's character mapping (roles)");
  in->add_option("--animation", info->animation, "Animation in the file (default: the first)");
  in->add_option("--reference", info->reference, "Compare with this movement of gait-reference.md (walk, trot, canter, gallop, stop, jump, rear, buck)");
  in->add_option("--loops", info->loops, "Loops of a file's animation to measure (default 1; 4 for a cycle from another tool)");
  in->add_option("--pair", info->pair, "A crowd scene's pair to measure, by index from 0 (default: every pair in turn)");
  in->add_option("--ground-cm", info->ground_cm, "A hoof this low or lower is down (default 0.001; 0.5 for another tool's animation)");
  in->add_flag("--allow-impossible", info->allow_impossible,
               "Measure a scene beyond a horse's limits (docs/horse-limits.md) anyway");
  in->allow_extras();
  in->callback([info, in] {
    info->params = in->remaining();
    runInfo(*info);
  });
}

}  // namespace stirrup::cli
