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

from . import export, gltf_files, mapping, program, transforms


def chosen(context):
    """The horse and rider armatures, or a StirrupError saying what is missing."""
    s = context.scene.stirrup
    for kind in mapping.KINDS:
        obj = getattr(s, kind)
        if obj is None:
            raise program.StirrupError("no %s chosen: pick the %s's armature in the Stirrup panel (scene.stirrup.%s)" % (kind, kind, kind))
        if obj.type != "ARMATURE":
            raise program.StirrupError("the %s, %s, is not an armature" % (kind, obj.name))
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


def ride(context):
    """Rides the scene: returns the report's line. Nothing in the scene changes until stirrup has ridden."""
    p = Prepared(context, export.work_dir(context))
    scene_file = p.write_scene()
    h, r = mapping.to_rig(p.maps["horse"]), mapping.to_rig(p.maps["rider"])
    ride_file = os.path.join(p.work, "ride.glb")
    program.run(["bake", scene_file, "--rider-only", "-o", ride_file], context)
    c = np.linalg.inv(h) @ r
    times, rider_d = file_deformations(ride_file, c)
    frames = p.blender_frames(times)
    horse_action = None
    if not p.horse_keyed:
        # A generated gait moves the horse too: stirrup's whole bake, its horse's skin matrices (metres over
        # centimetres: times 100) taken to the horse's file by H^-1 ... H.
        shot_file = os.path.join(p.work, "ride-shot.glb")
        program.run(["bake", scene_file, "-o", shot_file], context)
        to_horse = np.linalg.inv(h) @ np.diag([100.0, 100.0, 100.0, 1.0])
        _, bake_d = file_deformations(shot_file, to_horse, armature="horse")
        horse_d = {n: d @ h for n, d in bake_d.items()}
        horse_action, _ = key_armature(p.horse, horse_d, p.horse_at_export, frames, "%s_stirrup_%s" % (p.horse.name, p.context.scene.stirrup.gait))
    rider_action, unsupported = key_armature(p.rider, rider_d, p.rider_at_export, frames, "%s_stirrup_ride" % p.rider.name)
    # Committed: the mappings made, and the new actions (undo gives back the old ones).
    p.keep_new_maps()
    for arm, action in ((p.rider, rider_action), (p.horse, horse_action)):
        if action is not None:
            arm.animation_data_create()
            arm.animation_data.action = action
    line = "stirrup rode frames %d-%d: %d bones of %s keyed%s" % (
        frames[0], frames[-1], len({fc.group.name for fc in rider_action.fcurves}), p.rider.name,
        (", the horse on a generated %s" % context.scene.stirrup.gait) if horse_action else "")
    if unsupported:
        line += "; %d bones follow constraints or inherit otherwise and will not show it (%s)" % (len(unsupported), ", ".join(unsupported[:3]))
    context.scene.stirrup.last_ride = line
    return line


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
