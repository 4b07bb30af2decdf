#include "tests/fuzz/targets.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "cli/options.h"
#include "render/farm/farm_plan.h"
#include "rig/bake.h"
#include "rig/curve_spine.h"
#include "rig/error.h"
#include "rig/io/channel_csv.h"
#include "rig/io/character_mapping_json.h"
#include "rig/io/gltf_character.h"
#include "rig/io/gltf_clip.h"
#include "rig/io/gltf_shot.h"
#include "rig/io/keyed_horse_clip.h"
#include "rig/io/spine_json.h"
#include "rig/mapping/character_mapping.h"
#include "rig/pose.h"
#include "rig/rider_rig.h"
#include "scene/clip_factory.h"
#include "scene/frame_range.h"
#include "scene/profile_resolver.h"
#include "scene/rig_profile_json.h"
#include "scene/scene.h"

namespace stirrup::fuzz {
namespace {

namespace fs = std::filesystem;

// One scratch folder per process (libFuzzer's -jobs run several), laid out so the files a seed names
// are there, as beside the shipped scenes: inputs are written to ROOT/work/scene/, where characters/,
// profiles/ and the *-mapping.json files (scenes/fox/ holds the Fox's) link to the shipped scenes', and ROOT/scenes and
// ROOT/shared link to the source tree's scenes/ and the shared assets, for paths such as
// "../../scenes/profiles/thesis.json" (tests/golden/) and "../../shared/assets/fox/Fox.glb"
// (scenes/). The links are only read through: no target writes a file a scene names.
const fs::path& scratch() {
  static const fs::path dir = [] {
    const fs::path root = fs::temp_directory_path() / ("stirrup_fuzz_" + std::to_string(::getpid()));
    const fs::path d = root / "work" / "scene";
    const fs::path scenes = fs::path(STIRRUP_SOURCE_DIR) / "scenes";
    fs::create_directories(d);
    std::error_code ec;
    fs::create_directory_symlink(scenes, root / "scenes", ec);
    fs::create_directory_symlink(fs::path(STIRRUP_SHARED_DIR), root / "shared", ec);
    for (const auto& e : fs::recursive_directory_iterator(scenes)) {
      const std::string name = e.path().filename().string();
      const bool top = e.path().parent_path() == scenes;
      if (top && (name == "characters" || name == "profiles")) fs::create_directory_symlink(e.path(), d / name, ec);
      else if (name.size() > 13 && name.ends_with("-mapping.json")) fs::create_symlink(e.path(), d / name, ec);
    }
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(fs::temp_directory_path() / ("stirrup_fuzz_" + std::to_string(::getpid())), ec);
    });
    return d;
  }();
  return dir;
}

fs::path writeInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const fs::path file = scratch() / name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

// glTF readers pick the container by extension; the bytes say which one a user would have saved.
std::string gltfName(const std::uint8_t* data, std::size_t size, const char* stem) {
  const bool glb = size >= 4 && std::equal(data, data + 4, "glTF");
  return std::string(stem) + (glb ? ".glb" : ".gltf");
}

// The oracle (targets.h): InputError with a one-line message is a correct rejection.
template <typename F>
int expectOnlyInputErrors(F&& f) {
  try {
    f();
  } catch (const rig::InputError& e) {
    const std::string what = e.what();
    if (what.empty() || what.find('\n') != std::string::npos) {
      std::fprintf(stderr, "InputError message is not one line: \"%s\"\n", what.c_str());
      std::abort();
    }
  }
  return 0;
}

// A clip is sampled where a render samples it: start, middle, end and past the end.
void sampleClip(const rig::Clip& clip) {
  const double d = clip.duration();
  if (!std::isfinite(d) || d < 0) {
    std::fprintf(stderr, "clip duration %g\n", d);
    std::abort();
  }
  for (const double t : {0.0, d * 0.5, d, d + 1.0}) (void)clip.sample(t);
  (void)clip.obstacles();
}

}  // namespace

SceneStage sceneJsonStage(const std::uint8_t* data, std::size_t size) {
  SceneStage stage = SceneStage::Refused;
  expectOnlyInputErrors([&] {
    const scene::SceneSpec scene = scene::loadScene(writeInput(data, size, "scene.json"));
    stage = SceneStage::Read;
    // What every command does next: the profile with its overrides, the clip, the first frames baked.
    const rig::RigProfile profile = scene::resolveProfile(scene);
    stage = SceneStage::Profile;
    const std::unique_ptr<rig::Clip> clip = scene::makeClip(scene.clip);
    stage = SceneStage::Clip;
    const std::vector<int> frames = scene::parseFrameList(scene.frames, "frames");
    for (std::size_t i = 0; i < std::min<std::size_t>(frames.size(), 2); ++i)
      (void)rig::bakeFrame(*clip, profile, frames[i], scene::frameTime(scene, frames[i]));
    stage = SceneStage::Baked;
  });
  return stage;
}

int sceneJson(const std::uint8_t* data, std::size_t size) {
  (void)sceneJsonStage(data, size);
  return 0;
}

int rigProfileJson(const std::uint8_t* data, std::size_t size) {
  return expectOnlyInputErrors([&] {
    const rig::RigProfile p = scene::loadRigProfile(writeInput(data, size, "p.json").string(), scratch() / "profiles");
    (void)rig::evaluateRider(rig::HorseChannels{}, p);
    (void)scene::profileToJson(p).dump();
  });
}

int profileSets(const std::uint8_t* data, std::size_t size) {
  return expectOnlyInputErrors([&] {
    // One --set argument per line, as a shell would pass them.
    std::vector<std::string> sets;
    std::string text(reinterpret_cast<const char*>(data), size);
    for (std::size_t start = 0; start <= text.size();) {
      const std::size_t nl = std::min(text.find('\n', start), text.size());
      sets.push_back(text.substr(start, nl - start));
      start = nl + 1;
    }
    rig::RigProfile p = rig::RigProfile::thesis();
    scene::applyProfileOverrides(p, cli::parseSets(sets), "--set");
    (void)rig::evaluateRider(rig::HorseChannels{}, p);
  });
}

int horseCsv(const std::uint8_t* data, std::size_t size) {
  return expectOnlyInputErrors([&] {
    const rig::HorseTrack track = rig::readHorseCsv(writeInput(data, size, "horse.csv"));
    // rig eval evaluates every row.
    for (const rig::HorseChannels& h : track.horse) (void)rig::evaluateRider(h, rig::RigProfile::thesis());
  });
}

int spineJson(const std::uint8_t* data, std::size_t size) {
  return expectOnlyInputErrors([&] {
    const rig::SpineFile spine = rig::readSpineFile(writeInput(data, size, "spine.json").string());
    // What stirrup spine does with it.
    const rig::CurveSpine curve(spine.bones, spine.segments, spine.layout);
    for (std::size_t i = 0; i < std::min<std::size_t>(spine.poses.size(), 4); ++i)
      (void)rig::spineResultToJson(curve.solve(spine.poses[i].controllers, spine.poses[i].stretch), spine.poses[i].stretch)
          .dump();
  });
}

int gltfClip(const std::uint8_t* data, std::size_t size) {
  return expectOnlyInputErrors([&] {
    const rig::GltfClip clip(writeInput(data, size, gltfName(data, size, "clip")), rig::contractMapping());
    sampleClip(clip);
  });
}

int gltfCharacter(const std::uint8_t* data, std::size_t size) {
  const fs::path file = writeInput(data, size, gltfName(data, size, "character"));
  for (const rig::CharacterKind kind : {rig::CharacterKind::Horse, rig::CharacterKind::Rider})
    expectOnlyInputErrors([&] { (void)rig::loadCharacterGltf(file, kind); });
  return 0;
}

int gltfShot(const std::uint8_t* data, std::size_t size) {
  const fs::path file = writeInput(data, size, gltfName(data, size, "shot"));
  // A baked shot, every pair posed at its first and last frames.
  expectOnlyInputErrors([&] {
    const std::unique_ptr<rig::GltfShot> shot = rig::GltfShot::read(file);
    if (!shot) return;
    for (std::size_t p = 0; p < shot->pairs().size(); ++p)
      for (const int frame : {1, shot->frameCount()}) (void)shot->pose(p, frame);
  });
  // The file as a horse playing its own animation: keyed exactly, and sampled.
  expectOnlyInputErrors([&] {
    const rig::Character horse = rig::loadCharacterGltf(file, rig::CharacterKind::Horse);
    const rig::KeyedHorseClip clip(file, "", rig::keyedHorseMapping(horse), &horse);
    sampleClip(clip);
    (void)rig::poseHorse(horse, clip.sample(clip.duration() * 0.5));
  });
  return 0;
}

int mappingJson(const std::uint8_t* data, std::size_t size) {
  const fs::path file = writeInput(data, size, "mapping.json");
  // The same file as a character mapping of either kind and as a clip mapping.
  for (const rig::CharacterKind kind : {rig::CharacterKind::Horse, rig::CharacterKind::Rider})
    expectOnlyInputErrors([&] { (void)rig::loadCharacterMapping(file, kind); });
  expectOnlyInputErrors([&] { (void)rig::loadClipMapping(file); });
  return 0;
}

int frameSpec(const std::uint8_t* data, std::size_t size) {
  return expectOnlyInputErrors([&] {
    const std::vector<int> frames = scene::parseFrameList(std::string(reinterpret_cast<const char*>(data), size), "--frames");
    if (frames.size() > static_cast<std::size_t>(scene::kMaxFrameCount)) std::abort();
  });
}

int farmManifest(const std::uint8_t* data, std::size_t size) {
  // farm status and resume read OUT/farm.json back; a hand-edited or damaged one must be a one-line error.
  const fs::path file = writeInput(data, size, "farm.json");
  return expectOnlyInputErrors([&] { (void)render::readManifest(file.parent_path()); });
}

}  // namespace stirrup::fuzz
