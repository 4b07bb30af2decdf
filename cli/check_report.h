// What `stirrup check` found and the reports it writes of it (cli/cmd_check.cpp runs the check and
// picks the report): the findings as text or JSON on stdout, a JUnit XML file, and an HTML page with
// thumbnails of the flagged frames and SVG plots of the measures and channels around them (drawn on
// the review's plot canvas, render/review/plot_canvas.h).
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rig/character.h"
#include "rig/frame_check.h"
#include "rig/io/gltf_shot.h"
#include "rig/rig_profile.h"
#include "scene/scene.h"

namespace stirrup::cli {

// Every rule a pair's frames are judged by, in report order.
constexpr std::array<const char*, 9> kRules = {"limit",          "over-reach",    "hoof-slide",       "hoof-in-ground", "rider-in-horse",
                                               "hand-off-rein", "foot-off-stirrup", "trunk-balance", "gait"};

// One horse and rider of the shot, as it is checked: the characters, clip and profile the shot's
// evaluator gives it (scene/shot_evaluator.h; a crowd pair's at full detail), or a baked shot's
// file holds.
struct CheckedPair {
  std::string name;  // "" for a single pair; "pair 3" in a crowd; a baked shot's own ("pair03")
  int index = 0;
  const rig::Character* horse = nullptr;
  const rig::Character* rider = nullptr;
  std::shared_ptr<const rig::Character> own_horse;  // a baked shot's horse with the tack it does not hold left out (horse points at it)
  rig::RigProfile profile;
  const rig::Clip* clip = nullptr;  // sampled at the shot's time (a crowd's pair: its clip at its start phase); null for a baked shot
  std::size_t slot = 0;             // a baked shot's: the pair's place in the file's pairs
  std::vector<rig::FrameMeasures> measures;
  std::vector<rig::CheckFinding> findings;
  std::vector<std::string> unmeasured;
};

struct CheckInput {
  enum class Kind { Scene, Clip, Shot } kind = Kind::Scene;
  scene::SceneSpec scene;  // the scene; a clip's scene of its own; a baked shot's --scene (else the default)
  std::string source;       // what the report names: the scene or glTF file
  std::string name;         // the scene's name, or the glTF file's stem
  std::string frames;       // the frames checked unless --frames says
  std::unique_ptr<rig::GltfShot> shot;
  const rig::Terrain* terrain = nullptr;  // null: flat ground
  std::shared_ptr<const rig::Terrain> file_ground;  // a baked shot's own ground mesh (terrain points at it)
  // Where the ground came from: "scene" (the scene's terrain, or a baked shot's --scene), "file" (the
  // shot's own ground mesh) or "flat".
  std::string ground = "flat";
  std::string described;    // what the input was read as, for the report
};

struct Counts {
  int failures = 0, warnings = 0, notes = 0;
  void add(rig::CheckSeverity s) { (s == rig::CheckSeverity::Failure ? failures : s == rig::CheckSeverity::Warning ? warnings : notes)++; }
  int status() const { return failures ? 2 : warnings ? 1 : 0; }
};

// JUnit XML: one test suite a pair, one test case a rule (a rule with failures fails its case).
std::string junitXml(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames);

// The HTML page in `dir`: each run of flagged frames with a thumbnail of its worst frame and plots.
void writeHtml(const CheckInput& in, std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const std::filesystem::path& dir,
               const Counts& counts);

// The findings on stdout: as JSON (with the gait's measures where --reference gave them), or as text.
void printJson(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const Counts& counts,
               std::map<std::string, Counts>& by_rule, const nlohmann::json& gait_json);
void printText(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const Counts& counts,
               std::map<std::string, Counts>& by_rule);

}  // namespace stirrup::cli
