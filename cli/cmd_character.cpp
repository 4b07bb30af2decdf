// stirrup character make horse|rider [--param value ...] -o FILE.glb: builds a default character (or
// one with changed proportions) and writes it as a skinned glTF 2.0 binary (docs/characters.md).
// The build makes scenes/characters/*.glb with it (CMakeLists.txt, the characters target).
// stirrup character make humanoid [--pose t|a|relaxed] [--names ...] ... -o FILE.glb: a standing test
// character written the way other tools write theirs (docs/characters.md, "Test characters").
// stirrup character map FILE.glb --as rider|horse [-o MAP.json] [--preview P.png]: maps a user's
// character by itself (rig/mapping/auto_mapping.h), prints what it chose, writes the mapping file, and
// renders the character on the default horse (or the horse under the default rider) through the
// normal pipeline (docs/characters.md, "Mapping by itself").
#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include <unistd.h>

#include "cli/commands.h"
#include "cli/options.h"
#include "render/shot.h"
#include "render/tracer/image.h"
#include "rig/characters/character_params.h"
#include "rig/characters/horse_tack.h"
#include "rig/characters/standing_humanoid.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_humanoid.h"
#include "rig/io/gltf_mapping.h"
#include "rig/mapping/auto_mapping.h"
#include "scene/preset.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"

namespace stirrup::cli {
namespace {

struct MapOptions {
  std::string file;
  std::string as;
  std::string output;
  std::string preview;
  int frame = 1;
  int threads = 0;
  bool ignore_names = false;
};

// The preview: one frame of the default scene (the trot) seen from the three-quarter view, at the
// review preset's samples, with the character and its mapping file in the scene as a user would put
// them, so it shows what a render shows.
void renderPreview(const MapOptions& o, const std::string& mapping_file, rig::CharacterKind kind) {
  namespace fs = std::filesystem;
  if (fs::path(o.preview).extension() != ".png") throw rig::InputError("--preview: " + o.preview + ": expected a file name ending in .png");
  scene::SceneSpec scene;
  scene.name = "map_preview";
  scene.frames = std::to_string(o.frame);
  (kind == rig::CharacterKind::Rider ? scene.rider : scene.horse) = fs::absolute(o.file).string();
  (kind == rig::CharacterKind::Rider ? scene.rider_mapping : scene.horse_mapping) = mapping_file;
  scene::applyPreset(scene, scene::findPreset("review"));
  scene::CameraSpec camera;
  camera.name = "persp";
  camera.view = "persp";
  scene.cameras = {camera};
  const rig::RigProfile profile = scene::resolveProfile(scene);
  try {
    render::Shot shot(scene, profile, camera, o.threads);
    const render::Image image = shot.renderFrame(o.frame);
    if (!fs::path(o.preview).parent_path().empty()) fs::create_directories(fs::path(o.preview).parent_path());
    render::writePng(image, o.preview);
  } catch (const rig::InputError& e) {
    throw rig::InputError("--preview: not rendered: " + std::string(e.what()));
  }
  std::printf("preview: %s (frame %d of the trot, %s the default %s, three-quarter view)\n", o.preview.c_str(), o.frame,
              kind == rig::CharacterKind::Rider ? "the rider on" : "the horse under", kind == rig::CharacterKind::Rider ? "horse" : "rider");
}

// What the rig does about a mapped horse's tack (rig/characters/horse_tack.h), one line: loading the horse
// through the mapping adds it.
std::string tackText(const std::string& file, const rig::AutoMapping& mapped) {
  rig::HorseTackReport tack;
  try {
    rig::loadCharacterGltf(file, rig::CharacterKind::Horse, &mapped.mapping, nullptr, &tack);
  } catch (const rig::InputError& e) {
    return "  tack     not placed: " + std::string(e.what()) + "\n";
  }
  if (!tack.added) return "  tack     the horse's own, mapped (saddle, stirrups and reins)\n";
  char seat[96];
  std::snprintf(seat, sizeof seat, "the seat at (%.1f, %.1f, %.1f) cm", tack.seat.x, tack.seat.y, tack.seat.z + 0.0f);
  if (tack.own_saddle)
    return std::string("  tack     the horse's own saddle (a mesh or material named saddle): the rider sits on it, ") + seat +
           "; the rig adds stirrups, bridle and reins, not a second saddle\n";
  return std::string("  tack     none in the file: the rig adds a saddle, stirrups, bridle and reins, ") + seat + "\n";
}

void runMap(const MapOptions& o) {
  namespace fs = std::filesystem;
  if (o.as != "rider" && o.as != "horse") throw rig::InputError("character map: --as: expected rider or horse, got \"" + o.as + "\"");
  const rig::CharacterKind kind = o.as == "rider" ? rig::CharacterKind::Rider : rig::CharacterKind::Horse;
  if (!o.output.empty() && fs::path(o.output).extension() != ".json")
    throw rig::InputError("-o: " + o.output + ": expected a mapping file name ending in .json");
  rig::AutoMappingParams params;
  params.use_names = !o.ignore_names;
  const rig::AutoMapping mapped = rig::autoMapCharacterFile(o.file, kind, params);
  std::fputs(rig::autoMappingReportText(mapped).c_str(), stdout);
  if (kind == rig::CharacterKind::Horse && mapped.report.not_mapped.empty()) std::fputs(tackText(o.file, mapped).c_str(), stdout);
  const std::string json = rig::autoMappingFileText(mapped);
  if (!o.output.empty()) {
    rig::writeFileAtomically(o.output, std::vector<unsigned char>(json.begin(), json.end()));
    std::printf("wrote %s\n", o.output.c_str());
  }
  if (o.preview.empty()) return;
  std::fflush(stdout);
  if (!mapped.report.not_mapped.empty()) {
    std::string roles;
    for (const std::string& r : mapped.report.not_mapped) roles += (roles.empty() ? "" : ", ") + r;
    throw rig::InputError("--preview: not rendered: " + o.file + ": the " + o.as + "'s " + roles +
                     (mapped.report.not_mapped.size() == 1 ? " is" : " are") + " not mapped and this version needs " +
                     (mapped.report.not_mapped.size() == 1 ? "it" : "them") + " (name the joints in the mapping file -o writes)");
  }
  if (!o.output.empty()) return renderPreview(o, fs::absolute(o.output).string(), kind);
  // Without -o the preview's scene reads the mapping from a file of its own, removed after.
  const fs::path dir = fs::temp_directory_path() / ("stirrup-map-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "mapping.json";
  rig::writeFileAtomically(file, std::vector<unsigned char>(json.begin(), json.end()));
  try {
    renderPreview(o, file.string(), kind);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(dir, ec);
    throw;
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
}

struct CharacterOptions {
  std::string kind;
  std::string output;
  std::vector<std::string> params;
};

// Applies "--name value" pairs to a params struct; unknown names and bad numbers are one-line errors.
template <class P>
void applyParams(const std::vector<rig::CharacterParam<P>>& table, const std::vector<std::string>& args,
                 const std::string& kind, P& out) {
  const std::string cmd = "character make " + kind;
  for (const auto& [key, value] : namedParameters(cmd, args)) rig::setCharacterParameter(table, key, value, cmd, out);
}

constexpr const char* kHumanoidOptions =
    "  humanoid: --names mixamo|rigify|unreal|vrm|humanik|none (mixamo)  --pose t|a|relaxed (t)\n"
    "    --spine-joints 1..8 (3)  --neck-joints 1..2 (1; rigify 2)  --shared-wrist-hand  --no-toes  --no-clavicles\n"
    "    --no-fingers  --split-limbs|--no-split-limbs (on for rigify)  --end-joints|--no-end-joints (on for mixamo)\n"
    "    --ground-root|--no-ground-root (on for unreal, vrm)  --detached-limbs|--no-detached-limbs (on for rigify)\n"
    "    --joint-axes bone|world (world for vrm)\n"
    "    --height 100..250 cm (170)  --seed S (0: the stated proportions)  --cell 0.5..5 cm (1.4)\n";

// The humanoid's options: --names first (it sets the convention's layout), then the rest over it.
rig::StandingHumanoidParams humanoidParams(const std::vector<std::string>& args) {
  const std::string cmd = "character make humanoid";
  const auto value_of = [&](std::size_t& i, std::string& key) {
    std::string a = args[i];
    if (const auto eq = a.find('='); eq != std::string::npos) {
      key = a.substr(0, eq);
      return a.substr(eq + 1);
    }
    key = a;
    if (i + 1 >= args.size()) throw rig::InputError(cmd + ": " + key + ": expected a value");
    return args[++i];
  };
  const auto whole = [&](const std::string& key, const std::string& text, long long lo, long long hi) {
    long long v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || v < lo || v > hi)
      throw rig::InputError(cmd + ": " + key + ": expected a whole number " + std::to_string(lo) + ".." + std::to_string(hi) +
                       ", got \"" + text + "\"");
    return v;
  };
  const auto number = [&](const std::string& key, const std::string& text, float lo, float hi) {
    float v = 0.0f;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || !(v >= lo && v <= hi)) {
      char range[64];
      std::snprintf(range, sizeof range, "%g..%g", lo, hi);
      throw rig::InputError(cmd + ": " + key + ": expected a number " + range + ", got \"" + text + "\"");
    }
    return v;
  };
  rig::HumanoidNames names = rig::HumanoidNames::Mixamo;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] != "--names" && args[i].rfind("--names=", 0) != 0) continue;
    std::string key;
    const std::string v = value_of(i, key);
    if (!rig::parseHumanoidNames(v, names))
      throw rig::InputError(cmd + ": --names: expected mixamo, rigify, unreal, vrm, humanik or none, got \"" + v + "\"");
  }
  rig::StandingHumanoidParams p = rig::humanoidConventionDefaults(names);
  const std::map<std::string, bool rig::StandingHumanoidParams::*> switches = {
      {"--toes", &rig::StandingHumanoidParams::toes},
      {"--clavicles", &rig::StandingHumanoidParams::clavicles},
      {"--fingers", &rig::StandingHumanoidParams::fingers},
      {"--split-limbs", &rig::StandingHumanoidParams::split_limbs},
      {"--end-joints", &rig::StandingHumanoidParams::end_joints},
      {"--ground-root", &rig::StandingHumanoidParams::ground_root},
      {"--detached-limbs", &rig::StandingHumanoidParams::detached_limbs}};
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--shared-wrist-hand") {
      p.separate_hand = false;
      continue;
    }
    if (const auto sw = switches.find(a); sw != switches.end()) {
      p.*(sw->second) = true;
      continue;
    }
    if (a.rfind("--no-", 0) == 0)
      if (const auto sw = switches.find("--" + a.substr(5)); sw != switches.end()) {
        p.*(sw->second) = false;
        continue;
      }
    std::string key;
    if (a.rfind("--", 0) != 0) throw rig::InputError(cmd + ": expected an option, got \"" + a + "\"");
    const std::string name = a.substr(0, a.find('='));
    if (name != "--names" && name != "--pose" && name != "--spine-joints" && name != "--neck-joints" && name != "--joint-axes" &&
        name != "--height" && name != "--seed" && name != "--cell")
      throw rig::InputError(cmd + ": " + name + ": unknown option (expected one of --names --pose --spine-joints --neck-joints "
                       "--shared-wrist-hand --no-toes --no-clavicles --no-fingers --split-limbs --end-joints --ground-root --detached-limbs "
                       "--joint-axes --height --seed --cell)");
    const std::string v = value_of(i, key);
    if (key == "--pose") {
      if (v == "t") p.pose = rig::HumanoidRestPose::T;
      else if (v == "a") p.pose = rig::HumanoidRestPose::A;
      else if (v == "relaxed") p.pose = rig::HumanoidRestPose::Relaxed;
      else throw rig::InputError(cmd + ": --pose: expected t, a or relaxed, got \"" + v + "\"");
    } else if (key == "--spine-joints") {
      p.spine_joints = static_cast<int>(whole(key, v, 1, 8));
    } else if (key == "--neck-joints") {
      p.neck_joints = static_cast<int>(whole(key, v, 1, 2));
    } else if (key == "--joint-axes") {
      if (v == "bone") p.joint_axes = rig::HumanoidJointAxes::Bone;
      else if (v == "world") p.joint_axes = rig::HumanoidJointAxes::World;
      else throw rig::InputError(cmd + ": --joint-axes: expected bone or world, got \"" + v + "\"");
    } else if (key == "--height") {
      p.height = number(key, v, 100.0f, 250.0f);
    } else if (key == "--seed") {
      p.seed = static_cast<std::uint32_t>(whole(key, v, 0, 4294967295LL));
    } else if (key == "--cell") {
      p.cell = number(key, v, 0.5f, 5.0f);
    }
  }
  return p;
}

void runMakeHumanoid(const CharacterOptions& o) {
  const rig::StandingHumanoid h = rig::buildStandingHumanoid(humanoidParams(o.params));
  const std::vector<unsigned char> bytes = rig::humanoidGlb(h);
  rig::writeFileAtomically(o.output, bytes);
  static const char* const kPose[] = {"T", "A", "relaxed"};
  std::printf("wrote %s: standing humanoid, %s names, %s pose, %zu joints, %zu vertices, %zu triangles, %zu bytes\n",
              o.output.c_str(), std::string(rig::humanoidNamesName(h.params.names)).c_str(),
              kPose[static_cast<int>(h.params.pose)], h.character.skeleton.size(), h.character.mesh.vertexCount(),
              h.character.mesh.triangleCount(), bytes.size());
}

void runMake(const CharacterOptions& o) {
  if (o.kind == "humanoid") return runMakeHumanoid(o);
  rig::Character c;
  if (o.kind == "horse") {
    rig::HorseParams p;
    applyParams(rig::horseParameters(), o.params, o.kind, p);
    if (!(p.cell >= 0.5f)) throw rig::InputError("character make horse: --cell: expected at least 0.5 cm");
    c = rig::buildHorse(p);
  } else if (o.kind == "rider") {
    rig::RiderParams p;
    applyParams(rig::riderParameters(), o.params, o.kind, p);
    if (!(p.cell >= 0.5f)) throw rig::InputError("character make rider: --cell: expected at least 0.5 cm");
    c = rig::buildRider(p, rig::HorseParams{}.mount);
  } else {
    throw rig::InputError("character make: expected horse, rider or humanoid, got \"" + o.kind + "\"");
  }
  const std::vector<unsigned char> bytes = rig::characterGlb(c);
  rig::writeFileAtomically(o.output, bytes);
  std::printf("wrote %s: %s, %zu joints, %zu vertices, %zu triangles, %zu bytes\n", o.output.c_str(), c.name.c_str(),
              c.skeleton.size(), c.mesh.vertexCount(), c.mesh.triangleCount(), bytes.size());
}

}  // namespace

void addCharacterCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "character", "Make the default horse and rider or a standing test humanoid as skinned glTF 2.0; map a user's character");
  cmd->require_subcommand(1);
  auto make = std::make_shared<CharacterOptions>();
  CLI::App* mk = cmd->add_subcommand("make", "Build a character from its parameters and write it as .glb");
  mk->footer("Parameters (centimetres; colours linear RGB; vectors x,y,z in the bind pose):\n  horse:" +
             rig::characterParameterList(rig::horseParameters()) + "\n  rider:" + rig::characterParameterList(rig::riderParameters()) +
             "\nThe stirrup and rein places are the horse's mount (rig/characters/horse_character.h), shared by both.\n" +
             std::string(kHumanoidOptions) +
             "Examples: stirrup character make horse -o scenes/characters/horse.glb\n"
             "          stirrup character make humanoid --names rigify --pose a --spine-joints 6 -o rigify-a.glb");
  mk->add_option("kind", make->kind, "horse, rider or humanoid (a standing test character in another tool's style)")->required();
  mk->add_option("-o,--output", make->output, "Output file (.glb)")->required();
  mk->allow_extras();
  mk->callback([make, mk] {
    make->params = mk->remaining();
    runMake(*make);
  });

  auto map = std::make_shared<MapOptions>();
  CLI::App* mp = cmd->add_subcommand("map", "Map a skinned glTF character's joints to the rig's roles by itself");
  mp->footer(
      "Recognises Mixamo, HumanIK, Unreal mannequin, Rigify and VRM joint names (and stirrup's own role names),\n"
      "else maps by the skeleton's shape: mirror-image limb pairs, legs reaching the ground, the spine up to the head.\n"
      "Prints the role chosen for each joint and why, the axes and scale found and the roles it could not map;\n"
      "-o writes them as a mapping file a scene can name (edit it to change a choice). docs/characters.md, \"Mapping by itself\".\n"
      "Example: stirrup character map my-rider.glb --as rider -o my-rider.json --preview my-rider.png");
  mp->add_option("file", map->file, "The character (.glb or .gltf)")->required();
  mp->add_option("--as", map->as, "rider or horse")->required();
  mp->add_option("-o,--output", map->output, "Write the mapping file (.json)");
  mp->add_option("--preview", map->preview,
                 "Render one frame (.png): the rider seated on the default horse, or the horse under the default rider, at the trot");
  mp->add_option("--frame", map->frame, "The trot's frame the preview shows (default 1)")->check(CLI::Range(1, 48));
  mp->add_flag("--ignore-names", map->ignore_names, "Map by the skeleton's shape alone, whatever the joints are called");
  mp->add_option("--threads,-t", map->threads, "Preview render threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  mp->callback([map] { runMap(*map); });
}

}  // namespace stirrup::cli
