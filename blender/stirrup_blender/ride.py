# Ride: the rider's own bones keyed over the scene's frame range, seated on the horse in Blender's world
# as `stirrup bake --rider-only` seats her (docs/blender.md, "Ride").
#
# The rider-only file holds her motion in her own file's space (her mapping's to_rig undone, R), while
# the horse plays its own animation in stirrup's world through the horse's mapping (H): stirrup's world
# is the horse's file's world through H, and her file's through R. A deformation D of hers in her file is
# R^-1 S R (S stirrup's skin matrix); in the horse's file, where she must sit, it is H^-1 S R, so every
# one is taken there by C = H^-1 R before it poses her bones (transforms.Poser). Both files are
# Blender's exports of the scene as it stands, so the horse's file's world is Blender's (Y up).
import json
import os

import bpy
import numpy as np

from . import controls, export, gltf_files, layer, mapping, program, reduce, tack, transforms


def chosen(context):
    """The horse and rider armatures, or a StirrupError saying what is missing."""
    s = context.scene.stirrup
    for kind in mapping.KINDS:
        obj = getattr(s, kind)
        if obj is None:
            raise program.StirrupError("no %s chosen: pick the %s's armature in the Stirrup panel (scene.stirrup.%s)" % (kind, kind, kind))
        if obj.type != "ARMATURE":
            raise program.StirrupError("the %s, %s, is not an armature" % (kind, obj.name))
        if obj.mode == "EDIT":
            raise program.StirrupError("the %s, %s, is in Edit Mode: leave it (Tab) and try again" % (kind, obj.name))
        if not export.meshes_of(obj):
            raise program.StirrupError("the %s, %s, deforms no mesh (expected the armature of a skinned character: its body "
                                       "parented to it with an Armature modifier)" % (kind, obj.name))
    if s.horse == s.rider:
        raise program.StirrupError("the horse and the rider are the same armature, %s" % s.horse.name)
    return s.horse, s.rider


def fps_of(scene):
    return scene.render.fps / scene.render.fps_base


def object_at_export(path, obj):
    """The armature object's world matrix (Blender's, 4x4) as the exported file binds its skin: the file's
    armature node taken back from glTF's axes (gltf_files.armature_world)."""
    try:
        world = gltf_files.armature_world(gltf_files.Glb(path), obj.name)
    except (ValueError, OSError) as e:
        raise program.StirrupError(str(e))
    return transforms.G_INV @ world @ transforms.G


class Prepared:
    """What stirrup needs to ride the scene: the characters exported, their mappings (kept ones moved with
    the objects, or made now), the scene file, and how Blender's frames are stirrup's."""

    def __init__(self, context, work, with_horse_animation=True):
        self.context = context
        self.horse, self.rider = chosen(context)
        program.find_program(context)
        self.work = work
        self.fps = fps_of(context.scene)
        self.horse_keyed = with_horse_animation and export.has_action(self.horse)
        self.horse_glb = export.export(context, [self.horse], os.path.join(work, "horse.glb"), self.horse_keyed)
        self.rider_glb = export.export(context, [self.rider], os.path.join(work, "rider.glb"), False)
        # Where each armature object stood for its file's bind (Blender world): the file's own armature node.
        self.horse_at_export = object_at_export(self.horse_glb, self.horse)
        self.rider_at_export = object_at_export(self.rider_glb, self.rider)
        self.maps, self.new_maps = mapping.for_both(context, work, {"horse": self.horse_glb, "rider": self.rider_glb})
        self.map_files = {k: mapping.write(k, d, work) for k, d in self.maps.items()}
        # Blender's frame F is stirrup's F - first + 1: the exported animation's first key is stirrup's
        # frame 1 (Blender keys frame F at F / fps); a generated gait starts at the scene's first frame.
        start = gltf_files.Glb(self.horse_glb).start_time() if self.horse_keyed else None
        scene = context.scene
        self.first = int(round(start * self.fps)) if start is not None else scene.frame_start
        self.frames = (max(scene.frame_start, self.first), scene.frame_end)
        if self.frames[1] < self.frames[0]:
            raise program.StirrupError("the scene's frame range %d-%d ends before the horse's action starts (frame %d)" %
                                       (scene.frame_start, scene.frame_end, self.first))

    def stirrup_frames(self):
        return "%d-%d" % (self.frames[0] - self.first + 1, self.frames[1] - self.first + 1)

    def write_scene(self):
        s = self.context.scene.stirrup
        horse = {"file": self.horse_glb, "mapping": self.map_files["horse"]}
        clip = dict(horse) if self.horse_keyed else {"generator": s.gait}
        scene = {
            "name": "blender", "fps": self.fps, "frames": self.stirrup_frames(),
            "characters": {"horse": horse, "rider": {"file": self.rider_glb, "mapping": self.map_files["rider"]}},
            "clip": clip, "profile": s.profile, "profile_overrides": {"seat.stirrup_holes_up": s.stirrup_holes_up},
            "output": os.path.join(self.work, "out"),
        }
        path = os.path.join(self.work, "scene.json")
        json.dump(scene, open(path, "w"), indent=2)
        return path

    def keep_new_maps(self):
        mapping.keep_new(self.context, self.new_maps)

    def blender_frames(self, times):
        """Blender's frame of each key time of a stirrup file (seconds = (frame - 1) / fps)."""
        return [int(round(t * self.fps)) + self.first for t in times]


def file_deformations(path, to_world, armature=None):
    """Each joint's deformation at each key of a stirrup file, taken to a world by `to_world` (4x4): (key
    times, {joint: (keys, 4, 4)}), of the skin whose armature node is named `armature` (a bake's "horse"),
    or the file's only skin."""
    glb = gltf_files.Glb(path)
    times, worlds = gltf_files.keyed_worlds(glb)
    nodes = glb.json["nodes"]
    skins = glb.json["skins"]
    k = 0
    if armature is not None:
        k = [i for i, s in enumerate(skins) if nodes[s.get("skeleton", -1)].get("name") == armature][0]
    ibm = gltf_files.inverse_binds(glb, k)
    out = {}
    for j in skins[k]["joints"]:
        name = nodes[j]["name"]
        out[name] = to_world @ worlds[j] @ ibm[name]
    return times, out


def key_armature(arm, deformations, object_at_export, frames, action_name):
    """A new action for `arm` posing its bones by the deformations (glTF world) at Blender `frames`."""
    poser = transforms.Poser(arm, list(deformations), object_at_export)
    if not poser.names:
        raise program.StirrupError("%s: stirrup's file names none of its bones" % arm.name)
    bases = poser.bases(arm, poser.stack(deformations))
    action = transforms.key_action(arm, action_name, frames, poser.names, bases)
    return action, transforms.unsupported_bones(arm, poser.names)


class RiderTargets:
    """Where stirrup puts her deform bones: each one's pose matrix (armature space) at each ridden frame,
    and their heads in Blender's world, for keying and for measuring what Blender then shows."""

    def __init__(self, rider, deformations, object_at_export):
        self.poser = transforms.Poser(rider, list(deformations), object_at_export)
        if not self.poser.names:
            raise program.StirrupError("%s: stirrup's file names none of her bones" % rider.name)
        self.names = self.poser.names
        self.pose = self.poser.pose_matrices(rider, self.poser.stack(deformations))  # (frames, bones, 4, 4)

    def frame(self, k):
        return {n: self.pose[k, i] for i, n in enumerate(self.names)}


def evaluated_heads(context, rider, names, frames):
    """Her deform bones' heads (armature space) as Blender evaluates the scene at each of `frames`:
    (frames, bones, 3)."""
    scene = context.scene
    now = scene.frame_current
    out = []
    for f in frames:
        scene.frame_set(f)
        out.append(controls.deform_heads(rider, names))
    scene.frame_set(now)
    return np.array(out)


def worst_of(a, b, names, frames):
    """The worst distance between two sets of heads (frames, bones, 3), and the bone and frame where it is."""
    d = np.linalg.norm(a - b, axis=2)
    k, i = np.unravel_index(int(np.argmax(d)), d.shape)
    return float(d[k, i]), "%s at frame %d" % (names[i], frames[k])


def solve_controls(context, rider, plan, targets):
    """Her controls' values (frames, controls, 4, 4) that put her deform bones at the targets, solved with
    her animation set aside and her pose given back afterwards."""
    solver = controls.Solver(rider, plan)
    out = []
    with layer.set_aside(rider), export.meshes_still(rider):
        solver.apply_sets()
        solver.open(context)
        try:
            held = [solver.held_bases(context, solver.targets(targets.frame(k))) for k in range(len(targets.pose))]
        finally:
            solver.close()
        for bases in held:
            bases = solver.settle_scale(context, bases)
            out.append([transforms.np_matrix(bases[n]) for n in solver.names])
    return solver.names, np.array(out)


def key_rider(context, p, plan, targets, frames):
    """The ride's action: her controls keyed by the plan, or her deform bones as stirrup poses them."""
    name = "%s_stirrup_ride" % p.rider.name
    if plan is None:
        action = transforms.key_action(p.rider, name, frames, targets.names, targets.poser.bases_from_pose(p.rider, targets.pose))
        return action, targets.names, transforms.unsupported_bones(p.rider, targets.names)
    names, bases = solve_controls(context, p.rider, plan, targets)
    action = transforms.key_action(p.rider, name, frames, names, bases, skip_rest=True)
    transforms.key_properties(action, frames, plan.set)
    return action, names, []


def ride(context):
    """Rides the scene: returns the report's line. Nothing in the scene changes until stirrup has ridden."""
    s = context.scene.stirrup
    horse, rider = chosen(context)
    plan = controls.plan_for(rider, s.limbs, controls_text(context))
    check_horse(horse)
    tack.check_replaceable(context.scene)
    p = Prepared(context, export.work_dir(context))
    scene_file = p.write_scene()
    h, r = mapping.to_rig(p.maps["horse"]), mapping.to_rig(p.maps["rider"])
    ride_file = os.path.join(p.work, "ride.glb")
    program.run(["bake", scene_file, "--rider-only", "-o", ride_file], context)
    c = np.linalg.inv(h) @ r
    times, rider_d = file_deformations(ride_file, c)
    frames = p.blender_frames(times)
    # The whole shot baked too: the tack stirrup fits the horse (tack.py), and a generated gait's horse.
    shot_file = os.path.join(p.work, "ride-shot.glb")
    program.run(["bake", scene_file, "-o", shot_file], context)
    fitted_tack = tack.prepare(shot_file, p.horse, p.horse_at_export, h)
    horse_action = None
    if not p.horse_keyed:
        # A generated gait moves the horse: the bake's horse skin matrices (metres over centimetres: times
        # 100) taken to the horse's file by H^-1 ... H.
        to_horse = np.linalg.inv(h) @ np.diag([100.0, 100.0, 100.0, 1.0])
        _, bake_d = file_deformations(shot_file, to_horse, armature="horse")
        horse_d = {n: d @ h for n, d in bake_d.items()}
        horse_action, _ = key_armature(p.horse, horse_d, p.horse_at_export, frames, "%s_stirrup_%s" % (p.horse.name, s.gait))
    targets = RiderTargets(p.rider, rider_d, p.rider_at_export)
    rider_action, keyed, unsupported = key_rider(context, p, plan, targets, frames)
    # Committed: the mappings made, the ride's layer, and the horse's generated gait (undo gives back all).
    p.keep_new_maps()
    if horse_action is not None:
        p.horse.animation_data_create()
        p.horse.animation_data.action = horse_action
    layer.drop_if_unused(layer.put(p.rider, rider_action, frames[0]))
    tack.bring(context, fitted_tack, frames)
    line = report_ride(context, p, plan, targets, frames, rider_action, keyed, unsupported, horse_action)
    line += ("; the tack in the collection \"%s\"" % tack.COLLECTION) if fitted_tack is not None else "; the horse's own tack"
    s.last_ride = line
    return line


def report_ride(context, p, plan, targets, frames, action, keyed, unsupported, horse_action):
    """What the ride did, as Blender shows it: her joints against stirrup's at every frame (and the keys
    reduced, when asked, to within the tolerance of the dense ride), and the warnings."""
    s = context.scene.stirrup
    unit_cm = 100.0 * p.rider.matrix_world.to_scale()[0]
    names = targets.names
    with layer.own_keys_aside(p.rider), export.meshes_still(p.rider):
        dense = evaluated_heads(context, p.rider, names, frames)
        shown = dense
        reduced = ""
        if s.reduce_keys:
            def against_dense():
                return worst_of(evaluated_heads(context, p.rider, names, frames), dense, names, frames)[0]
            before, after, left = reduce.reduce(context, p.rider, action, s.reduce_tolerance_cm / unit_cm, against_dense)
            shown = evaluated_heads(context, p.rider, names, frames)
            reduced = "; keys reduced from %d to %d, within %.2f cm of the dense ride" % (before, after, left * unit_cm)
    worst, where = worst_of(shown, targets.pose[:, :, :3, 3], names, frames)
    what = plan.describe() if plan is not None else "%d bones of %s" % (len(keyed), p.rider.name)
    line = "stirrup rode frames %d-%d: %s keyed in the NLA track \"%s\"%s; her joints within %.2f cm of stirrup's (worst: %s)" % (
        frames[0], frames[-1], what, layer.TRACK, reduced, worst * unit_cm, where)
    if horse_action is not None:
        line += ", the horse on a generated %s" % s.gait
    if unsupported:
        line += "; %d bones follow constraints or inherit otherwise and will not show it (%s)" % (len(unsupported), ", ".join(unsupported[:3]))
    for obj, count in export.unweighted_vertices(p.rider):
        line += "; warning: %d vertices of %s carry no bone weight and stay where she stood" % (count, obj.name)
    return line


def controls_text(context):
    """The rider mapping's controls, a JSON object in the Blender text it names (empty: none named)."""
    name = context.scene.stirrup.rider_map.controls_text
    if not name:
        return ""
    text = bpy.data.texts.get(name)
    if text is None:
        raise program.StirrupError("the rider mapping's controls name the text %s, which is not in this .blend" % name)
    return text.as_string()


def check_horse(horse):
    """A horse without an action gets stirrup's gait keyed on its deform bones: refused when constraints
    drive them (a rig Rigify generated), where those keys would not show."""
    if export.has_action(horse):
        return
    driven = [b.name for b in horse.data.bones if b.use_deform and
              any(c.influence > 0 and not c.mute for c in horse.pose.bones[b.name].constraints)]
    if driven:
        raise program.StirrupError("the horse, %s, has no action, and constraints drive its deform bones (%s, ...): key its walk "
                                   "on its controls, or ride a horse whose bones are its own on a generated gait" % (horse.name, driven[0]))


class STIRRUP_OT_ride(bpy.types.Operator):
    """Key the rider's bones over the scene's frame range, seated on the horse as stirrup rides her"""
    bl_idname = "stirrup.ride"
    bl_label = "Ride"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        try:
            self.report({"INFO"}, ride(context))
        except program.StirrupError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}


classes = [STIRRUP_OT_ride]
