// What the Blender add-on's tests share (tests/cli/blender_addon_test.cpp on imported characters,
// tests/cli/blender_rigify_ride_test.cpp on Rigify's generated rigs): the add-on enabled from the build
// tree as Blender finds it (BLENDER_USER_SCRIPTS=build/blender, which holds addons/stirrup_blender) with
// the program beside it (build/bin/stirrup, PATH holding no other), a script run headless or in a window
// under xvfb-run, its result.json read back, and the command line's bake as the oracle for Ride.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/io/character_mapping_json.h"
#include "rig/mapping/character_mapping.h"
#include "tests/blender_fixture.h"
#include "tests/cli/baked_file.h"
#include "tests/cli/blender_script.h"
#include "tests/cli/run_command.h"

namespace stirrup::test {

inline std::filesystem::path addonTestDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(STIRRUP_BINARY_DIR) / "test_blender_addon" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// What every add-on script starts with after kBlenderScriptStart: the add-on enabled, the program it
// found, and helpers. args[0] is the test's folder.
constexpr const char* kAddonEnable = R"(
import math, os, time
import addon_utils
from mathutils import Matrix, Vector
out = args[0]
mod = addon_utils.enable("stirrup_blender", default_set=True)
assert mod is not None and hasattr(bpy.types.Scene, "stirrup"), "the add-on did not enable"
from stirrup_blender import live, program, review
result = {"addon": mod.__file__, "program": program.find_program()}
scene = bpy.context.scene
s = scene.stirrup
s.work_dir = os.path.join(out, "work")

def heads(arm):
    """Every deform bone's head in Blender's world, metres, at the current frame."""
    bpy.context.view_layer.update()
    return {b.name: arm.matrix_world @ b.head for b in arm.pose.bones if b.bone.use_deform}

def gltf(v):  # Blender's world to glTF's (+Y up)
    return [v.x, v.z, -v.y]

def worst_cm(a, b):
    return max((a[n] - b[n]).length for n in a) * 100.0

def attempt(op, **kw):
    """An operator run as a script runs it: Blender turns an error report into RuntimeError."""
    try:
        return {"ok": sorted(op(**kw))}
    except RuntimeError as e:
        return {"error": str(e).strip()}

def export(arm, path, animations):
    """The test's own export of a character as it stands (Blender's exporter, deform bones)."""
    bpy.ops.object.select_all(action="DESELECT")
    for o in [arm] + [c for c in arm.children if c.type == "MESH"]:
        o.select_set(True)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.export_scene.gltf(filepath=path, export_format="GLB", use_selection=True, export_def_bones=True,
                              export_animations=animations, export_force_sampling=True, export_anim_single_armature=False)

def keyed(arm, first=1, last=48):
    """Her deform joints in glTF's world at every frame, as Blender shows them: frame -> joint -> xyz."""
    frames = {}
    for f in range(first, last + 1):
        scene.frame_set(f)
        frames[str(f)] = {n: gltf(p) for n, p in heads(arm).items()}
    return frames

def ride_layer(arm):
    """The ride's NLA track as Blender holds it: its place among her tracks and its strip's action."""
    ad = arm.animation_data
    if ad is None:
        return {}
    names = [t.name for t in ad.nla_tracks]
    t = ad.nla_tracks.get("stirrup ride")
    return {"tracks": names, "action": t.strips[0].action.name if t is not None and len(t.strips) else "",
            "active": ad.action.name if ad.action else "", "blend": ad.action_blend_type}

def done():
    json.dump(result, open(os.path.join(out, "result.json"), "w"), indent=1)

def finish():  # a windowed run's end (its script returns to Blender's event loop, which timers then drive)
    done()
    bpy.ops.wm.quit_blender()
)";

struct AddonRun {
  CommandResult command;
  nlohmann::json result;
};

// Runs kBlenderScriptStart + kAddonEnable + body in Blender (opening `blend` first when given) with the
// add-on found from the build tree and the program beside it, `args` after the test's folder, and reads
// its result.json. With `windowed`, Blender runs in a window under xvfb-run and the body ends the run
// itself (finish()), within 5 minutes.
inline AddonRun runAddon(const std::filesystem::path& dir, const std::string& body, const std::string& args,
                         const std::filesystem::path& blend = {}, bool windowed = false) {
  AddonRun run;
  const std::filesystem::path script = dir / "script.py";
  std::ofstream(script) << kBlenderScriptStart << kAddonEnable << body << (windowed ? "" : "\ndone()\n");
  const std::string env = "env BLENDER_USER_SCRIPTS=" + quote(STIRRUP_BINARY_DIR "/blender") + " PATH=/usr/bin:/bin ";
  const std::string blender = windowed ? "timeout 300 xvfb-run -a -s '-screen 0 1280x800x24' blender" : "blender -b";
  const std::string file = blend.empty() ? std::string() : std::string(" ") + quote(blend.string());
  run.command = runCommand(env + blender + file + " --factory-startup --python-exit-code 3 --python " + quote(script.string()) + " -- " +
                           quote(dir.string()) + " " + args + " 2>&1");
  if (std::filesystem::exists(dir / "result.json")) run.result = nlohmann::json::parse(readText(dir / "result.json"));
  return run;
}

#define SKIP_WITHOUT_BLENDER() \
  if (!blenderInstalled()) GTEST_SKIP() << "blender is not installed (apt-get install blender python3-numpy)"

#define ASSERT_RAN(run)                                                            \
  ASSERT_EQ((run).command.exit_code, 0) << (run).command.out << (run).command.err; \
  ASSERT_TRUE((run).result.is_object()) << (run).command.out

// The Rigify human of the rider's .blend (args[1]) linked into the opened scene of the generated horse, beside it.
inline constexpr const char* kRiderBesideTheHorse = R"(
with bpy.data.libraries.load(args[1]) as (src, dst):
    dst.objects = [n for n in src.objects if n in ("rider", "rider body")]
for o in dst.objects:
    scene.collection.objects.link(o)
rider, horse = bpy.data.objects["rider"], bpy.data.objects["horse"]
rider.location = (3.0, 0.0, 0.0)
)";

// Each case of `tried` (what the script attempted: case -> {"error": text}) failed with an error that
// says `says[case]`, on one line.
inline void expectOneLineErrors(const nlohmann::json& tried, const std::map<std::string, std::string>& says) {
  for (const auto& [what, text] : says) {
    ASSERT_TRUE(tried.contains(what)) << what;
    ASSERT_TRUE(tried[what].contains("error")) << what << ": " << tried[what];
    const std::string said = tried[what]["error"].get<std::string>();
    EXPECT_NE(said.find(text), std::string::npos) << what << ": " << said;
    EXPECT_EQ(said.find('\n'), std::string::npos) << what << ": one line, got " << said;
  }
}

// Where `stirrup bake --rider-only` puts her joints, in the horse's file's world (Blender's, glTF axes,
// metres) at each key: her file's joints (rider-only keeps her file's space) taken to stirrup's world by
// her mapping and back to the horse's file by the horse's. The characters are mapped by `character map`
// here, in `dir`.
inline std::map<std::string, std::vector<glm::dvec3>> bakedRider(const std::filesystem::path& dir, const std::filesystem::path& horse_glb,
                                                                 const std::filesystem::path& rider_glb) {
  const std::string horse = horse_glb.string(), rider = rider_glb.string();
  const std::string horse_map = (dir / "horse_t-map.json").string(), rider_map = (dir / "rider_t-map.json").string();
  EXPECT_EQ(runStirrup("character map " + quote(horse) + " --as horse -o " + quote(horse_map)).exit_code, 0);
  EXPECT_EQ(runStirrup("character map " + quote(rider) + " --as rider -o " + quote(rider_map)).exit_code, 0);
  const nlohmann::json scene = {{"name", "oracle"},
                                {"output", (dir / "out").string()},
                                {"characters", {{"horse", {{"file", horse}, {"mapping", horse_map}}}, {"rider", {{"file", rider}, {"mapping", rider_map}}}}},
                                {"clip", {{"file", horse}, {"mapping", horse_map}}}};
  std::ofstream(dir / "oracle.json") << scene.dump(2);
  const CommandResult bake = runStirrup("bake " + quote((dir / "oracle.json").string()) + " --rider-only -o " + quote((dir / "oracle.glb").string()));
  EXPECT_EQ(bake.exit_code, 0) << bake.err;
  const glm::dmat4 h = rig::mappingToRig(rig::loadCharacterMapping(horse_map, rig::CharacterKind::Horse));
  const glm::dmat4 r = rig::mappingToRig(rig::loadCharacterMapping(rider_map, rig::CharacterKind::Rider));
  const glm::dmat4 to_horse_file = glm::inverse(h) * r;
  tinygltf::Model model;
  tinygltf::TinyGLTF io;
  std::string err, warn;
  std::map<std::string, std::vector<glm::dvec3>> out;
  if (!io.LoadBinaryFromFile(&model, &err, &warn, (dir / "oracle.glb").string())) {
    ADD_FAILURE() << err;
    return out;
  }
  const AnimatedNodes nodes(model);
  for (const int j : model.skins.at(0).joints)
    for (std::size_t key = 0; key < nodes.times.size(); ++key)
      out[model.nodes[std::size_t(j)].name].push_back(glm::dvec3(to_horse_file * nodes.world(j, key)[3]));
  return out;
}

// The worst distance (cm) between her joints as Blender shows them (keyed: frame -> joint -> glTF
// position) and as the command line bakes them, Blender's frame F the bake's key F - first; `compared`
// counts the joints compared, `where` names the worst.
inline double worstAgainstBake(const nlohmann::json& keyed, const std::map<std::string, std::vector<glm::dvec3>>& baked, std::size_t* compared,
                               std::string* where, int first = 1) {
  double worst = 0.0;
  *compared = 0;
  for (const auto& [frame, joints] : keyed.items())
    for (const auto& [name, p] : joints.items()) {
      const auto it = baked.find(name);
      if (it == baked.end()) continue;
      const int key = std::stoi(frame) - first;
      if (key < 0 || std::size_t(key) >= it->second.size()) continue;
      const double d = glm::length(glm::dvec3(p[0], p[1], p[2]) - it->second[std::size_t(key)]) * 100.0;
      if (d > worst) worst = d, *where = name + " at frame " + frame;
      ++*compared;
    }
  return worst;
}

}  // namespace stirrup::test
