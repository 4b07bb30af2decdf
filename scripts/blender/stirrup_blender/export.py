# The characters and the shot exported with Blender's own glTF exporter, as the user has them: the deform
# bones, the armature objects' transforms, the meshes skinned to them; the action playing, as Blender plays
# it (NLA included). Selection, active object, mode and frame are put back as they were.
import contextlib
import os
import tempfile

import bpy
import numpy as np

from . import gltf_files, mapping, program

# Debian 12's numpy 1.24 removed the alias np.bool, which Blender 3.4's glTF exporter still uses.
if "bool" not in vars(np):  # (hasattr would ask numpy's module __getattr__, which warns)
    np.bool = bool


def work_dir(context):
    s = context.scene.stirrup
    path = bpy.path.abspath(s.work_dir) if s.work_dir else os.path.join(tempfile.gettempdir(), "stirrup-blender-%d" % os.getpid())
    os.makedirs(path, exist_ok=True)
    return path


def meshes_of(arm):
    """The meshes an armature deforms: its children, and any mesh with an Armature modifier on it."""
    out = []
    for o in bpy.data.objects:
        if o.type != "MESH":
            continue
        if o.parent == arm or any(m.type == "ARMATURE" and m.object == arm for m in o.modifiers):
            out.append(o)
    return out


def is_ground_name(name):
    """Whether an object's name makes it the shot's ground for stirrup check (docs/check.md, "The ground"):
    "ground", or "ground" then "_", "." or "-" ("Ground.001", "ground_mesh"), any case."""
    n = name.lower()
    return n == "ground" or (n.startswith("ground") and n[6] in "_.-")


def ground_objects():
    """The scene's ground, exported with a shot: every mesh named as the ground or under an object so named,
    with the objects between it and that name (so the name reaches the file)."""
    out = []
    for o in bpy.data.objects:
        if o.type != "MESH":
            continue
        chain, a = [], o
        while a is not None and not is_ground_name(a.name):
            chain.append(a)
            a = a.parent
        if a is not None:
            out += [x for x in chain + [a] if x not in out]
    return out


def has_action(arm):
    """Whether Blender plays an action on the armature: its active action, or an NLA strip's that is not muted."""
    ad = arm.animation_data
    if ad is None:
        return False
    if ad.action is not None:
        return True
    return any(not t.mute and any(st.action is not None and not st.mute for st in t.strips) for t in ad.nla_tracks)


@contextlib.contextmanager
def _selected(context, objects):
    view_layer = context.view_layer
    was_active = view_layer.objects.active
    was_selected = [o for o in view_layer.objects if o.select_get()]
    was_mode = context.mode
    frame = context.scene.frame_current
    if was_mode != "OBJECT" and was_active is not None:
        bpy.ops.object.mode_set(mode="OBJECT")
    try:
        for o in was_selected:
            o.select_set(False)
        for o in objects:
            o.select_set(True)
        view_layer.objects.active = objects[0]
        yield
    finally:
        for o in objects:
            o.select_set(False)
        for o in was_selected:
            o.select_set(True)
        view_layer.objects.active = was_active
        if was_mode.startswith("POSE") and was_active is not None:
            bpy.ops.object.mode_set(mode="POSE")
        elif was_mode.startswith("EDIT") and was_active is not None:
            bpy.ops.object.mode_set(mode="EDIT")
        if context.scene.frame_current != frame:
            context.scene.frame_set(frame)


def export(context, armatures, path, animations, extra=()):
    """Exports the armatures and their meshes (and the `extra` objects) to `path` (GLB): deform bones only,
    +Y up, the actions as Blender plays them when `animations`, else the rest."""
    objects = []
    for arm in armatures:
        objects += [arm] + meshes_of(arm)
    objects += [o for o in extra if o not in objects]
    with _selected(context, objects):
        try:
            bpy.ops.export_scene.gltf(
                filepath=path, export_format="GLB", use_selection=True, export_yup=True, export_def_bones=True,
                export_skins=True, export_apply=False, export_animations=animations, export_nla_strips=False,
                export_force_sampling=True, export_frame_range=True, export_cameras=False, export_lights=False,
                export_extras=False, export_materials="EXPORT")
        except RuntimeError as e:
            raise program.StirrupError("Blender's glTF exporter failed on %s: %s" % (
                ", ".join(a.name for a in armatures), program.last_line(str(e))))
    return path


def shot(context, horse, rider, horse_map, rider_map, path):
    """The scene's horse and rider as one shot, as they stand in Blender, rewritten for stirrup (docs/check.md,
    "A baked shot"): the armatures named "horse" and "rider", each mesh node carrying its character's role
    table by bone name (stirrup_role_joints), and in the scene's extras the horse's mapping as the file's
    world in stirrup's ("stirrup_world", rig/io/gltf_shot.h) and the scene's fps. The scene's ground goes with
    them (ground_objects), so the check measures the hooves on it."""
    export(context, [horse, rider], path, True, ground_objects())
    glb = gltf_files.Glb(path)
    nodes = glb.json["nodes"]
    parent = glb.parents()
    roots = {}
    for k, skin in enumerate(glb.json.get("skins", [])):
        top = [j for j in skin["joints"] if parent[j] not in skin["joints"]][0]
        roots[k] = parent[top]
    cast = {}
    for k, arm_node in roots.items():
        name = nodes[arm_node].get("name") if arm_node >= 0 else None
        for kind, obj, data in (("horse", horse, horse_map), ("rider", rider, rider_map)):
            if name == obj.name:
                cast[k] = (kind, data)
                nodes[arm_node]["name"] = kind
    if sorted(kind for kind, _ in cast.values()) != ["horse", "rider"]:
        raise program.StirrupError("%s: Blender's exporter wrote no armatures named %s and %s" % (path, horse.name, rider.name))
    for node in nodes:
        if "skin" in node and node["skin"] in cast:
            node.setdefault("extras", {})["stirrup_role_joints"] = dict(cast[node["skin"]][1]["roles"])
    scene = glb.json["scenes"][glb.json.get("scene", 0)]
    extras = scene.setdefault("extras", {})
    extras["stirrup_world"] = {k: horse_map[k] for k in ("scale_cm", "forward", "up", "offset_cm")}
    fps = context.scene.render.fps / context.scene.render.fps_base
    extras["fps"] = fps
    glb.write(path)
    return glb

