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

#include "cli/commands.h"
#include "render/review/spine_plot.h"
#include "rig/curve_spine.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "rig/io/spine_json.h"

namespace stirrup::cli {
namespace {

struct SpineOptions {
  std::string input;
  std::string output;
  std::string plot;
};

void runSpine(const SpineOptions& o) {
  namespace fs = std::filesystem;
  const rig::SpineFile spine = rig::readSpineFile(o.input);
  const rig::CurveSpine rig(spine.bones, spine.segments, spine.layout);
  std::vector<rig::SpineResult> results;
  nlohmann::json out;
  out["bones"] = spine.bones;
  out["segments"] = spine.segments;
  out["poses"] = nlohmann::json::array();
  for (const rig::SpinePose& p : spine.poses) {
    results.push_back(rig.solve(p.controllers, p.stretch));
    out["poses"].push_back(rig::spineResultToJson(results.back(), p.stretch));
  }

  if (o.output.empty()) {
    std::cout << out.dump(2) << '\n';
  } else {
    rig::writeFileAtomically(o.output, out.dump(2) + "\n");
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
      "Example: stirrup spine scenes/spine/demo.json --plot docs/images/curve-spine.png");
  cmd->add_option("input", opts->input, "Spine poses (JSON), e.g. scenes/spine/demo.json")->required();
  cmd->add_option("-o,--output", opts->output, "Write the result JSON here (default: standard output)");
  cmd->add_option("--plot", opts->plot, "Draw every pose into this image (PNG)");
  cmd->callback([opts] { runSpine(*opts); });
}

}  // namespace stirrup::cli
