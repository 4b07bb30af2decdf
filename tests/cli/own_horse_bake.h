// A user's horse baked whole: Blender's Rigify horse as tests/cli/own_horse_test.cpp has it (the metarig,
// every bone, its body skinned by Blender, its walk keyed; made once a run by tests/blender/rigify-horse
// with the same command, so the folder is shared), mapped by itself, ridden by the default rider and baked
// with `stirrup bake` (frames 1-24): a horse without tack of its own, which the rig saddles, bridles and
// reins. Skipped by the caller where Blender is not installed.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/blender_fixture.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {

struct OwnHorseBake {
  std::filesystem::path horse;  // the Rigify horse's file
  std::filesystem::path baked;  // the bake; empty when it could not be made (`why` says why)
  std::string why;
};

// The bake in `dir` (a test's own folder).
inline OwnHorseBake bakeOwnHorse(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  OwnHorseBake out;
  const fs::path script = STIRRUP_SOURCE_DIR "/tests/blender/rigify-horse";
  const fs::path made = fs::path(STIRRUP_BINARY_DIR) / "test_own_horse" / "metarig";
  const BlenderMade m = madeByBlender(made, script, quote(script.string()) + " " + quote((made / "horse.glb").string()) +
                                                        " --form metarig --bones all --walk --expected " + quote((made / "blender.json").string()));
  if (!m.ok) return out.why = "tests/blender/rigify-horse failed: " + m.log, out;
  out.horse = made / "horse.glb";
  const nlohmann::json scene = {{"name", "own_walk"},
                                {"output", (dir / "out").string()},
                                {"frames", "1-24"},
                                {"characters", {{"horse", out.horse.string()}, {"rider", "default"}}},
                                {"clip", {{"file", out.horse.string()}, {"animation", "Walk"}}},
                                {"cameras", {{{"name", "side"}, {"view", "side"}}}}};
  std::ofstream(dir / "scene.json") << scene.dump(2);
  const CommandResult bake = runStirrup("bake " + quote((dir / "scene.json").string()) + " -o " + quote((dir / "baked.glb").string()));
  if (bake.exit_code != 0) return out.why = "stirrup bake failed: " + bake.err, out;
  out.baked = dir / "baked.glb";
  return out;
}

}  // namespace stirrup::test
