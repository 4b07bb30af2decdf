// stirrup check SCENE.json | SHOT.glb | CLIP.glb [--json] [--junit REPORT.xml] [--html DIR]: a shot checked
// frame by frame and pair by pair without rendering it (docs/check.md):
//  - the limits a horse has (rig/motion/horse_limits.h): along every path of a scene, a generated
//    clip's gait speeds (the clip's, not a frame's), or from a glTF clip's own travel (speed, speeding
//    up, braking, turning);
//  - a baked shot (rig/io/gltf_shot.h: `stirrup bake -o`, or Blender's re-export of one) measured on its
//    own joints and meshes as the file keys them, nothing re-posed;
//  - every pair of a scene or clip posed as every consumer poses it (rig::poseMounted) and measured in world space
//    (rig/frame_check.h): hooves sliding while down, over-reaching, in the ground; the rider in the
//    horse; hands off the reins; feet out of the stirrups; the trunk outside the balance band;
//  - a glTF clip against the gait reference (`--reference GAIT`, as `clip info` measures it).
// Exit status 0 clean, 1 warnings, 2 failures (notes do not count), 3 an input that cannot be checked.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "cli/commands.h"
#include "cli/progress.h"
#include "render/review/index_page.h"
#include "render/tracer/image.h"
#include "render/scene/preset.h"
#include "render/scene/profile_resolver.h"
#include "render/scene/scene.h"
#include "render/shot.h"
#include "render/scene/shot_evaluator.h"
#include "rig/bake.h"
#include "rig/error.h"
#include "rig/frame_check.h"
#include "rig/io/atomic_file.h"
#include "rig/io/frame_range.h"
#include "rig/io/gltf_clip.h"
#include "rig/io/gltf_shot.h"
#include "rig/motion/clip_report.h"
#include "rig/motion/horse_limits.h"
#include "rig/motion/path_clip.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"

namespace stirrup::cli {
namespace {

namespace fs = std::filesystem;

struct CheckOptions {
  std::string input;
  std::string frames;
  std::string pairs;
  bool json = false;
  std::string junit, html;
  // A glTF clip: how to read it and what to measure it against.
  std::string mapping, animation, reference;
  double fps = 24.0;
  // A baked shot: the scene giving its ground (and its pairs' profiles), and the profile for them all.
  std::string scene, profile;
  bool progress = false;
};

// Every rule a pair's frames are judged by, in report order.
constexpr std::array<const char*, 9> kRules = {"limit",          "over-reach",    "hoof-slide",       "hoof-in-ground", "rider-in-horse",
                                               "hand-off-rein", "foot-off-stirrup", "trunk-balance", "gait"};

// One horse and rider of the shot, as it is checked: the characters, clip and profile the shot's
// evaluator gives it (render/scene/shot_evaluator.h; a crowd pair's at full detail), or a baked shot's
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
  render::SceneSpec scene;  // the scene; a clip's scene of its own; a baked shot's --scene (else the default)
  std::string source;       // what the report names: the scene or glTF file
  std::string name;         // the scene's name, or the glTF file's stem
  std::string frames;       // the frames checked unless --frames says
  std::unique_ptr<rig::GltfShot> shot;
  const rig::Terrain* terrain = nullptr;  // null: flat ground
  std::string described;    // what the input was read as, for the report
};

bool isGltf(const std::string& f) {
  const std::string e = fs::path(f).extension().string();
  return e == ".glb" || e == ".gltf";
}

std::string plural(std::size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

// A glTF clip ridden by the default pair on flat ground, as a scene of its own: every frame of the clip.
CheckInput clipScene(const CheckOptions& o) {
  nlohmann::json clip = {{"file", fs::absolute(o.input).string()}};
  if (!o.mapping.empty()) clip["mapping"] = fs::absolute(o.mapping).string();
  if (!o.animation.empty()) clip["animation"] = o.animation;
  nlohmann::json j = {{"name", fs::path(o.input).stem().string()}, {"clip", clip}, {"fps", o.fps}, {"frames", "1"}};
  CheckInput in;
  in.kind = CheckInput::Kind::Clip;
  in.source = o.input;
  in.scene = render::parseScene(j, o.input, {true});
  in.name = in.scene.name;
  const std::unique_ptr<rig::Clip> c = render::makeSceneClip(in.scene);
  const int last = std::max(1, 1 + int(std::floor(c->duration() * o.fps + 1e-9)));
  in.frames = in.scene.frames = "1-" + std::to_string(last);
  in.described = "a horse clip ridden by the default pair, " + plural(std::size_t(last), "frame", "frames") + " at " + printfNumber("%g", o.fps) + " fps";
  return in;
}

// A baked shot (rig/io/gltf_shot.h): its own pairs and frames, on --scene's ground.
CheckInput shotInput(const CheckOptions& o, std::unique_ptr<rig::GltfShot> shot) {
  if (!o.mapping.empty() || !o.reference.empty())
    throw InputError("check: --mapping and --reference apply to a horse clip, and " + o.input + " is a baked shot");
  CheckInput in;
  in.kind = CheckInput::Kind::Shot;
  in.source = o.input;
  in.name = fs::path(o.input).stem().string();
  if (!o.scene.empty()) {
    in.scene = render::loadScene(o.scene, {true});
    in.terrain = in.scene.terrain.get();
  }
  in.frames = "1-" + std::to_string(shot->frameCount());
  std::string names;
  for (const rig::GltfShot::Pair& p : shot->pairs())
    names += (names.empty() ? "" : ", ") + (p.name.empty() ? p.horse_armature + " and " + p.rider_armature : p.name);
  in.described = "a baked shot: " + plural(shot->pairs().size(), "pair", "pairs") + " (" + names + "), " +
                 plural(std::size_t(shot->frameCount()), "frame", "frames") + " at " + printfNumber("%g", shot->fps()) + " fps" +
                 (shot->animationName().empty() ? ", no animation" : ", animation \"" + shot->animationName() + "\"");
  for (const std::string& other : shot->leftOut()) in.described += " (\"" + other + "\" left out: it keys the same joints; --animation picks it)";
  in.shot = std::move(shot);
  return in;
}

CheckInput loadInput(const CheckOptions& o) {
  if (isGltf(o.input)) {
    if (!fs::exists(o.input)) throw InputError(o.input + ": no such file");
    rig::GltfShotOptions so;
    so.fps = o.fps;
    so.animation = o.animation;
    if (std::unique_ptr<rig::GltfShot> shot = rig::GltfShot::read(o.input, so)) return shotInput(o, std::move(shot));
    if (!o.scene.empty() || !o.profile.empty())
      throw InputError("check: --scene and --profile apply to a baked shot, and " + o.input + " is a horse clip (no armatures \"horse\" and \"rider\")");
    return clipScene(o);
  }
  if (!o.mapping.empty() || !o.animation.empty() || !o.reference.empty())
    throw InputError("check: --mapping, --animation and --reference apply to a glTF clip, not to the scene " + o.input);
  if (!o.scene.empty() || !o.profile.empty()) throw InputError("check: --scene and --profile apply to a baked shot, not to the scene " + o.input);
  CheckInput in;
  // Loaded whatever its limits: check reports them frame by frame.
  in.scene = render::loadScene(o.input, {true});
  in.source = in.scene.file.string();
  in.name = in.scene.name;
  in.frames = in.scene.frames;
  in.terrain = in.scene.terrain.get();
  const std::size_t pairs = in.scene.pairs.empty() ? 1 : in.scene.pairs.size();
  in.described = "a scene: " + plural(pairs, "pair", "pairs");
  return in;
}

// The pairs to check: the scene's one pair, or a crowd's (all, or those --pairs lists).
std::vector<CheckedPair> checkedPairs(const CheckInput& in, const CheckOptions& o, render::ShotEvaluator& shot) {
  const render::SceneSpec& scene = in.scene;
  if (scene.pairs.empty() && !o.pairs.empty())
    throw InputError("--pairs: expected a crowd scene, " + in.source + " has one horse and rider");
  std::vector<int> chosen;
  if (o.pairs.empty()) {
    for (int i = 0; i < shot.pairCount(); ++i) chosen.push_back(i);
  } else {
    for (const int i : rig::parseFrameList(o.pairs, "--pairs")) {
      if (i < 0 || i >= shot.pairCount())
        throw InputError("--pairs: expected pair indices from 0 to " + std::to_string(shot.pairCount() - 1) + ", got " + std::to_string(i));
      chosen.push_back(i);
    }
  }
  std::vector<CheckedPair> out;
  for (const int i : chosen) {
    CheckedPair p;
    p.index = i;
    p.name = shot.isCrowd() ? "pair " + std::to_string(i) : "";
    p.horse = &shot.horseAt(i, 0);
    p.rider = &shot.riderAt(i, 0);
    p.profile = shot.profile(i);
    p.clip = &shot.shownClip(i);
    out.push_back(std::move(p));
  }
  return out;
}

// The horse without its rein and stirrup roles where they are points the rig placed, not joints of the
// file (null when the file holds them, or the horse has none).
std::shared_ptr<rig::Character> withoutPlacedTack(const rig::Character& horse) {
  std::vector<std::string> placed;
  for (const char* role : {"lRein", "rRein", "lStirrup", "rStirrup"}) {
    const auto it = horse.roles.find(role);
    if (it != horse.roles.end() && it->second >= 0 && horse.skeleton.joints[std::size_t(it->second)].rig_point) placed.push_back(role);
  }
  if (placed.empty()) return nullptr;
  auto out = std::make_shared<rig::Character>(horse);
  for (const std::string& role : placed) out->roles.erase(role);
  return out;
}

// A baked shot's pairs to check: every pair the file holds, or those --pairs lists (by their indices,
// pair03's 3), each with the profile --profile names, else its pair's in --scene (a crowd's pairs ride
// their own), else the scene's, else the thesis's: only its balance band is used.
std::vector<CheckedPair> shotPairs(const CheckInput& in, const CheckOptions& o) {
  const std::vector<rig::GltfShot::Pair>& all = in.shot->pairs();
  std::vector<int> chosen;
  if (!o.pairs.empty()) {
    if (all.size() == 1 && all[0].name.empty()) throw InputError("--pairs: expected a crowd's shot, " + in.source + " has one horse and rider");
    chosen = rig::parseFrameList(o.pairs, "--pairs");
    for (const int i : chosen)
      if (std::none_of(all.begin(), all.end(), [i](const rig::GltfShot::Pair& p) { return p.index == i; }))
        throw InputError("--pairs: " + in.source + " has no pair " + std::to_string(i) + " (expected the NN of its pairNN_horse armatures)");
  }
  std::map<std::string, rig::RigProfile> resolved;  // by profile name: each resolved once
  const auto profileNamed = [&](const std::string& name, bool from_scene) -> const rig::RigProfile& {
    auto it = resolved.find(name);
    if (it != resolved.end()) return it->second;
    render::SceneSpec named = in.scene;
    named.profile = name;
    return resolved.emplace(name, from_scene ? render::resolveProfile(named) : render::resolveProfile(name)).first->second;
  };
  std::vector<CheckedPair> out;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const rig::GltfShot::Pair& sp = all[k];
    if (!chosen.empty() && std::find(chosen.begin(), chosen.end(), sp.index) == chosen.end()) continue;
    CheckedPair p;
    p.index = sp.index;
    p.slot = k;
    p.name = sp.name;
    p.horse = &sp.horse;
    p.rider = &sp.rider;
    // Reins and stirrups the file does not hold (a user's horse exported from Blender: the rig's tack is
    // only points it placed on the horse at rest) say nothing of where her hands and feet belong; those
    // rules are then not measured, and said so (rig::PairCheck), rather than measured against the rest.
    if (std::shared_ptr<rig::Character> own = withoutPlacedTack(sp.horse)) {
      p.own_horse = own;
      p.horse = own.get();
    }
    if (!o.profile.empty()) p.profile = profileNamed(o.profile, false);
    else if (o.scene.empty()) p.profile = profileNamed("thesis", false);
    else if (std::size_t(sp.index) < in.scene.pairs.size() && !sp.name.empty()) p.profile = profileNamed(in.scene.pairs[std::size_t(sp.index)].profile, true);
    else p.profile = profileNamed(in.scene.profile, true);
    // A bake keys its hooves where they are: no target they could fall short of, no clip to hold to a horse's limits.
    p.unmeasured = {"over-reach: a baked shot keys its hooves where they stand, with no targets for them to fall short of",
                    "limit: a baked shot has no path or clip to hold to a horse's limits (check the scene it was baked from)"};
    out.push_back(std::move(p));
  }
  return out;
}

// One pair's frame posed: its time, the horse's clip frame (a baked shot's: none), both skeletons.
struct PosedFrame {
  double time_s = 0;
  rig::HorseFrame horse;
  rig::MountedPose pose;
};
using PoseAt = std::function<PosedFrame(const CheckedPair& pair, int frame)>;

// Every pair's frames measured (rig::PairCheck) and judged. Frames are independent: each writes only its
// own slot, so the report is the same at any thread count.
void measurePairs(std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const rig::PairCheck::GroundHeight& ground,
                  const PoseAt& poseAt, ProgressBar& bar) {
  int done = 0;
  for (CheckedPair& p : pairs) {
    const rig::PairCheck checker(*p.horse, *p.rider, p.profile.balance);
    const std::vector<std::string>& cannot = checker.unmeasured();
    p.unmeasured.insert(p.unmeasured.begin(), cannot.begin(), cannot.end());
    p.measures.resize(frames.size());
    tbb::parallel_for(std::size_t(0), frames.size(), [&](std::size_t i) {
      const PosedFrame f = poseAt(p, frames[i]);
      p.measures[i] = checker.measure(frames[i], f.time_s, f.horse, f.pose, ground);
    });
    bar.step(done += int(frames.size()));
    p.findings = checker.judge(p.measures, p.index);
  }
}

struct Counts {
  int failures = 0, warnings = 0, notes = 0;
  void add(rig::CheckSeverity s) { (s == rig::CheckSeverity::Failure ? failures : s == rig::CheckSeverity::Warning ? warnings : notes)++; }
  int status() const { return failures ? 2 : warnings ? 1 : 0; }
};

// Writes `text` to `file` whole or not at all (a temporary name, then a rename).
void writeWhole(const fs::path& file, const std::string& text) { rig::writeFileAtomically(file, text); }

// JUnit XML: one test suite a pair, one test case a rule. A rule with failures fails its case; one with
// only warnings passes and lists them in system-out (exit status 1 is the gate for warnings); a rule the
// pair cannot be measured by is skipped with the reason.
std::string junitXml(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames) {
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"stirrup check\">\n";
  for (const CheckedPair& p : pairs) {
    const std::string suite = in.name + (p.name.empty() ? "" : "." + p.name);
    int failures = 0, skipped = 0;
    std::string cases;
    for (const char* rule : kRules) {
      std::string failed, warned, skip;
      for (const std::string& u : p.unmeasured)
        if (u.rfind(std::string(rule) + ":", 0) == 0) skip += (skip.empty() ? "" : "; ") + u;
      int n_fail = 0;
      std::string first_failure;
      for (const rig::CheckFinding& f : p.findings) {
        if (f.rule != rule || f.severity == rig::CheckSeverity::Note) continue;
        const std::string line = (f.frame > 0 ? "frame " + std::to_string(f.frame) + ": " : "") + f.text + "\n";
        if (f.severity == rig::CheckSeverity::Failure) {
          if (first_failure.empty()) first_failure = line.substr(0, line.size() - 1);
          failed += line, ++n_fail;
        } else {
          warned += "warning: " + line;
        }
      }
      cases += "    <testcase classname=\"" + render::htmlEscape(suite) + "\" name=\"" + rule + "\">\n";
      if (n_fail) {
        ++failures;
        cases += "      <failure type=\"" + std::string(rule) + "\" message=\"" + render::htmlEscape(std::to_string(n_fail) + " failing: " + first_failure) +
                 "\">" + render::htmlEscape(failed) + "</failure>\n";
      } else if (!skip.empty()) {
        ++skipped;
        cases += "      <skipped message=\"" + render::htmlEscape(skip) + "\"/>\n";
      }
      if (!warned.empty()) cases += "      <system-out>" + render::htmlEscape(warned) + "</system-out>\n";
      cases += "    </testcase>\n";
    }
    x += "  <testsuite name=\"" + render::htmlEscape(suite) + "\" tests=\"" + std::to_string(kRules.size()) + "\" failures=\"" +
         std::to_string(failures) + "\" errors=\"0\" skipped=\"" + std::to_string(skipped) + "\">\n";
    x += "    <properties><property name=\"file\" value=\"" + render::htmlEscape(in.source) + "\"/><property name=\"frames\" value=\"" +
         std::to_string(frames.size()) + "\"/></properties>\n";
    x += cases + "  </testsuite>\n";
  }
  return x + "</testsuites>\n";
}

// The value a rule measures at a frame (for the HTML page's plot), -1 where there is none.
double measureOf(const rig::FrameMeasures& m, const rig::FrameMeasures* prev, const std::string& rule, const std::string& where) {
  static const std::map<std::string, int> kLeg = {{"lf", 0}, {"rf", 1}, {"lb", 2}, {"rb", 3}};
  const int leg = kLeg.count(where) ? kLeg.at(where) : -1;
  const int side = where == "left" ? 0 : where == "right" ? 1 : -1;
  if (rule == "hoof-slide" && leg >= 0) {
    if (!prev || !prev->down[std::size_t(leg)] || !m.down[std::size_t(leg)]) return 0;
    return rig::soleSlide(prev->contact[std::size_t(leg)], m.contact[std::size_t(leg)]);
  }
  if (rule == "over-reach" && leg >= 0) return std::max(0.0f, m.reach_short_cm[std::size_t(leg)]);
  if (rule == "hoof-in-ground" && leg >= 0) return m.below_ground_cm[std::size_t(leg)];
  if (rule == "rider-in-horse") return m.rider_depth_cm;
  if (rule == "hand-off-rein" && side >= 0) return m.hand_off_cm[std::size_t(side)];
  if (rule == "foot-off-stirrup" && side >= 0) return m.foot_off_cm[std::size_t(side)];
  if (rule == "trunk-balance") return m.trunk_lean_deg;
  return -1;
}

// A small SVG line plot: series over frames, with horizontal guide lines.
struct Series {
  std::string name, colour;
  std::vector<std::pair<int, double>> points;
};
std::string svgPlot(const std::vector<Series>& series, const std::vector<std::pair<std::string, double>>& guides, int mark_frame) {
  constexpr double W = 360, H = 150, L = 40, R = 8, T = 8, B = 22;
  int f0 = mark_frame, f1 = mark_frame;
  double lo = 0, hi = 0;
  for (const Series& s : series)
    for (const auto& [f, v] : s.points) f0 = std::min(f0, f), f1 = std::max(f1, f), lo = std::min(lo, v), hi = std::max(hi, v);
  for (const auto& g : guides) lo = std::min(lo, g.second), hi = std::max(hi, g.second);
  if (hi - lo < 1e-6) hi = lo + 1;
  if (f1 == f0) f1 = f0 + 1;
  const auto X = [&](double f) { return L + (f - f0) / double(f1 - f0) * (W - L - R); };
  const auto Y = [&](double v) { return T + (hi - v) / (hi - lo) * (H - T - B); };
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"360\" height=\"150\" font-size=\"10\">";
  s += "<rect x=\"" + printfNumber("%.0f", L) + "\" y=\"" + printfNumber("%.0f", T) + "\" width=\"" + printfNumber("%.0f", W - L - R) + "\" height=\"" +
       printfNumber("%.0f", H - T - B) + "\" fill=\"#fafafa\" stroke=\"#ccc\"/>";
  for (const auto& [name, v] : guides)
    s += "<line x1=\"" + printfNumber("%.1f", L) + "\" x2=\"" + printfNumber("%.1f", W - R) + "\" y1=\"" + printfNumber("%.1f", Y(v)) + "\" y2=\"" + printfNumber("%.1f", Y(v)) +
         "\" stroke=\"#c00\" stroke-dasharray=\"3,3\"/><text x=\"" + printfNumber("%.1f", W - R - 2) + "\" y=\"" + printfNumber("%.1f", Y(v) - 2) +
         "\" text-anchor=\"end\" fill=\"#c00\">" + render::htmlEscape(name) + "</text>";
  s += "<line x1=\"" + printfNumber("%.1f", X(mark_frame)) + "\" x2=\"" + printfNumber("%.1f", X(mark_frame)) + "\" y1=\"" + printfNumber("%.0f", T) + "\" y2=\"" +
       printfNumber("%.0f", H - B) + "\" stroke=\"#888\"/>";
  int row = 0;
  for (const Series& se : series) {
    std::string pts;
    for (const auto& [f, v] : se.points) pts += printfNumber("%.1f", X(f)) + "," + printfNumber("%.1f", Y(v)) + " ";
    s += "<polyline fill=\"none\" stroke=\"" + se.colour + "\" stroke-width=\"1.5\" points=\"" + pts + "\"/>";
    s += "<text x=\"" + printfNumber("%.0f", L + 4) + "\" y=\"" + printfNumber("%.0f", T + 11 + 11 * row++) + "\" fill=\"" + se.colour + "\">" + render::htmlEscape(se.name) + "</text>";
  }
  s += "<text x=\"" + printfNumber("%.0f", L) + "\" y=\"" + printfNumber("%.0f", H - 6) + "\">" + std::to_string(f0) + "</text>";
  s += "<text x=\"" + printfNumber("%.0f", W - R) + "\" y=\"" + printfNumber("%.0f", H - 6) + "\" text-anchor=\"end\">" + std::to_string(f1) + "</text>";
  s += "<text x=\"4\" y=\"" + printfNumber("%.1f", Y(hi) + 8) + "\">" + printfNumber("%.3g", hi) + "</text><text x=\"4\" y=\"" + printfNumber("%.1f", Y(lo)) + "\">" +
       printfNumber("%.3g", lo) + "</text>";
  return s + "</svg>";
}

// The channels plotted beside a rule's measure.
std::vector<std::string> plotChannels(const std::string& rule, const std::string& where) {
  if (rule == "hoof-slide" || rule == "over-reach" || rule == "hoof-in-ground") return {where + "Hoof.tx", where + "Hoof.ty"};
  if (rule == "hand-off-rein") return {where == "left" ? "lWrist.tx" : "rWrist.tx", "rearPivot.rz"};
  if (rule == "foot-off-stirrup") return {where == "left" ? "lFoot.tx" : "rFoot.tx", where == "left" ? "lFoot.tz" : "rFoot.tz"};
  if (rule == "trunk-balance" || rule == "rider-in-horse") return {"rearPivot.rz", "lowerBack.rz"};
  return {"rearPivot.rz"};
}

double channelValue(const rig::BakedFrame& b, const std::string& name) {
  if (const auto h = rig::horseChannelFromName(name)) return b.horse.controls[*h];
  if (const auto r = rig::riderChannelFromName(name)) return b.rider[*r];
  return 0;
}

// The HTML page: each run of flagged frames (consecutive frames of one pair, one rule and place) with
// a thumbnail of its worst frame and the measure and channels plotted around it.
void writeHtml(const CheckInput& in, std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const fs::path& dir,
               const Counts& counts) {
  constexpr int kMaxRuns = 24;        // thumbnails rendered at most (the rest are listed)
  constexpr int kPlotHalfFrames = 24;  // a second either side at 24 fps
  fs::create_directories(dir);
  struct Run {
    CheckedPair* pair;
    const rig::CheckFinding* worst;
    int first, last, count;
  };
  std::vector<Run> runs;
  for (CheckedPair& p : pairs) {
    std::vector<Run> mine;
    for (const rig::CheckFinding& f : p.findings) {
      if (f.severity == rig::CheckSeverity::Note) continue;
      bool joined = false;
      for (Run& r : mine)
        if (r.worst->rule == f.rule && r.worst->where == f.where && f.frame > 0 && f.frame <= r.last + 1) {
          r.last = std::max(r.last, f.frame);
          ++r.count;
          if (f.value > r.worst->value) r.worst = &f;
          joined = true;
          break;
        }
      if (!joined) mine.push_back({&p, &f, f.frame, f.frame, 1});
    }
    runs.insert(runs.end(), mine.begin(), mine.end());
  }
  std::stable_sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) {
    return int(a.worst->severity) != int(b.worst->severity) ? int(a.worst->severity) > int(b.worst->severity) : a.first < b.first;
  });

  std::string body;
  int rendered = 0;
  render::SceneSpec thumb = in.scene;
  thumb.width = 320;
  thumb.height = 180;
  render::applyPreset(thumb, render::findPreset("draft"));
  // Hoof and limit findings are seen from the side (the whole horse and its hooves), the rider's close up.
  std::map<std::pair<int, std::string>, std::unique_ptr<render::Shot>> shots;  // by pair index and view
  for (const Run& r : runs) {
    const rig::CheckFinding& f = *r.worst;
    CheckedPair& p = *r.pair;
    body += "<section class=\"" + std::string(rig::checkSeverityName(f.severity)) + "\"><h2>" +
            render::htmlEscape((p.name.empty() ? "" : p.name + ": ") + f.rule + (f.where.empty() ? "" : " (" + f.where + ")")) + ", frame" +
            (r.first == r.last ? " " + std::to_string(r.first) : "s " + std::to_string(r.first) + "-" + std::to_string(r.last)) + "</h2>";
    body += "<p>" + render::htmlEscape(std::string(rig::checkSeverityName(f.severity)) + " at frame " + std::to_string(f.frame) + ": " + f.text) + "</p>";
    // A baked shot has no scene to render a thumbnail from, nor a clip whose channels drive the measure.
    if (f.frame > 0 && rendered < kMaxRuns && p.clip) {
      const bool rider_rule = f.rule == "rider-in-horse" || f.rule == "hand-off-rein" || f.rule == "foot-off-stirrup" || f.rule == "trunk-balance";
      const std::string view = rider_rule ? "close" : "side";
      auto it = shots.find({p.index, view});
      if (it == shots.end()) {
        render::CameraSpec cam;
        cam.name = view;
        cam.view = view;
        cam.follow_pair = p.name.empty() ? -1 : p.index;
        it = shots.emplace(std::make_pair(p.index, view), std::make_unique<render::Shot>(thumb, p.profile, cam, 0)).first;
      }
      const std::string png = "frame_" + (p.name.empty() ? "" : std::to_string(p.index) + "_") + std::to_string(f.frame) + ".png";
      render::writePng(it->second->renderFrame(f.frame), dir / png);
      ++rendered;
      body += "<img src=\"" + png + "\" width=\"320\" height=\"180\" alt=\"frame " + std::to_string(f.frame) + "\">";
    }
    if (f.frame > 0) {
      Series measure{f.rule + (f.where.empty() ? "" : " " + f.where), "#000", {}};
      const std::vector<std::string> names = plotChannels(f.rule, f.where);
      std::vector<Series> channels;
      const char* colours[] = {"#1f77b4", "#2ca02c"};
      for (std::size_t k = 0; k < names.size() && k < 2 && p.clip; ++k) channels.push_back({names[k], colours[k], {}});
      for (std::size_t i = 0; i < p.measures.size(); ++i) {
        const rig::FrameMeasures& m = p.measures[i];
        if (std::abs(m.frame - f.frame) > kPlotHalfFrames) continue;
        const rig::FrameMeasures* prev = i > 0 && p.measures[i - 1].frame == m.frame - 1 ? &p.measures[i - 1] : nullptr;
        measure.points.emplace_back(m.frame, measureOf(m, prev, f.rule, f.where));
        if (!p.clip) continue;
        const rig::BakedFrame b = rig::bakeFrame(*p.clip, p.profile, m.frame, m.time_s);
        for (std::size_t k = 0; k < channels.size(); ++k) channels[k].points.emplace_back(m.frame, channelValue(b, names[k]));
      }
      body += svgPlot({measure}, {{"limit", f.bound}}, f.frame) + (p.clip ? svgPlot(channels, {}, f.frame) : "");
    }
    body += "</section>\n";
  }
  std::string unmeasured;
  for (const CheckedPair& p : pairs)
    for (const std::string& u : p.unmeasured) unmeasured += "<li>" + render::htmlEscape((p.name.empty() ? "" : p.name + ": ") + u) + "</li>";
  const std::string title = "stirrup check: " + in.source;
  std::string html = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + render::htmlEscape(title) +
                     "</title><style>body{font-family:sans-serif;margin:2em}section{border-top:1px solid #ccc;padding:.5em 0}"
                     "section.failure h2{color:#b00}section.warning h2{color:#a60}h2{font-size:1.1em}img,svg{vertical-align:top;margin-right:1em}"
                     "</style></head><body>\n<h1>" + render::htmlEscape(title) + "</h1>\n<p>" + render::htmlEscape(in.described) + ".</p>\n" +
                     (in.shot ? "<p>No thumbnails or channel plots: they need the scene the shot was baked from.</p>\n" : "") +
                     "<p>" + std::to_string(frames.size()) + " frames, " +
                     std::to_string(pairs.size()) + (pairs.size() == 1 ? " pair" : " pairs") + ": " + std::to_string(counts.failures) +
                     " failures, " + std::to_string(counts.warnings) + " warnings, " + std::to_string(counts.notes) + " notes; " +
                     std::to_string(runs.size()) + " runs of flagged frames" +
                     (int(runs.size()) > kMaxRuns ? " (thumbnails of the first " + std::to_string(kMaxRuns) + ")" : "") + ".</p>\n" +
                     (unmeasured.empty() ? "" : "<p>Not measured:</p><ul>" + unmeasured + "</ul>\n") +
                     (runs.empty() ? "<p>Nothing flagged.</p>\n" : body) + "</body></html>\n";
  writeWhole(dir / "index.html", html);
}

// Limits along a scene's paths (a crowd: each pair's) at each frame within half a frame; a glTF clip's
// own travel (it has no path). A baked shot has neither.
void addLimitFindings(const CheckInput& in, const std::vector<int>& frames, std::vector<CheckedPair>& pairs) {
  if (in.kind == CheckInput::Kind::Shot) return;
  const render::SceneSpec& scene = in.scene;
  const double half = 0.5 / scene.fps;
  std::vector<rig::CheckFinding> limit_findings;
  for (std::size_t k = 0; k < scene.limits.size(); ++k) {
    const render::SceneSpec::PathLimits& l = scene.limits[k];
    const int pair = scene.pairs.empty() ? 0 : int(k);
    for (int frame : frames) {
      const double t = render::frameTime(scene, frame);
      for (const rig::LimitBreach& b : l.check->during(t + l.clip_offset_s - half, t + l.clip_offset_s + half)) {
        const std::string what = b.text.substr(b.text.find(": ") + 2);
        limit_findings.push_back({frame, t, pair, rig::CheckSeverity::Failure, "limit", rig::horseLimitName(b.limit), b.value, b.bound,
                                  std::string(rig::horseLimitName(b.limit)) + " (" + l.check->clipField() + "." + b.field + ", segment " +
                                      std::to_string(b.segment) + "): " + what});
      }
    }
  }
  // A generated gait faster than horses go at it: the clip's, not one frame's.
  for (const rig::GaitSpeedBreach& b : scene.gait_breaches)
    limit_findings.push_back({0, 0, 0, rig::CheckSeverity::Failure, "limit", "gait speed", b.speed.speed_cm_s, b.bound_cm_s,
                              "gait speed (clip." + b.speed.field + "): " + b.text()});
  // A clip with no path (a glTF clip): its own travel.
  for (CheckedPair& p : pairs) {
    if (in.kind != CheckInput::Kind::Clip) break;
    for (int frame : frames) {
      const double t = render::frameTime(scene, frame);
      for (const auto& [limit, text] : rig::travelLimitsAt(*p.clip, t).breaches)
        limit_findings.push_back({frame, t, p.index, rig::CheckSeverity::Failure, "limit", rig::horseLimitName(limit), 0, 0,
                                  std::string(rig::horseLimitName(limit)) + " (the clip's travel): " + text});
    }
  }
  for (CheckedPair& p : pairs)
    for (const rig::CheckFinding& f : limit_findings)
      if (f.pair == p.index) p.findings.push_back(f);
}

// A glTF clip against the gait reference (--reference): its measures as JSON, each outside its range a warning.
nlohmann::json addGaitFindings(const CheckOptions& o, const CheckInput& in, std::vector<CheckedPair>& pairs) {
  if (o.reference.empty()) return nullptr;
  const auto ref = rig::gaitReference(o.reference);
  if (!ref) throw InputError("check: --reference: expected walk, trot, canter, gallop, stop, jump, rear or buck, got \"" + o.reference + "\"");
  rig::ClipInfoOptions io;
  io.fps = in.scene.fps;
  const rig::ClipInfo info = rig::measureClip(*pairs[0].clip, io);
  for (const rig::Verdict& v : rig::clipVerdicts(info, *ref)) {
    if (v.ok) continue;
    pairs[0].findings.push_back({0, 0, 0, rig::CheckSeverity::Warning, "gait", v.key, v.value, v.range.hi,
                                 v.key + " " + printfNumber("%.4g", v.value) + " outside the " + o.reference + " reference's " + printfNumber("%.4g", v.range.lo) +
                                     "-" + printfNumber("%.4g", v.range.hi) + (v.note.empty() ? "" : " (" + v.note + ")")});
  }
  return rig::clipInfoJson(info, &*ref);
}

void printJson(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const Counts& counts,
               std::map<std::string, Counts>& by_rule, const nlohmann::json& gait_json) {
  static const char* const kKinds[] = {"scene", "clip", "shot"};
  nlohmann::json j = {{"input", in.source}, {"read_as", kKinds[int(in.kind)]}, {"described", in.described}, {"frames", frames.size()},
                      {"pairs", pairs.size()}, {"status", counts.status()}, {"failures", counts.failures}, {"warnings", counts.warnings},
                      {"notes", counts.notes}};
  nlohmann::json rules = nlohmann::json::object();
  for (const char* rule : kRules) rules[rule] = {{"failures", by_rule[rule].failures}, {"warnings", by_rule[rule].warnings}, {"notes", by_rule[rule].notes}};
  j["rules"] = rules;
  nlohmann::json unmeasured = nlohmann::json::array(), list = nlohmann::json::array(), names = nlohmann::json::array();
  for (const CheckedPair& p : pairs) {
    names.push_back({{"pair", p.index}, {"name", p.name}});
    for (const std::string& u : p.unmeasured) unmeasured.push_back({{"pair", p.index}, {"rule", u.substr(0, u.find(':'))}, {"reason", u}});
    for (const rig::CheckFinding& f : p.findings) {
      nlohmann::json e = {{"pair", f.pair}, {"severity", rig::checkSeverityName(f.severity)}, {"rule", f.rule}, {"where", f.where},
                          {"value", f.value}, {"bound", f.bound}, {"text", f.text}};
      if (f.frame > 0) e["frame"] = f.frame, e["time_s"] = f.time_s;
      else e["frame"] = nullptr;
      list.push_back(e);
    }
  }
  j["pair_names"] = names;
  j["unmeasured"] = unmeasured;
  nlohmann::json paths = nlohmann::json::array();
  for (const render::SceneSpec::PathLimits& l : in.scene.limits) {
    if (in.kind == CheckInput::Kind::Shot) break;  // --scene's paths are not the shot's
    nlohmann::json breaches = nlohmann::json::array();
    for (const rig::LimitBreach& b : l.check->breaches())
      breaches.push_back({{"limit", rig::horseLimitName(b.limit)}, {"field", b.field}, {"segment", b.segment},
                          {"from_s", b.time_s}, {"value", b.value}, {"bound", b.bound}, {"error", l.check->errorText(b)}});
    paths.push_back({{"path", l.check->clipField()}, {"breaches", breaches}});
  }
  j["paths"] = paths;
  if (!gait_json.is_null()) j["gait"] = gait_json;
  j["findings"] = list;
  std::printf("%s\n", j.dump(2).c_str());
}

void printText(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const Counts& counts,
               std::map<std::string, Counts>& by_rule) {
  std::printf("%s: %s\n", in.source.c_str(), in.described.c_str());
  for (const CheckedPair& p : pairs) {
    for (const std::string& u : p.unmeasured)
      std::printf("%s: %snot measured: %s\n", in.source.c_str(), p.name.empty() ? "" : (p.name + ": ").c_str(), u.c_str());
    for (const rig::CheckFinding& f : p.findings) {
      const std::string where = f.frame > 0 ? "frame " + std::to_string(f.frame) + " (" + printfNumber("%.3f", f.time_s) + " s)" : "the clip";
      std::printf("%s: %s%s: %s: %s: %s\n", in.source.c_str(), where.c_str(), p.name.empty() ? "" : (", " + p.name).c_str(),
                  rig::checkSeverityName(f.severity), f.rule.c_str(), f.text.c_str());
    }
  }
  std::string per_rule;
  for (const char* rule : kRules)
    if (by_rule[rule].failures + by_rule[rule].warnings > 0)
      per_rule += std::string(per_rule.empty() ? " (" : ", ") + rule + " " + std::to_string(by_rule[rule].failures + by_rule[rule].warnings);
  if (!per_rule.empty()) per_rule += ")";
  std::printf("%s: %zu frames, %zu %s: %d failures, %d warnings, %d notes%s\n", in.source.c_str(), frames.size(), pairs.size(),
              pairs.size() == 1 ? "pair" : "pairs", counts.failures, counts.warnings, counts.notes, per_rule.c_str());
}

void check(const CheckOptions& o) {
  const CheckInput in = loadInput(o);
  const std::vector<int> frames = rig::parseFrameList(o.frames.empty() ? in.frames : o.frames, "--frames");
  if (!o.html.empty() && fs::exists(o.html) && !fs::is_directory(o.html))
    throw InputError("--html: expected a folder, " + o.html + " is a file");
  const rig::Terrain* terrain = in.terrain;
  const rig::PairCheck::GroundHeight ground = [terrain](double x, double z) { return terrain ? terrain->height(x, z) : 0.0; };

  std::unique_ptr<render::ShotEvaluator> evaluator;  // a scene's or clip's pairs point into it
  std::vector<CheckedPair> pairs;
  PoseAt poseAt;
  if (in.kind == CheckInput::Kind::Shot) {
    const int last = in.shot->frameCount();
    for (const int f : frames)
      if (f < 1 || f > last) throw InputError("--frames: " + in.source + " keys frames 1-" + std::to_string(last) + ", got " + std::to_string(f));
    pairs = shotPairs(in, o);
    const double fps = in.shot->fps();
    poseAt = [&](const CheckedPair& p, int frame) { return PosedFrame{(frame - 1) / fps, {}, in.shot->pose(p.slot, frame, ground)}; };
  } else {
    evaluator = std::make_unique<render::ShotEvaluator>(in.scene, render::resolveProfile(in.scene), 0);
    pairs = checkedPairs(in, o, *evaluator);
    poseAt = [&](const CheckedPair& p, int frame) {
      const double t = render::frameTime(in.scene, frame);
      const rig::BakedFrame b = rig::bakeFrame(*p.clip, p.profile, frame, t);
      return PosedFrame{t, b.horse, rig::poseMounted(*p.horse, *p.rider, b.horse, b.rider, p.profile)};
    };
  }
  ProgressBar bar("check " + in.name, int(frames.size() * pairs.size()), o.progress);
  measurePairs(pairs, frames, ground, poseAt, bar);
  addLimitFindings(in, frames, pairs);
  const nlohmann::json gait_json = addGaitFindings(o, in, pairs);

  Counts counts;
  std::map<std::string, Counts> by_rule;
  for (CheckedPair& p : pairs) {
    std::stable_sort(p.findings.begin(), p.findings.end(), [](const rig::CheckFinding& a, const rig::CheckFinding& b) { return a.frame < b.frame; });
    for (const rig::CheckFinding& f : p.findings) counts.add(f.severity), by_rule[f.rule].add(f.severity);
  }
  if (o.json) printJson(in, pairs, frames, counts, by_rule, gait_json);
  else printText(in, pairs, frames, counts, by_rule);
  std::fflush(stdout);
  if (!o.junit.empty()) writeWhole(o.junit, junitXml(in, pairs, frames));
  if (!o.html.empty()) writeHtml(in, pairs, frames, o.html, counts);
  if (counts.status() != 0) throw ExitStatus{counts.status()};
}

// An input that cannot be checked (bad input) exits 3, apart from the findings' 0-2.
void runCheck(const CheckOptions& o) {
  try {
    check(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "stirrup: %s\n", e.what());
    throw ExitStatus{3};
  }
}

}  // namespace

void addCheckCommand(CLI::App& app) {
  auto opts = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand("check", "Check a shot frame by frame: a horse's limits, hooves, the rider's seat, hands and feet");
  cmd->footer(
      "Input: a scene (every pair of a crowd, or --pairs); a baked shot (stirrup bake -o, or a DCC's re-export of one:\n"
      "armatures horse and rider, or pairNN_horse and pairNN_rider), its own joints measured as keyed; or a glTF horse\n"
      "clip ridden by the default pair.\n"
      "Rules: limit (a horse's speed, acceleration, braking, turn, slopes, a gait's speed), over-reach, hoof-slide,\n"
      "hoof-in-ground, rider-in-horse, hand-off-rein, foot-off-stirrup, trunk-balance, gait (a glTF clip with\n"
      "--reference).\n"
      "Each warns at one measure and fails at a larger one (docs/check.md lists them and their sources).\n"
      "Exit status: 0 clean, 1 warnings, 2 failures (notes do not count), 3 an input that cannot be checked.\n"
      "Examples: stirrup check scenes/trail.json --junit check.xml\n"
      "          stirrup check my_trot.glb --reference trot --html check_report\n"
      "          stirrup check trot_from_blender.glb --scene scenes/trot.json");
  cmd->add_option("input", opts->input, "Scene file (JSON), baked shot or glTF horse clip (.glb, .gltf)")->required();
  cmd->add_option("--frames,-f", opts->frames,
                  "Frames to check, e.g. 1-120x2 (default: the scene's frames, a clip's or baked shot's every frame; a shot's frame 1 is its first key)");
  cmd->add_option("--pairs", opts->pairs, "A crowd's pairs to check, e.g. 0-4 (default: every pair; a baked shot's by their pairNN)");
  cmd->add_flag("--json", opts->json, "Write the findings as JSON on stdout");
  cmd->add_option("--junit", opts->junit, "Also write a JUnit XML report (a test suite a pair, a test case a rule)");
  cmd->add_option("--html", opts->html, "Also write an HTML page with thumbnails and plots of the flagged frames into this folder");
  cmd->add_option("--mapping", opts->mapping, "glTF clip: a clip mapping file (its nodes to the channel contract's controls)");
  cmd->add_option("--animation", opts->animation,
                  "glTF clip or baked shot: the animation to read (default: a clip's first; a shot's every animation together)");
  cmd->add_option("--reference", opts->reference, "glTF clip: measure it against this gait's reference (walk, trot, canter, ...)");
  cmd->add_option("--fps", opts->fps, "glTF clip: frames a second to check it at; baked shot: its rate where the file does not say (default 24)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--scene", opts->scene, "Baked shot: the scene it was baked from, for its ground (default flat) and its pairs' profiles");
  cmd->add_option("--profile", opts->profile, "Baked shot: the rig profile whose balance band the trunk is held to (default: the scene's, else thesis)");
  cmd->add_flag("--progress", opts->progress, "Show a progress bar");
  cmd->callback([opts] { runCheck(*opts); });
}

}  // namespace stirrup::cli
