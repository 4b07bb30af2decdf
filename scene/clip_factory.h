// Which clip to play: a named generator with its parameters ({"generator": "jump",
// "fence_height_cm": 90}) or a glTF file read through a mapping ({"file": "clips/x.glb", "mapping":
// "fox-mapping.json", "animation": "Walk"}). Parsed and checked once, so a typo is a one-line error
// naming the file and the field before anything is rendered; made into a Clip by makeClip().
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

#include "rig/character.h"
#include "rig/clip.h"
#include "rig/io/json_fields.h"
#include "rig/motion/horse_limits.h"
#include "rig/motion/path_clip.h"
#include "rig/motion/procedural_gait.h"
#include "rig/motion/terrain.h"

namespace stirrup::scene {

struct ClipSpec {
  std::string generator = "trot";     // empty when the clip is a file
  nlohmann::json params = nlohmann::json::object();  // the generator's parameters, as given (checked)
  std::filesystem::path file;         // glTF clip (resolved against the scene's folder)
  // A clip mapping ("nodes": rig/io/gltf_clip.h), a character mapping of the file's horse ("roles":
  // rig/mapping/character_mapping.h, as `stirrup character map` writes it), or empty: the file's nodes named
  // as the contract's controls (a stirrup clip), else the file is a horse whose animation is read through
  // its roles (the scene's horse's own mapping when it is the scene's horse, else found by itself).
  std::filesystem::path mapping;
  bool character_mapping = false;     // `mapping` holds roles
  std::optional<bool> control_nodes;  // readsControlNodes, found once by parseClipSpec
  std::string animation;
  std::string source = "clip";        // "FILE: clip" for messages
  // The ground the clip moves over (the scene's "terrain"); null = flat. A path clip plants its hooves
  // on it; the other generators move on flat ground.
  std::shared_ptr<const rig::Terrain> terrain;
  // The horse's rest hoof places (x forward, z right, cm), lf rf lb rb, for a path clip (it turns
  // planted hooves about them); unset = the default horse's (rig/motion/path_clip.h).
  std::optional<std::array<glm::dvec2, 4>> hoof_rest;
};

// The generators makeClip knows, for help texts.
const std::vector<std::string>& clipGenerators();
// The parameters a generator accepts (empty for an unknown generator).
std::vector<std::string> clipGeneratorParameters(const std::string& generator);

// Reads a clip object; unknown generators, unknown parameters and bad values fail through `r` (one
// line naming the file and field). Relative paths resolve against base_dir.
ClipSpec parseClipSpec(rig::JsonObjectReader& r, const std::filesystem::path& base_dir);

// The gait a steady-gait spec plays (walk, trot, canter, gallop), else nullopt.
std::optional<rig::GaitParams> steadyGaitParams(const ClipSpec& spec);
// The speed of every gait a generator rides and the field that sets it (rig/motion/horse_limits.h): a
// steady gait's speed_cm_s, the stop's gallop in (entry_speed_cm_s), the jump's canter up to the fence
// (approach_speed_cm_s), each of a sequence's gaits (gaits[i], at its reference speed). Empty for the
// other generators (a path picks its gait from its speed: only its top speed applies) and for files.
std::vector<rig::GaitSpeed> generatedGaitSpeeds(const ClipSpec& spec);

// Without the horse, a horse's own animation (a file clip whose file is the scene's horse) is read as
// any other horse's: its controls only, for the default horse. makeClip(spec, horse) keys the horse itself.
std::unique_ptr<rig::Clip> makeClip(const ClipSpec& spec);
// A path clip's parameters (the default horse's rest hoof places unless spec.hoof_rest), else nullopt.
std::optional<rig::PathClipParams> pathClipParams(const ClipSpec& spec);
// The clip for this horse: a path clip turns its hooves about the horse's own rest places, and a clip
// whose file is the horse's own plays its animation on it exactly as keyed (rig/io/keyed_horse_clip.h).
std::unique_ptr<rig::Clip> makeClip(const ClipSpec& spec, const rig::Character& horse);
// Whether the spec's file holds the contract's control nodes (a clip stirrup wrote), read as a clip
// mapping's nodes; otherwise a file clip without a clip mapping is a horse read through its roles.
bool readsControlNodes(const ClipSpec& spec);
// A file clip's animation length (seconds; a horse's own animation from its first key): a scene that
// plays one and names no frames plays all of it.
double fileClipDuration(const ClipSpec& spec);

}  // namespace stirrup::scene
