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
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "cli/check_report.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "render/review/index_page.h"
#include "render/shot.h"
#include "render/tracer/image.h"
#include "rig/bake.h"
#include "rig/error.h"
#include "rig/frame_check.h"
#include "rig/io/atomic_file.h"
#include "rig/io/gltf_clip.h"
#include "rig/io/gltf_shot.h"
#include "rig/motion/clip_report.h"
#include "rig/motion/horse_limits.h"
#include "rig/motion/terrain.h"
#include "rig/motion/path_clip.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"
#include "scene/file_shot.h"
#include "scene/frame_range.h"
#include "scene/preset.h"
#include "scene/profile_resolver.h"
#include "scene/scene.h"
#include "scene/shot_evaluator.h"

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
  in.scene = scene::parseScene(j, o.input, {true});
  in.name = in.scene.name;
  const std::unique_ptr<rig::Clip> c = scene::makeSceneClip(in.scene);
  const int last = std::max(1, 1 + int(std::floor(c->duration() * o.fps + 1e-9)));
  in.frames = in.scene.frames = "1-" + std::to_string(last);
  in.described = "a horse clip ridden by the default pair, " + plural(std::size_t(last), "frame", "frames") + " at " + rig::printfNumber("%g", o.fps) + " fps";
  return in;
}

// A baked shot (rig/io/gltf_shot.h): its own pairs and frames, on --scene's ground.
CheckInput shotInput(const CheckOptions& o, std::unique_ptr<rig::GltfShot> shot) {
  if (!o.mapping.empty() || !o.reference.empty())
    throw rig::InputError("check: --mapping and --reference apply to a horse clip, and " + o.input + " is a baked shot");
  CheckInput in;
  in.kind = CheckInput::Kind::Shot;
  in.source = o.input;
  in.name = fs::path(o.input).stem().string();
  // The ground: --scene's terrain where it is given, else the file's own ground mesh, else flat.
  std::string ground;
  if (!o.scene.empty()) {
    in.scene = scene::loadScene(o.scene, {true});
    in.terrain = in.scene.terrain.get();
    in.ground = "scene";
    ground = "ground: " + o.scene + "'s " + (in.terrain && !in.terrain->flat() ? "terrain" : "flat ground");
  } else if (const std::shared_ptr<const rig::TerrainMesh> mesh = shot->ground()) {
    in.file_ground = std::make_shared<const rig::Terrain>(rig::Terrain::mesh(mesh));
    in.terrain = in.file_ground.get();
    in.ground = "file";
    ground = "ground: the file's ground mesh (" + plural(mesh->triangleCount(), "triangle", "triangles") + ")";
  } else {
    ground = "ground: flat (the file has no ground mesh: a node named \"ground\")";
  }
  in.frames = "1-" + std::to_string(shot->frameCount());
  std::string names;
  for (const rig::GltfShot::Pair& p : shot->pairs())
    names += (names.empty() ? "" : ", ") + (p.name.empty() ? p.horse_armature + " and " + p.rider_armature : p.name);
  in.described = "a baked shot: " + plural(shot->pairs().size(), "pair", "pairs") + " (" + names + "), " +
                 plural(std::size_t(shot->frameCount()), "frame", "frames") + " at " + rig::printfNumber("%g", shot->fps()) + " fps" +
                 (shot->animationName().empty() ? ", no animation" : ", animation \"" + shot->animationName() + "\"");
  for (const std::string& other : shot->leftOut()) in.described += " (\"" + other + "\" left out: it keys the same joints; --animation picks it)";
  in.described += "; " + ground;
  in.shot = std::move(shot);
  return in;
}

CheckInput loadCheckInput(const CheckOptions& o) {
  if (scene::isGltfFile(o.input)) {
    if (!fs::exists(o.input)) throw rig::InputError(o.input + ": no such file");
    rig::GltfShotOptions so;
    so.fps = o.fps;
    so.animation = o.animation;
    if (std::unique_ptr<rig::GltfShot> shot = rig::GltfShot::read(o.input, so)) return shotInput(o, std::move(shot));
    if (!o.scene.empty() || !o.profile.empty())
      throw rig::InputError("check: --scene and --profile apply to a baked shot, and " + o.input + " is a horse clip (no armatures \"horse\" and \"rider\")");
    return clipScene(o);
  }
  if (!o.mapping.empty() || !o.animation.empty() || !o.reference.empty())
    throw rig::InputError("check: --mapping, --animation and --reference apply to a glTF clip, not to the scene " + o.input);
  if (!o.scene.empty() || !o.profile.empty()) throw rig::InputError("check: --scene and --profile apply to a baked shot, not to the scene " + o.input);
  CheckInput in;
  // Loaded whatever its limits: check reports them frame by frame.
  in.scene = scene::loadScene(o.input, {true});
  in.source = in.scene.file.string();
  in.name = in.scene.name;
  in.frames = in.scene.frames;
  in.terrain = in.scene.terrain.get();
  if (in.terrain && !in.terrain->flat()) in.ground = "scene";
  const std::size_t pairs = in.scene.pairs.empty() ? 1 : in.scene.pairs.size();
  in.described = "a scene: " + plural(pairs, "pair", "pairs");
  return in;
}

// The pairs to check: the scene's one pair, or a crowd's (all, or those --pairs lists).
std::vector<CheckedPair> checkedPairs(const CheckInput& in, const CheckOptions& o, scene::ShotEvaluator& shot) {
  const scene::SceneSpec& scene = in.scene;
  if (scene.pairs.empty() && !o.pairs.empty())
    throw rig::InputError("--pairs: expected a crowd scene, " + in.source + " has one horse and rider");
  std::vector<int> chosen;
  if (o.pairs.empty()) {
    for (int i = 0; i < shot.pairCount(); ++i) chosen.push_back(i);
  } else {
    for (const int i : scene::parseFrameList(o.pairs, "--pairs")) {
      if (i < 0 || i >= shot.pairCount())
        throw rig::InputError("--pairs: expected pair indices from 0 to " + std::to_string(shot.pairCount() - 1) + ", got " + std::to_string(i));
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
    if (all.size() == 1 && all[0].name.empty()) throw rig::InputError("--pairs: expected a crowd's shot, " + in.source + " has one horse and rider");
    chosen = scene::parseFrameList(o.pairs, "--pairs");
    for (const int i : chosen)
      if (std::none_of(all.begin(), all.end(), [i](const rig::GltfShot::Pair& p) { return p.index == i; }))
        throw rig::InputError("--pairs: " + in.source + " has no pair " + std::to_string(i) + " (expected the NN of its pairNN_horse armatures)");
  }
  std::map<std::string, rig::RigProfile> resolved;  // by profile name: each resolved once
  const auto profileNamed = [&](const std::string& name, bool from_scene) -> const rig::RigProfile& {
    auto it = resolved.find(name);
    if (it != resolved.end()) return it->second;
    scene::SceneSpec named = in.scene;
    named.profile = name;
    return resolved.emplace(name, from_scene ? scene::resolveProfile(named) : scene::resolveProfile(name)).first->second;
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

// Limits along a scene's paths (a crowd: each pair's) at each frame within half a frame; a glTF clip's
// own travel (it has no path). A baked shot has neither.
void addLimitFindings(const CheckInput& in, const std::vector<int>& frames, std::vector<CheckedPair>& pairs) {
  if (in.kind == CheckInput::Kind::Shot) return;
  const scene::SceneSpec& scene = in.scene;
  const double half = 0.5 / scene.fps;
  std::vector<rig::CheckFinding> limit_findings;
  for (std::size_t k = 0; k < scene.limits.size(); ++k) {
    const scene::SceneSpec::PathLimits& l = scene.limits[k];
    const int pair = l.pair;
    for (int frame : frames) {
      const double t = scene::frameTime(scene, frame);
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
      const double t = scene::frameTime(scene, frame);
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
  if (!ref) throw rig::InputError("check: --reference: expected walk, trot, canter, gallop, stop, jump, rear or buck, got \"" + o.reference + "\"");
  rig::ClipInfoOptions io;
  io.fps = in.scene.fps;
  const rig::ClipInfo info = rig::measureClip(*pairs[0].clip, io);
  for (const rig::Verdict& v : rig::clipVerdicts(info, *ref)) {
    if (v.ok) continue;
    pairs[0].findings.push_back({0, 0, 0, rig::CheckSeverity::Warning, "gait", v.key, v.value, v.range.hi,
                                 v.key + " " + rig::printfNumber("%.4g", v.value) + " outside the " + o.reference + " reference's " + rig::printfNumber("%.4g", v.range.lo) +
                                     "-" + rig::printfNumber("%.4g", v.range.hi) + (v.note.empty() ? "" : " (" + v.note + ")")});
  }
  return rig::clipInfoJson(info, &*ref);
}


void check(const CheckOptions& o) {
  const CheckInput in = loadCheckInput(o);
  const std::vector<int> frames = scene::parseFrameList(o.frames.empty() ? in.frames : o.frames, "--frames");
  if (!o.html.empty() && fs::exists(o.html) && !fs::is_directory(o.html))
    throw rig::InputError("--html: expected a folder, " + o.html + " is a file");
  const rig::Terrain* terrain = in.terrain;
  const rig::PairCheck::GroundHeight ground = [terrain](double x, double z) { return terrain ? terrain->height(x, z) : 0.0; };

  std::unique_ptr<scene::ShotEvaluator> evaluator;  // a scene's or clip's pairs point into it
  std::vector<CheckedPair> pairs;
  PoseAt poseAt;
  if (in.kind == CheckInput::Kind::Shot) {
    const int last = in.shot->frameCount();
    for (const int f : frames)
      if (f < 1 || f > last) throw rig::InputError("--frames: " + in.source + " keys frames 1-" + std::to_string(last) + ", got " + std::to_string(f));
    pairs = shotPairs(in, o);
    const double fps = in.shot->fps();
    poseAt = [&in, fps](const CheckedPair& p, int frame) {
      rig::HorseFrame keyed;  // no clip: only the hooves the bake slides on purpose
      keyed.hoof_sliding = in.shot->hoofSliding(p.slot, frame);
      return PosedFrame{(frame - 1) / fps, keyed, in.shot->pose(p.slot, frame)};
    };
  } else {
    evaluator = std::make_unique<scene::ShotEvaluator>(in.scene, scene::resolveProfile(in.scene), 0);
    pairs = checkedPairs(in, o, *evaluator);
    poseAt = [&](const CheckedPair& p, int frame) {
      const double t = scene::frameTime(in.scene, frame);
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
  if (!o.junit.empty()) rig::writeFileAtomically(o.junit, junitXml(in, pairs, frames));
  if (!o.html.empty()) writeHtml(in, pairs, frames, o.html, counts);
  if (counts.status() != 0) throw ExitStatus{counts.status()};
}

// An input that cannot be checked (bad input) exits 3, apart from the findings' 0-2.
void runCheck(const CheckOptions& o) {
  try {
    check(o);
  } catch (const rig::InputError& e) {
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
