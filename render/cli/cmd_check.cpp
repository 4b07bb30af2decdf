// stirrup check SCENE.json [--json] [--frames LIST]: a scene's shot checked frame by frame (issue 36,
// a first part): the limits a horse has along every path of the scene (rig/motion/horse_limits.h) and
// hooves beyond their legs' reach (rig::HorseReach). Exit status 0 clean, 1 warnings, 2 failures, 3 a
// scene that cannot be checked (a one-line error on stderr).
//
// Severity. A limit broken is a failure: no horse can ride it. A planted hoof short of its target by
// HorseReach::kOverReachCm or more is a warning: it hovers over its print. A swinging hoof short of its
// target is a note (it misses a point in the air by a few centimetres at the ends of long strides in
// the shipped clips, docs/horse-limits.md), reported but not counted in the exit status.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/cli/commands.h"
#include "render/scene.h"
#include "rig/bake.h"
#include "rig/error.h"
#include "rig/io/frame_range.h"
#include "rig/io/ridden_pair.h"
#include "rig/pose.h"
#include "rig/rig_profile.h"

namespace stirrup::cli {
namespace {

struct CheckOptions {
  std::string scene;
  std::string frames;
  bool json = false;
};

constexpr const char* kLegNames[4] = {"lf", "rf", "lb", "rb"};

struct Finding {
  int frame = 0;
  double time_s = 0;
  std::string severity;  // failure, warning, note
  std::string kind;      // limit, over-reach
  std::string text;      // one line
  nlohmann::json detail;
};

void check(const CheckOptions& o) {
  const render::SceneSpec scene = render::loadScene(o.scene, {true});
  const std::string file = scene.file.string();
  const std::vector<int> frames = rig::parseFrameList(o.frames.empty() ? scene.frames : o.frames, "--frames");
  std::vector<Finding> findings;

  // Limits, per frame: each path's breaches within half a frame of the frame's time.
  const double half = 0.5 / scene.fps;
  for (int frame : frames) {
    const double t = render::frameTime(scene, frame);
    for (const render::SceneSpec::PathLimits& l : scene.limits)
      for (const rig::LimitBreach& b : l.check->during(t + l.clip_offset_s - half, t + l.clip_offset_s + half)) {
        Finding f{frame, t, "failure", "limit", "", {}};
        const std::string what = b.text.substr(b.text.find(": ") + 2);
        f.text = std::string(rig::horseLimitName(b.limit)) + " (" + l.check->clipField() + "." + b.field + ", segment " +
                 std::to_string(b.segment) + "): " + what;
        f.detail = {{"limit", rig::horseLimitName(b.limit)}, {"path", l.check->clipField()}, {"field", b.field},
                    {"segment", b.segment}, {"value", b.value}, {"bound", b.bound}};
        findings.push_back(std::move(f));
      }
  }

  // Over-reach, per frame, posed as every consumer poses the pair (a crowd's pairs are not posed here).
  const bool posed = scene.pairs.empty();
  if (posed) {
    const rig::RigProfile profile = render::resolveProfile(scene);
    const rig::RiddenPair pair = rig::resolveRiddenPair(scene.horse, scene.horse_mapping, scene.rider, scene.rider_mapping, profile);
    const std::unique_ptr<rig::Clip> clip = render::makeSceneClip(scene);
    for (int frame : frames) {
      const double t = render::frameTime(scene, frame);
      const rig::BakedFrame b = rig::bakeFrame(*clip, profile, frame, t);
      const rig::HorseReach reach = rig::poseMounted(pair.horse, pair.rider, b.horse, b.rider, profile).reach;
      for (int leg = 0; leg < 4; ++leg) {
        if (!reach.overReached(leg)) continue;
        const bool planted = reach.planted[std::size_t(leg)];
        char text[160];
        std::snprintf(text, sizeof text, "over-reach: %s hoof %s %.2f cm short of its target, its leg at full reach",
                      kLegNames[leg], planted ? "planted" : "in the air", reach.short_cm[std::size_t(leg)]);
        findings.push_back({frame, t, planted ? "warning" : "note", "over-reach", text,
                            {{"leg", kLegNames[leg]}, {"planted", planted}, {"short_cm", reach.short_cm[std::size_t(leg)]}}});
      }
    }
  }

  int failures = 0, warnings = 0, notes = 0;
  for (const Finding& f : findings) (f.severity == "failure" ? failures : f.severity == "warning" ? warnings : notes)++;
  const int status = failures ? 2 : warnings ? 1 : 0;
  if (o.json) {
    nlohmann::json j = {{"scene", file}, {"frames", frames.size()}, {"status", status}, {"failures", failures},
                        {"warnings", warnings}, {"notes", notes}, {"over_reach_checked", posed}};
    nlohmann::json paths = nlohmann::json::array();
    for (const render::SceneSpec::PathLimits& l : scene.limits) {
      nlohmann::json breaches = nlohmann::json::array();
      for (const rig::LimitBreach& b : l.check->breaches())
        breaches.push_back({{"limit", rig::horseLimitName(b.limit)}, {"field", b.field}, {"segment", b.segment},
                            {"from_s", b.time_s}, {"value", b.value}, {"bound", b.bound}, {"error", l.check->errorText(b)}});
      paths.push_back({{"path", l.check->clipField()}, {"breaches", breaches}});
    }
    j["paths"] = paths;
    nlohmann::json list = nlohmann::json::array();
    for (const Finding& f : findings) {
      nlohmann::json e = {{"frame", f.frame}, {"time_s", f.time_s}, {"severity", f.severity}, {"kind", f.kind}, {"text", f.text}};
      e.update(f.detail);
      list.push_back(e);
    }
    j["findings"] = list;
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    for (const Finding& f : findings)
      std::printf("%s: frame %d (%.3f s): %s: %s\n", file.c_str(), f.frame, f.time_s, f.severity.c_str(), f.text.c_str());
    std::printf("%s: %zu frames: %d failures, %d warnings, %d notes%s\n", file.c_str(), frames.size(), failures, warnings,
                notes, posed ? "" : " (over-reach not checked: a crowd's pairs are not posed by check yet)");
  }
  std::fflush(stdout);
  if (status != 0) throw ExitStatus{status};
}

// A scene that cannot be checked (bad input) exits 3, apart from the findings' 0-2.
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
  CLI::App* cmd = app.add_subcommand("check", "Check a scene's shot frame by frame: a horse's limits, hooves beyond reach");
  cmd->footer(
      "Failures: a path beyond a limit a horse has (docs/horse-limits.md) at that frame. Warnings: a planted hoof\n"
      "1 cm or more short of its target (its leg at full reach). Notes: a hoof in the air short of its target.\n"
      "Exit status: 0 clean, 1 warnings, 2 failures (notes do not count), 3 a scene that cannot be checked.\n"
      "Example: stirrup check scenes/trail.json --json");
  cmd->add_option("scene", opts->scene, "Scene file (JSON), e.g. scenes/trail.json")->required();
  cmd->add_option("--frames,-f", opts->frames, "Frames to check (default: the scene's frames)");
  cmd->add_flag("--json", opts->json, "Write the findings as JSON");
  cmd->callback([opts] { runCheck(*opts); });
}

}  // namespace stirrup::cli
