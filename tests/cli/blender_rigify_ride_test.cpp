// Ride on the rigs Blender animators use (docs/blender.md, "Riding a Rigify rig"): Rigify's generated human
// (tests/blender/rigify-rider --blend: 700-odd bones, her DEF- bones driven by constraints from her
// controls, her body skinned to them) standing 3 m beside Rigify's generated horse (tests/blender/rigify-
// horse --form generated --rigify-stretch: its walk keyed on its leg IK controls, or on its FK controls),
// both as Blender holds them in a .blend, the add-on enabled from the build tree. What is measured is what
// Blender shows: her DEF- bones evaluated with every constraint, against the command line's bake of the
// same characters. Skipped, with a message, where `blender` is not installed.
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/cli/blender_addon_support.h"

namespace stirrup::test {
namespace {

namespace fs = std::filesystem;

constexpr double kRideCm = 0.5;  // the issue's bar: what Blender shows within 0.5 cm of the command line's bake
constexpr int kFrames = 48;      // the horses' walk: two strides at 24 fps, Blender frames 1-48

// After kAddonEnable, in the horse's .blend: the rider appended from hers, standing 3 m beside the horse,
// both chosen. args: OUT_DIR RIDER.blend.
const std::string kRigifyScene = std::string(kRiderBesideTheHorse) + R"(
from mathutils import Quaternion
body = bpy.data.objects["rider body"]
scene.frame_start, scene.frame_end = 1, 48
s.horse, s.rider = horse, rider

def ride_action(arm):
    return arm.animation_data.nla_tracks["stirrup ride"].strips[0].action

def keyed_bones(action):
    return sorted({fc.data_path.split('"')[1] for fc in action.fcurves})

def switches(action):
    return {fc.data_path.split('"')[1]: [k.co[1] for k in fc.keyframe_points] for fc in action.fcurves if "IK_FK" in fc.data_path}

def horse_export_cm():
    """The worst distance (cm) between the horse's joints in the file the add-on exported for the ride and
    the horse's DEF- bones as Blender shows them, at every key."""
    from stirrup_blender import gltf_files
    g = gltf_files.Glb(os.path.join(out, "work", "horse.glb"))
    times, worlds = gltf_files.keyed_worlds(g)
    worst = 0.0
    for k, t in enumerate(times):
        scene.frame_set(int(round(t * scene.render.fps)))
        bpy.context.view_layer.update()
        for i, n in enumerate(g.json["nodes"]):
            pb = horse.pose.bones.get(n.get("name", ""))
            if pb is not None and pb.bone.use_deform:
                p = gltf(horse.matrix_world @ pb.head)
                worst = max(worst, math.dist(p, worlds[i][k, :3, 3]) * 100.0)
    return worst

def nod(frame):
    """Her own key over the ride: a 30 degree nod on the head control at `frame` (inserted as Blender inserts
    a key over an NLA stack, the nod relative to the ride)."""
    scene.frame_set(frame)
    head = rider.pose.bones["head"]
    head.rotation_quaternion = head.rotation_quaternion @ Quaternion((1.0, 0.0, 0.0), math.radians(30.0))
    head.keyframe_insert("rotation_quaternion", frame=frame)
)";

// The fixtures, made once for every test process: the horses' folder and her .blend.
struct RigifyFixtures {
  fs::path horses, rider;
  std::string failed;
};

RigifyFixtures rigifyFixtures() {
  RigifyFixtures f;
  BlenderMade horses, rider;
  f.horses = blenderRigifyHorses(&horses);
  f.rider = blenderRigifyRiderBlend(&rider);
  if (!horses.ok || !rider.ok) f.failed = "making the fixtures failed: " + horses.log + rider.log;
  return f;
}

AddonRun rideRigify(const fs::path& dir, const std::string& horse, const std::string& body) {
  const RigifyFixtures f = rigifyFixtures();
  if (!f.failed.empty()) {
    AddonRun run;
    run.command.err = f.failed;
    return run;
  }
  return runAddon(dir, std::string(kRigifyScene) + body, quote(f.rider.string()), f.horses / (horse + ".blend"));
}

// Her joints as Blender showed them (result["keyed"]) against the command line's bake of the horse as the
// add-on exported it (checked against Blender on its own) and her as the test exported her.
double worstAgainstTheBake(const fs::path& dir, const nlohmann::json& keyed, std::string* where) {
  std::size_t compared = 0;
  const double worst = worstAgainstBake(keyed, bakedRider(dir, dir / "work" / "horse.glb", dir / "rider_t.glb"), &compared, where);
  EXPECT_GT(compared, std::size_t(kFrames) * 150u) << "her 160 deform joints at every frame";
  return worst;
}

void expectOnlyControls(const nlohmann::json& bones) {
  for (const nlohmann::json& b : bones) {
    const std::string name = b.get<std::string>();
    for (const char* mechanism : {"DEF-", "ORG-", "MCH-"}) EXPECT_NE(name.rfind(mechanism, 0), 0u) << name << " is not a control";
  }
}

bool has(const nlohmann::json& list, const char* name) {
  for (const nlohmann::json& x : list)
    if (x == name) return true;
  return false;
}

// Ride in IK (the default) on the horse keyed on its IK feet: her controls keyed (torso, chest, spine FK,
// neck, head, IK feet and hands, the IK bases' twist, IK_FK 0), none of her mechanism; her DEF- bones, as
// Blender evaluates them, within 0.5 cm of the command line's bake at every frame; the horse's exported
// joints where Blender shows them. The ride is an NLA track of its own below hers; her 30 degree nod keyed
// over it shows, and survives a second Ride, which replaces only its own track.
TEST(BlenderRigifyRide, IKControlsKeyedSoBlenderShowsTheBake) {
  SKIP_WITHOUT_BLENDER();
  const fs::path dir = addonTestDir("rigify-ik");
  const AddonRun run = rideRigify(dir, "ik", R"(
mine = bpy.data.actions.new("my layer")
mine.fcurves.new('pose.bones["tweak_spine.005"].location', index=0).keyframe_points.insert(1, 0.0)
rider.animation_data_create().nla_tracks.new().name = "my layer"
rider.animation_data.nla_tracks["my layer"].strips.new("my layer", 1, mine)
scene.frame_set(1)
stood = heads(rider)
result["ride"] = attempt(bpy.ops.stirrup.ride)
result["said"] = s.last_ride
result["layer"] = ride_layer(rider)
first = ride_action(rider)
result["keyed_bones"] = keyed_bones(first)
result["switches"] = switches(first)
export(rider, os.path.join(out, "rider_t.glb"), False)
result["keyed"] = keyed(rider)
scene.frame_set(1)
result["moved_from_stand_cm"] = worst_cm(heads(rider), stood)
result["horse_export_cm"] = horse_export_cm()
scene.frame_set(20)
ridden = heads(rider)
nod(20)
scene.frame_set(19); scene.frame_set(20)
nodded = heads(rider)
result["again"] = attempt(bpy.ops.stirrup.ride)
scene.frame_set(19); scene.frame_set(20)
result["nod_kept_cm"] = worst_cm(heads(rider), nodded)
result["nod_over_ride_cm"] = worst_cm(heads(rider), ridden)
result["layer_again"] = ride_layer(rider)
result["ride_actions"] = sorted(a.name for a in bpy.data.actions if a.get("stirrup_ride") and a.id_root == "OBJECT" and rider.animation_data and
                               any(st.action == a for t in rider.animation_data.nla_tracks for st in t.strips))
result["all_ride_actions"] = sorted(a.name for a in bpy.data.actions if a.get("stirrup_ride"))
# The rig's pole mode (Rigify's pole_vector switch): the knees and elbows by their poles.
rider.animation_data.action = None
for p in ("thigh_parent.L", "thigh_parent.R", "upper_arm_parent.L", "upper_arm_parent.R"):
    rider.pose.bones[p]["pole_vector"] = 1
result["poles"] = attempt(bpy.ops.stirrup.ride)
result["pole_bones"] = keyed_bones(ride_action(rider))
result["keyed_poles"] = keyed(rider)
)");
  ASSERT_RAN(run);
  const nlohmann::json& r = run.result;
  ASSERT_TRUE(r["ride"].contains("ok")) << r["ride"];
  EXPECT_NE(r["said"].get<std::string>().find("stirrup rode frames 1-48: 21 controls of Rigify's human rig (IK limbs)"), std::string::npos)
      << r["said"];
  EXPECT_EQ(r["layer"]["tracks"], nlohmann::json::parse(R"(["stirrup ride", "my layer"])")) << "the ride below her own track";
  EXPECT_EQ(r["layer"]["blend"], "COMBINE");
  expectOnlyControls(r["keyed_bones"]);
  for (const char* c : {"torso", "chest", "spine_fk.001", "neck", "head", "foot_ik.L", "foot_ik.R", "hand_ik.L", "hand_ik.R", "thigh_ik.L",
                        "upper_arm_ik.R", "toe_ik.L", "shoulder.L"})
    EXPECT_TRUE(has(r["keyed_bones"], c)) << c << " is not keyed: " << r["keyed_bones"];
  for (const char* c : {"foot_heel_ik.L", "foot_spin_ik.L", "thigh_fk.L", "f_index.01.L"}) EXPECT_FALSE(has(r["keyed_bones"], c)) << c;
  ASSERT_EQ(r["switches"].size(), 4u) << r["switches"];
  for (const auto& [bone, values] : r["switches"].items())
    for (const nlohmann::json& v : values) EXPECT_EQ(v.get<double>(), 0.0) << bone << ": IK_FK keyed IK";
  EXPECT_GT(r["moved_from_stand_cm"].get<double>(), 100.0) << "she was seated, not left standing 3 m away";
  std::string where;
  const double worst = worstAgainstTheBake(dir, r["keyed"], &where);
  EXPECT_LT(worst, kRideCm) << "cm, " << where;
  EXPECT_LT(r["horse_export_cm"].get<double>(), kRideCm) << "the horse's exported joints against what Blender shows";
  std::printf("rigify IK: worst %.3f cm (%s); horse's export %.4f cm\n", worst, where.c_str(), r["horse_export_cm"].get<double>());
  // Her layer over the ride, and a second ride under it.
  ASSERT_TRUE(r["again"].contains("ok")) << r["again"];
  EXPECT_GT(r["nod_over_ride_cm"].get<double>(), 5.0) << "her nod shows over the ride";
  EXPECT_LT(r["nod_kept_cm"].get<double>(), 0.05) << "a second ride keeps her nod where it was";
  EXPECT_EQ(r["layer_again"]["tracks"], nlohmann::json::parse(R"(["stirrup ride", "my layer"])"));
  EXPECT_NE(r["layer_again"]["active"], "") << "her nod's action";
  EXPECT_EQ(r["ride_actions"].size(), 1u) << "her ride's action in her layer: " << r["ride_actions"];
  // The first ride's actions replaced, not left behind: hers and the tack rig's (docs/blender.md, "The tack").
  EXPECT_EQ(r["all_ride_actions"].size(), 2u) << r["all_ride_actions"];
  // In pole mode the poles are keyed too, and she is where the bake puts her.
  ASSERT_TRUE(r["poles"].contains("ok")) << r["poles"];
  for (const char* c : {"thigh_ik_target.L", "thigh_ik_target.R", "upper_arm_ik_target.L", "upper_arm_ik_target.R"})
    EXPECT_TRUE(has(r["pole_bones"], c)) << c << " is not keyed: " << r["pole_bones"];
  EXPECT_TRUE(has(r["pole_bones"], "thigh_ik.L")) << "the IK base keyed for its scale";
  std::string pole_where;
  std::size_t compared = 0;
  const double pole_worst =
      worstAgainstBake(r["keyed_poles"], bakedRider(dir, dir / "work" / "horse.glb", dir / "rider_t.glb"), &compared, &pole_where);
  EXPECT_LT(pole_worst, kRideCm) << "cm, " << pole_where;
}

// Ride in FK on the horse keyed on its FK controls: her FK chains keyed (thigh, shin, foot, toe, upper arm,
// forearm, hand), IK_FK 1, no IK control; Blender shows her within 0.5 cm of the bake; the horse's exported
// joints where Blender shows them.
TEST(BlenderRigifyRide, FKControlsKeyedSoBlenderShowsTheBake) {
  SKIP_WITHOUT_BLENDER();
  const fs::path dir = addonTestDir("rigify-fk");
  const AddonRun run = rideRigify(dir, "fk", R"(
s.limbs = "FK"
result["ride"] = attempt(bpy.ops.stirrup.ride)
result["said"] = s.last_ride
action = ride_action(rider)
result["keyed_bones"] = keyed_bones(action)
result["switches"] = switches(action)
export(rider, os.path.join(out, "rider_t.glb"), False)
result["keyed"] = keyed(rider)
result["horse_export_cm"] = horse_export_cm()
)");
  ASSERT_RAN(run);
  const nlohmann::json& r = run.result;
  ASSERT_TRUE(r["ride"].contains("ok")) << r["ride"];
  EXPECT_NE(r["said"].get<std::string>().find("25 controls of Rigify's human rig (FK limbs)"), std::string::npos) << r["said"];
  expectOnlyControls(r["keyed_bones"]);
  for (const char* c : {"thigh_fk.L", "shin_fk.R", "foot_fk.L", "toe_fk.R", "upper_arm_fk.L", "forearm_fk.R", "hand_fk.L", "torso", "head"})
    EXPECT_TRUE(has(r["keyed_bones"], c)) << c << " is not keyed: " << r["keyed_bones"];
  for (const char* c : {"foot_ik.L", "hand_ik.R", "thigh_ik.L"}) EXPECT_FALSE(has(r["keyed_bones"], c)) << c;
  ASSERT_EQ(r["switches"].size(), 4u) << r["switches"];
  for (const auto& [bone, values] : r["switches"].items())
    for (const nlohmann::json& v : values) EXPECT_EQ(v.get<double>(), 1.0) << bone << ": IK_FK keyed FK";
  std::string where;
  const double worst = worstAgainstTheBake(dir, r["keyed"], &where);
  EXPECT_LT(worst, kRideCm) << "cm, " << where;
  EXPECT_LT(r["horse_export_cm"].get<double>(), kRideCm) << "the horse's exported joints against what Blender shows";
  std::printf("rigify FK: worst %.3f cm (%s); horse's export %.4f cm\n", worst, where.c_str(), r["horse_export_cm"].get<double>());
}

// Reduce keys: the same ride with its curves decimated by Blender to within 0.25 cm: far fewer keys, the
// worst joint it reports within the tolerance, and what Blender then shows within the tolerance of the
// dense ride, measured here joint by joint at every frame. Then Live on the generated rider: her controls
// posed as Ride keys them (Blender shows her where the dense ride put her), a frame change moves her; off,
// the helper armature and its constraints are gone and the ride plays again.
TEST(BlenderRigifyRide, ReducedKeysStayWithinTheirToleranceAndLivePosesHerControls) {
  SKIP_WITHOUT_BLENDER();
  const fs::path dir = addonTestDir("rigify-reduce");
  const AddonRun run = rideRigify(dir, "ik", R"(
result["dense"] = attempt(bpy.ops.stirrup.ride)
dense = keyed(rider)
result["dense_keys"] = sum(len(fc.keyframe_points) for fc in ride_action(rider).fcurves)
s.reduce_keys, s.reduce_tolerance_cm = True, 0.25
result["reduced"] = attempt(bpy.ops.stirrup.ride)
result["said"] = s.last_ride
result["keys"] = sum(len(fc.keyframe_points) for fc in ride_action(rider).fcurves)
reduced = keyed(rider)
result["against_dense_cm"] = max(math.dist(reduced[f][n], dense[f][n]) for f in dense for n in dense[f]) * 100.0
# Live
ridden = {n: Vector(p) for n, p in dense["10"].items()}
def shown():
    return {n: Vector(gltf(p)) for n, p in heads(rider).items()}
s.live = True
result["error_on"] = live.last_error()
result["on"] = live.session() is not None
scene.frame_set(20)
result["frame_change_cm"] = worst_cm(shown(), ridden)
times = []
for f in list(range(11, 20)) + [10]:
    t = time.perf_counter()
    scene.frame_set(f)
    bpy.context.view_layer.update()
    times.append(time.perf_counter() - t)
result["live_vs_ride_cm"] = worst_cm(shown(), ridden)
result["frame_ms"] = sorted(times)[len(times) // 2] * 1000.0
s.live = False
scene.frame_set(11); scene.frame_set(10)
result["after_cm"] = worst_cm(shown(), {n: Vector(p) for n, p in reduced["10"].items()})
result["left"] = [o.name for o in bpy.data.objects if o.name.startswith("stirrup solve")] + \
    [pb.name for pb in rider.pose.bones for c in pb.constraints if c.name == "stirrup solve"]
result["error"] = live.last_error()
)");
  ASSERT_RAN(run);
  const nlohmann::json& r = run.result;
  ASSERT_TRUE(r["dense"].contains("ok")) << r["dense"];
  ASSERT_TRUE(r["reduced"].contains("ok")) << r["reduced"];
  const std::string said = r["said"].get<std::string>();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(said, m, std::regex("keys reduced from (\\d+) to (\\d+), within ([0-9.]+) cm of the dense ride"))) << said;
  EXPECT_EQ(std::stoi(m[1]), r["dense_keys"].get<int>());
  EXPECT_EQ(std::stoi(m[2]), r["keys"].get<int>());
  EXPECT_LT(r["keys"].get<int>() * 3, r["dense_keys"].get<int>()) << "fewer than a third of the keys left";
  EXPECT_LE(std::stod(m[3]), 0.25) << "the worst it reports";
  EXPECT_LE(r["against_dense_cm"].get<double>(), 0.25 + 0.005) << "what Blender shows, joint by joint, against the dense ride";
  EXPECT_NEAR(r["against_dense_cm"].get<double>(), std::stod(m[3]), 0.01) << "the worst it reports is the worst there is";
  std::printf("reduce: %d keys to %d, %.3f cm from the dense ride\n", r["dense_keys"].get<int>(), r["keys"].get<int>(),
              r["against_dense_cm"].get<double>());
  // Live
  ASSERT_TRUE(r["on"].get<bool>()) << r["error_on"];
  EXPECT_GT(r["frame_change_cm"].get<double>(), 20.0) << "frame 20 is a stride away from frame 10";
  EXPECT_LT(r["live_vs_ride_cm"].get<double>(), kRideCm) << "live against the dense ride";
  EXPECT_LT(r["after_cm"].get<double>(), 0.01) << "off, the ride's layer plays again";
  EXPECT_EQ(r["left"], nlohmann::json::array());
  EXPECT_EQ(r["error"], "");
  // How fast is measured by tests/bench/blender-live-playback (docs/blender.md, "Live"), not asserted: printed.
  std::printf("live on a generated rider: a frame change in %.1f ms\n", r["frame_ms"].get<double>());
}

// Refused in one line, nothing keyed: her constraints all muted, her DEF- bones' constraints muted, the rig
// in Edit Mode, no rig_id, and a control rig that is not Rigify's with no controls named. Named in the rider
// mapping's controls (a Blender text), that rig rides. Vertices no bone weights draw a warning naming the
// mesh and the count.
TEST(BlenderRigifyRide, BadRigsAreRefusedAndOtherRigsNameTheirControls) {
  SKIP_WITHOUT_BLENDER();
  const fs::path dir = addonTestDir("rigify-bad");
  const AddonRun run = rideRigify(dir, "ik", R"(
tried = {}
cons = [c for pb in rider.pose.bones for c in pb.constraints]
for c in cons: c.mute = True
tried["all muted"] = attempt(bpy.ops.stirrup.ride)
for c in cons: c.mute = False
deform_cons = [c for pb in rider.pose.bones if pb.bone.use_deform for c in pb.constraints]
for c in deform_cons: c.mute = True
tried["deform muted"] = attempt(bpy.ops.stirrup.ride)
for c in deform_cons: c.mute = False
bpy.context.view_layer.objects.active = rider
bpy.ops.object.mode_set(mode="EDIT")
tried["edit mode"] = attempt(bpy.ops.stirrup.ride)
bpy.ops.object.mode_set(mode="OBJECT")
rig_id = rider.data["rig_id"]
del rider.data["rig_id"]
tried["no rig_id"] = attempt(bpy.ops.stirrup.ride)
rider.data["rig_id"] = rig_id
walk = horse.animation_data.action
horse.animation_data.action = None
tried["horse without action"] = attempt(bpy.ops.stirrup.ride)
horse.animation_data.action = walk
del rider.data["rig_id"]
bpy.ops.object.mode_set(mode="EDIT")
rider.data.edit_bones["torso"].name = "body"
bpy.ops.object.mode_set(mode="OBJECT")
tried["not rigify"] = attempt(bpy.ops.stirrup.ride)
result["tried"] = tried
result["untouched"] = rider.animation_data is None or len(rider.animation_data.nla_tracks) == 0
# The same rig's controls named by hand, as a TD names a rig of her own.
follow = {"body": "DEF-spine", "hips": "DEF-spine", "chest": "DEF-spine.003", "spine_fk": "DEF-spine",
          "spine_fk.001": "DEF-spine.001", "spine_fk.002": "DEF-spine.002", "spine_fk.003": "DEF-spine.003",
          "neck": "DEF-spine.004", "head": "DEF-spine.006"}
twist, switch = {}, {}
for sd in ("L", "R"):
    follow.update({"shoulder." + sd: "DEF-shoulder." + sd, "foot_ik." + sd: "DEF-foot." + sd, "toe_ik." + sd: "DEF-toe." + sd,
                   "hand_ik." + sd: "DEF-hand." + sd})
    twist["thigh_ik." + sd] = ["DEF-thigh." + sd, "DEF-shin." + sd, "DEF-foot." + sd]
    twist["upper_arm_ik." + sd] = ["DEF-upper_arm." + sd, "DEF-forearm." + sd, "DEF-hand." + sd]
    switch['thigh_parent.%s["IK_FK"]' % sd] = 0.0
    switch['upper_arm_parent.%s["IK_FK"]' % sd] = 0.0
text = bpy.data.texts.new("rider controls")
text.write(json.dumps({"follow": follow, "twist": twist, "set": switch}))
s.rider_map.controls_text = text.name
import bmesh
bm = bmesh.new()
bm.from_mesh(body.data)
for k in range(7):
    bm.verts.new((0.02 * k, 0.0, 2.5))
bm.to_mesh(body.data)
bm.free()
result["named"] = attempt(bpy.ops.stirrup.ride)
result["said"] = s.last_ride
export(rider, os.path.join(out, "rider_t.glb"), False)
result["keyed"] = keyed(rider)
)");
  ASSERT_RAN(run);
  const nlohmann::json& tried = run.result["tried"];
  const std::map<std::string, std::string> says = {
      {"all muted", "is a Rigify rig with every constraint muted"},
      {"deform muted", "whose deform bones' constraints are muted (DEF-"},
      {"edit mode", "is in Edit Mode"},
      {"no rig_id", "but no rig_id"},
      {"not rigify", "has deform bones driven by constraints Ride cannot key through (DEF-"},
      {"horse without action", "has no action, and constraints drive its deform bones"},
  };
  expectOneLineErrors(tried, says);
  EXPECT_TRUE(run.result["untouched"].get<bool>()) << "a refused ride keys nothing";
  ASSERT_TRUE(run.result["named"].contains("ok")) << run.result["named"];
  const std::string said = run.result["said"].get<std::string>();
  EXPECT_NE(said.find("controls of her rig (named in the rider mapping)"), std::string::npos) << said;
  EXPECT_NE(said.find("warning: 7 vertices of rider body carry no bone weight"), std::string::npos) << said;
  std::string where;
  EXPECT_LT(worstAgainstTheBake(dir, run.result["keyed"], &where), kRideCm) << where;
}

}  // namespace
}  // namespace stirrup::test
