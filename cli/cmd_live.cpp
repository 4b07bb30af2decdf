// stirrup live SCENE: the rider kept on a horse another tool keys live (scene/live_rider.h), over a
// line protocol on stdin and stdout: the Blender add-on's Live toggle (docs/blender.md, "Live").
//
//   out, once:   {"ready": true, "horse_joints": [...], "rider_joints": [...], "tack_joints": [...], "first": F0,
//                 "last": F1, "fps": FPS}
//   in, a line:  {"set": [{"frame": F, "horse": [[16 numbers]...]}...], "get": F}   (either part may be left out)
//   out, a line: {"frame": F, "rider": [[16 numbers]...], "tack": [[16 numbers]...], "ms": MS}, or {"ok": true}
//                without "get", or {"error": "one line"} for a request that could not be answered (the session goes on)
//
// Matrices are deformations (a joint's world times its inverse bind) in the glTF files' space, 16 numbers
// column by column as glTF writes them; "horse" lists the horse's joints as "horse_joints" names them,
// "rider" the rider's as "rider_joints" does, "tack" the horse's tack joints (saddle, lStirrup, rStirrup,
// lRein, rRein: the stirrups at her feet, the rein ends in her hands) as "tack_joints" does, from their rest
// in the horse's file (scene/live_rider.h). The session ends at the end of stdin.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "rig/error.h"
#include "scene/frame_range.h"
#include "scene/live_rider.h"
#include "scene/profile_resolver.h"
#include "scene/ridden_pair.h"
#include "scene/scene.h"

namespace stirrup::cli {
namespace {

struct LiveOptions {
  std::string scene;
  int first = 0, last = -1;  // the tool's frames; last < first: the scene's frames
};

glm::dmat4 matrixOf(const nlohmann::json& m, const std::string& where) {
  if (!m.is_array() || m.size() != 16) throw rig::InputError(where + ": expected 16 numbers");
  glm::dmat4 out;
  for (int k = 0; k < 16; ++k) {
    if (!m[std::size_t(k)].is_number()) throw rig::InputError(where + ": expected 16 numbers");
    glm::value_ptr(out)[k] = m[std::size_t(k)].get<double>();
  }
  return out;
}

// One request answered: the frames set, then the rider at "get".
nlohmann::json answer(scene::LiveRider& live, const std::string& line) {
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json request = nlohmann::json::parse(line, nullptr, false);
  if (!request.is_object()) throw rig::InputError("expected a JSON object a line");
  if (request.contains("set")) {
    if (!request["set"].is_array()) throw rig::InputError("set: expected a list of {\"frame\": F, \"horse\": [...]}");
    for (const nlohmann::json& s : request["set"]) {
      if (!s.is_object() || !s.contains("frame") || !s["frame"].is_number_integer() || !s.contains("horse") || !s["horse"].is_array())
        throw rig::InputError("set: expected {\"frame\": F, \"horse\": [...]} entries");
      const int frame = s["frame"].get<int>();
      std::vector<glm::dmat4> horse;
      for (std::size_t k = 0; k < s["horse"].size(); ++k)
        horse.push_back(matrixOf(s["horse"][k], "set: frame " + std::to_string(frame) + ": horse[" + std::to_string(k) + "]"));
      live.setHorse(frame, horse);
    }
  }
  if (!request.contains("get")) return {{"ok", true}};
  if (!request["get"].is_number_integer()) throw rig::InputError("get: expected a frame number");
  const int frame = request["get"].get<int>();
  std::vector<glm::dmat4> tack;
  const std::vector<glm::dmat4> posed = live.rider(frame, &tack);
  const auto matrices = [](const std::vector<glm::dmat4>& list) {
    nlohmann::json out = nlohmann::json::array();
    for (const glm::dmat4& m : list) out.push_back(std::vector<double>(glm::value_ptr(m), glm::value_ptr(m) + 16));
    return out;
  };
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return {{"frame", frame}, {"rider", matrices(posed)}, {"tack", matrices(tack)}, {"ms", ms}};
}

void runLive(const LiveOptions& o) {
  const scene::SceneSpec scene = scene::loadScene(o.scene);
  std::error_code ec;
  if (scene.clip.file.empty() || scene.horse == "default" || !std::filesystem::equivalent(scene.clip.file, scene.horse, ec))
    throw rig::InputError(o.scene + ": clip.file: expected the horse's own file (" + scene.horse +
                     "): live reads the horse as the other tool keys it");
  const rig::RigProfile profile = scene::resolveProfile(scene);
  scene::RiddenPair pair = scene::resolveRiddenPair(scene.horse, scene.horse_mapping, scene.rider, scene.rider_mapping, profile);
  scene::LiveRiderSetup setup;
  setup.horse_file = scene.horse;
  setup.horse = std::make_shared<const rig::Character>(std::move(pair.horse));
  setup.rider = std::make_shared<const rig::Character>(std::move(pair.rider));
  setup.profile = profile;
  setup.fps = scene.fps;
  if (o.last >= o.first) {
    setup.first_frame = o.first, setup.last_frame = o.last;
  } else {
    const std::vector<int> frames = scene::parseFrameList(scene.frames, o.scene + ": frames");
    setup.first_frame = frames.front(), setup.last_frame = frames.back();
  }
  scene::LiveRider live(setup);
  const nlohmann::json ready = {{"ready", true},        {"horse_joints", live.horseJoints()}, {"rider_joints", live.riderJoints()},
                                {"tack_joints", live.tackJoints()}, {"first", live.firstFrame()},  {"last", live.lastFrame()},
                                {"fps", scene.fps}};
  std::cout << ready.dump() << std::endl;
  std::string line;
  while (std::getline(std::cin, line)) {
    if (line.empty()) continue;
    nlohmann::json out;
    try {
      out = answer(live, line);
    } catch (const rig::InputError& e) {
      out = {{"error", e.what()}};
    }
    std::cout << out.dump() << std::endl;
  }
}

}  // namespace

void addLiveCommand(CLI::App& app) {
  auto opts = std::make_shared<LiveOptions>();
  CLI::App* cmd = app.add_subcommand("live", "Keep the rider on a horse another tool keys live, over stdin and stdout (the Blender add-on)");
  cmd->footer(
      "The scene names the horse's own glTF file as its horse and its clip, and the rider; frames are the tool's\n"
      "(its frame F at F / fps). One JSON object a line each way: docs/blender.md, \"Live\".\n"
      "Example: stirrup live scene.json --first 1 --last 48");
  cmd->add_option("scene", opts->scene, "Scene file (JSON) naming the horse's file and mapping, its clip the same file, and the rider")->required();
  cmd->add_option("--first", opts->first, "The tool's first frame (default: the scene's first)");
  cmd->add_option("--last", opts->last, "The tool's last frame (default: the scene's last)");
  cmd->callback([opts] { runLive(*opts); });
}

}  // namespace stirrup::cli
