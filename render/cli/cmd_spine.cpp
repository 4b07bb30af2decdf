// stirrup spine IN.json: lays the curve spine (rig/curve_spine.h) for every pose of a file and writes
// the FK chain, curve, samples and chain joints as JSON, optionally with a picture of every pose.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/cli/commands.h"
#include "render/spine_plot.h"
#include "rig/curve_spine.h"
#include "rig/error.h"
#include "rig/json_fields.h"

namespace stirrup::cli {
namespace {

struct SpineOptions {
  std::string input;
  std::string output;
  std::string plot;
};

struct SpinePose {
  rig::SpineControllers controllers;
  double stretch = 1.0;
};

struct SpineFile {
  std::array<double, 3> bones{};
  int segments = rig::CurveSpine::kRiderSegments;
  rig::ChainLayout layout = rig::ChainLayout::EqualArcLength;
  std::vector<SpinePose> poses;
};

// An array of exactly N finite numbers at `path`, else one line naming the file and the field.
template <std::size_t N>
std::array<double, N> readNumbers(const std::string& file, const std::string& path, const nlohmann::json* v) {
  const auto fail = [&](const std::string& what) { throw InputError(file + ": " + path + ": " + what); };
  if (!v) fail("missing (expected " + std::to_string(N) + " numbers)");
  if (!v->is_array()) fail("expected " + std::to_string(N) + " numbers, got " + describeJson(*v));
  if (v->size() != N) fail("expected " + std::to_string(N) + " numbers, got " + std::to_string(v->size()));
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    const nlohmann::json& e = (*v)[i];
    if (!e.is_number() || !std::isfinite(e.get<double>()))
      throw InputError(file + ": " + path + "[" + std::to_string(i) + "]: expected a number, got " + describeJson(e));
    out[i] = e.get<double>();
  }
  return out;
}

glm::dvec3 toVec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

SpineFile readSpineFile(const std::string& file) {
  const nlohmann::json json = readJsonFile(file);
  JsonObjectReader top(file, "", json);
  SpineFile spine;

  spine.bones = readNumbers<3>(file, "bones", top.value("bones"));
  for (std::size_t i = 0; i < 3; ++i)
    if (!(spine.bones[i] > 0.0))
      top.fail("bones[" + std::to_string(i) + "]",
               "expected a positive length in cm, got " + describeJson(json["bones"][i]));

  if (!top.has("segments")) top.fail("segments", "missing (expected a whole number from 3 to 32)");
  const nlohmann::json& seg = json["segments"];
  if (!seg.is_number_integer() || seg.get<long long>() < rig::CurveSpine::kMinSegments ||
      seg.get<long long>() > rig::CurveSpine::kMaxSegments)
    top.fail("segments", "expected a whole number from 3 to 32, got " + describeJson(seg));
  spine.segments = top.integer("segments", rig::CurveSpine::kRiderSegments);

  const std::string layout = top.string("layout", "equal_arc_length");
  if (layout == "equal_chord") spine.layout = rig::ChainLayout::EqualChord;
  else if (layout != "equal_arc_length")
    top.fail("layout", "expected \"equal_arc_length\" or \"equal_chord\", got \"" + layout + "\"");

  const nlohmann::json* poses = top.value("poses");
  if (!poses) top.fail("poses", "missing (expected an array of poses)");
  if (!poses->is_array() || poses->empty())
    top.fail("poses", "expected a non-empty array of poses, got " + describeJson(*poses));
  for (std::size_t i = 0; i < poses->size(); ++i) {
    const std::string path = "poses[" + std::to_string(i) + "]";
    JsonObjectReader pose(file, path, (*poses)[i]);
    SpinePose p;
    p.controllers.lower = toVec(readNumbers<3>(file, path + ".lower", pose.value("lower")));
    p.controllers.middle = toVec(readNumbers<3>(file, path + ".middle", pose.value("middle")));
    p.controllers.top = toVec(readNumbers<3>(file, path + ".top", pose.value("top")));
    p.stretch = pose.number("stretch", 1.0);
    if (!(p.stretch > 0.0)) pose.fail("stretch", "expected a positive factor, got " + describeJson((*poses)[i]["stretch"]));
    pose.finish();
    spine.poses.push_back(p);
  }
  top.finish();
  return spine;
}

nlohmann::json toJson(const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

nlohmann::json toJson(const rig::SpineResult& r, double stretch) {
  nlohmann::json pose;
  pose["fk"] = nlohmann::json::array();
  for (const glm::dvec3& p : r.fk) pose["fk"].push_back(toJson(p));
  pose["curve_points"] = nlohmann::json::array();
  for (const glm::dvec3& p : r.curve_points) pose["curve_points"].push_back(toJson(p));
  pose["length"] = r.length;
  pose["stretch"] = stretch;
  pose["layout"] = r.layout == rig::ChainLayout::EqualChord ? "equal_chord" : "equal_arc_length";
  pose["bone_length"] = r.bone_length;
  pose["chain_length"] = r.chain_length;
  pose["bone_chords"] = r.bone_chords;
  pose["chain_deficit"] = r.chain_deficit;
  pose["layout_converged"] = r.layout_converged;
  pose["ten_null_length"] = r.ten_null_length;
  pose["samples"] = nlohmann::json::array();
  for (const glm::dvec3& p : r.samples) pose["samples"].push_back(toJson(p));
  pose["joints"] = nlohmann::json::array();
  for (std::size_t j = 0; j < r.joints.size(); ++j) {
    const glm::dquat& q = r.joints[j].rotation;
    pose["joints"].push_back({{"position", toJson(r.joints[j].position)},
                              {"rotation", nlohmann::json::array({q.w, q.x, q.y, q.z})},
                              {"twist", r.twist_deg[j]}});
  }
  return pose;
}

void runSpine(const SpineOptions& o) {
  namespace fs = std::filesystem;
  const SpineFile spine = readSpineFile(o.input);
  const rig::CurveSpine rig(spine.bones, spine.segments, spine.layout);
  std::vector<rig::SpineResult> results;
  nlohmann::json out;
  out["bones"] = spine.bones;
  out["segments"] = spine.segments;
  out["poses"] = nlohmann::json::array();
  for (const SpinePose& p : spine.poses) {
    results.push_back(rig.solve(p.controllers, p.stretch));
    out["poses"].push_back(toJson(results.back(), p.stretch));
  }

  if (o.output.empty()) {
    std::cout << out.dump(2) << '\n';
  } else {
    const fs::path file = o.output, tmp = o.output + ".tmp";
    if (!file.parent_path().empty()) fs::create_directories(file.parent_path());
    {
      std::ofstream f(tmp);
      if (!f) throw InputError(file.string() + ": cannot write the file");
      f << out.dump(2) << '\n';
      if (!f.flush()) throw InputError(file.string() + ": write failed");
    }
    fs::rename(tmp, file);
  }
  if (!o.plot.empty()) render::writeSpinePlot(results, o.plot);
}

}  // namespace

void addSpineCommand(CLI::App& app) {
  auto opts = std::make_shared<SpineOptions>();
  CLI::App* cmd = app.add_subcommand("spine", "Lay a curve spine from three FK spine controllers (Raisani 2004)");
  cmd->footer(
      "Input (JSON): {\"bones\": [L1, L2, L3], \"segments\": N, \"poses\": [{\"lower\": [rx, ry, rz],\n"
      "  \"middle\": [rx, ry, rz], \"top\": [rx, ry, rz], \"stretch\": s}, ...]}\n"
      "  bones: the three FK bone lengths in cm (> 0); segments: chain bones N, 3..32 (a rider uses 10);\n"
      "  lower/middle/top: controller rotations in degrees, rx twist, ry side to side, rz bend front/back;\n"
      "  stretch: optional factor (> 0, default 1) on the whole spine's length (squash and stretch);\n"
      "  layout: optional, \"equal_arc_length\" (default: bones of equal length measured along the curve,\n"
      "  the chain exactly as long as the curve) or \"equal_chord\" (equal straight bones).\n"
      "Rotation order XYZ: R = Rz(rz)·Ry(ry)·Rx(rx), twist first about the bone, then ry, then rz about\n"
      "  the parent's axes; each controller is parented under the one below. At rest the spine points\n"
      "  up (+Y), the rider faces +X, +Z is right: +rz bends forward, +ry leans right.\n"
      "Output (JSON): {\"poses\": [{\"fk\": 4 points, \"curve_points\": 5 points, \"length\": cm,\n"
      "  \"samples\": 129 points at equal arc length, \"joints\": N+1 of {\"position\": [x, y, z],\n"
      "  \"rotation\": [w, x, y, z], \"twist\": degrees}, \"bone_length\", \"chain_length\", \"bone_chords\",\n"
      "  \"chain_deficit\" (1 - sum of chords / length), ...}]}.\n"
      "  A joint's rotation maps bone axes to world: x along the bone to the next joint, y forward at rest.\n"
      "--plot draws every pose: x-y and z-y views side by side (grey FK, blue curve, orange chain).\n"
      "Example: stirrup spine scenes/spine-demo.json --plot docs/images/curve-spine.png");
  cmd->add_option("input", opts->input, "Spine poses (JSON), e.g. scenes/spine-demo.json")->required();
  cmd->add_option("-o,--output", opts->output, "Write the result JSON here (default: standard output)");
  cmd->add_option("--plot", opts->plot, "Draw every pose into this image (PNG)");
  cmd->callback([opts] { runSpine(*opts); });
}

}  // namespace stirrup::cli
