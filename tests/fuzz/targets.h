// The fuzz targets: one function per reader of user input, each taking raw bytes exactly as a user's
// file or argument would hold them. tests/fuzz/fuzz_NAME.cpp wraps one as a libFuzzer target (clang,
// STIRRUP_FUZZ=ON, docs/fuzzing.md); tests/fuzz/replay_test.cpp replays the checked-in corpora and
// every regression input through the same functions in the normal build.
//
// The oracle: a reader may reject input only with rig::InputError, whose message is one line
// (rig/error.h). Any other exception, a crash, a hang or a sanitizer report is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace stirrup::fuzz {

using Target = int (*)(const std::uint8_t* data, std::size_t size);

int sceneJson(const std::uint8_t* data, std::size_t size);       // scene/scene.* (+ its profile and clip)
int rigProfileJson(const std::uint8_t* data, std::size_t size);  // scene/rig_profile_json.*
int profileSets(const std::uint8_t* data, std::size_t size);     // --set lines: cli/options.h parseSets
int horseCsv(const std::uint8_t* data, std::size_t size);        // rig/io/channel_csv.*
int spineJson(const std::uint8_t* data, std::size_t size);       // rig/io/spine_json.* (+ laying the spine)
int gltfClip(const std::uint8_t* data, std::size_t size);        // rig/io/gltf_clip.* (.glb or .gltf)
int gltfCharacter(const std::uint8_t* data, std::size_t size);   // rig/io/gltf_character.* (.glb or .gltf)
int gltfShot(const std::uint8_t* data, std::size_t size);        // rig/io/gltf_shot.*, rig/io/keyed_horse_clip.*
int mappingJson(const std::uint8_t* data, std::size_t size);     // rig/mapping/character_mapping.*, clip mappings
int frameSpec(const std::uint8_t* data, std::size_t size);       // scene/frame_range.*
int farmManifest(const std::uint8_t* data, std::size_t size);    // render/farm/farm_plan.* (OUT/farm.json)

// How far sceneJson took a scene: refused by the reader, read, its profile resolved, its clip made, or
// its first frames baked. The replay test counts the seeds that reach the clip and the bake, so a seed
// corpus that only exercises the error paths (a scene whose characters are missing) fails.
enum class SceneStage { Refused, Read, Profile, Clip, Baked };
SceneStage sceneJsonStage(const std::uint8_t* data, std::size_t size);

struct NamedTarget {
  std::string_view name;  // the corpus folder: tests/fuzz/corpus/NAME, tests/fuzz/regressions/NAME
  Target run;
};
inline constexpr NamedTarget kTargets[] = {
    {"scene_json", sceneJson},     {"rig_profile_json", rigProfileJson}, {"profile_sets", profileSets},
    {"horse_csv", horseCsv},       {"spine_json", spineJson},            {"gltf_clip", gltfClip},
    {"gltf_character", gltfCharacter}, {"gltf_shot", gltfShot},          {"mapping_json", mappingJson},
    {"frame_spec", frameSpec},
    {"farm_manifest", farmManifest},
};

}  // namespace stirrup::fuzz
