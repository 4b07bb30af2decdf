// Blender 3.4 run headless by the tests, on a Python script the test writes: the lines every such script
// starts with, and the run. The tests that use it are skipped where `blender` is not installed.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/blender_fixture.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {

// What a script starts with: Debian's numpy 1.24 with Blender 3.4's importer (which still uses the
// removed alias np.bool), the script's own arguments (those after "--") in `args`, and
// import_glb(path), which empties the scene and imports a glTF file as Blender's importer does.
constexpr const char* kBlenderScriptStart = R"(
import json, sys
import numpy as np
np.bool = bool
import bpy
args = sys.argv[sys.argv.index("--") + 1:]
def import_glb(path):
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    bpy.ops.import_scene.gltf(filepath=path)
)";

// Writes kBlenderScriptStart + `body` to `script` and runs it in Blender (factory settings, a Python
// error failing the run with exit status 3) with `args` (already quoted) after "--".
inline CommandResult runBlenderScript(const std::filesystem::path& script, const std::string& body, const std::string& args) {
  std::ofstream(script) << kBlenderScriptStart << body;
  return runCommand("blender -b --factory-startup --python-exit-code 3 --python " + quote(script.string()) + " -- " + args);
}

}  // namespace stirrup::test
