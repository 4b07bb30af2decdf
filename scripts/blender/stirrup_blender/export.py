# The characters and the shot exported with Blender's own glTF exporter, as the user has them: the deform
# bones, the armature objects' transforms, the meshes skinned to them; the action playing, as Blender plays
# it (NLA included). Selection, active object, mode and frame are put back as they were.
import contextlib
import os
import tempfile

import bpy
import numpy as np

from . import gltf_files, layer, program

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


@contextlib.contextmanager
def meshes_still(arm):
    """Her meshes' Armature modifiers off in the viewport for the duration: the bones are evaluated as ever,
    the bodies not deformed (what solving and measuring a pose frame by frame need)."""
    mods = [m for o in meshes_of(arm) for m in o.modifiers if m.type == "ARMATURE" and m.object == arm and m.show_viewport]
    for m in mods:
        m.show_viewport = False
    try:
        yield
    finally:
        for m in mods:
            m.show_viewport = True


def unweighted_vertices(arm):
    """[(mesh object, count)] of her meshes' vertices that no deform bone of hers weights: they will stay
    where she stood."""
    deform = {b.name for b in arm.data.bones if b.use_deform}
    out = []
    for o in meshes_of(arm):
        groups = {g.index for g in o.vertex_groups if g.name in deform}
        count = sum(1 for v in o.data.vertices if not any(g.group in groups and g.weight > 0.0 for g in v.groups))
        if count:
            out.append((o, count))
    return out


def _moves(obj):
    """Whether anything animates the object's own transform (its or a parent's keys, NLA or constraints)."""
    while obj is not None:
        ad = obj.animation_data
        if obj.constraints or (ad is not None and (ad.action is not None or len(ad.nla_tracks) or len(ad.drivers))):
            return True
        obj = obj.parent
    return False


def world_at_export(context, obj):
    """The object's world matrix as Blender's glTF exporter writes it: at frame 0, where the exporter goes
    before it writes (io_scene_gltf2's save)."""
    if not _moves(obj):
        return obj.matrix_world.copy()
    scene = context.scene
    now = scene.frame_current
    scene.frame_set(0)
    m = obj.matrix_world.copy()
    scene.frame_set(now)
    return m


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


def export(context, armatures, path, animations):
    """Exports the armatures and their meshes to `path` (GLB): deform bones only, +Y up, the actions as
    Blender plays them when `animations`, else the rest. Not "single armature" (the exporter's default), which
    would also export every other armature action of the .blend, a ride's among them, on this armature."""
    objects = []
    for arm in armatures:
        objects += [arm] + meshes_of(arm)
    scene = context.scene
    frames = list(range(scene.frame_start, scene.frame_end + 1))
    with contextlib.ExitStack() as flat, _selected(context, objects):
        if animations:  # a layered armature through one action holding its stack (the exporter plays no NLA)
            for arm in armatures:
                flat.enter_context(layer.flattened(context, arm, frames))
        try:
            bpy.ops.export_scene.gltf(
                filepath=path, export_format="GLB", use_selection=True, export_yup=True, export_def_bones=True,
                export_skins=True, export_apply=False, export_animations=animations, export_nla_strips=False,
                export_force_sampling=True, export_frame_range=True, export_anim_single_armature=False, export_cameras=False, export_lights=False,
                export_extras=False, export_materials="EXPORT")
        except RuntimeError as e:
            raise program.StirrupError("Blender's glTF exporter failed on %s: %s" % (
                ", ".join(a.name for a in armatures), program.last_line(str(e))))
    return path


def shot(context, horse, rider, horse_map, rider_map, path):
    """The scene's horse and rider as one shot, as they stand in Blender, rewritten for stirrup (docs/check.md,
    "A baked shot"): the armatures named "horse" and "rider", each mesh node carrying its character's role
    table by bone name (stirrup_role_joints), and in the scene's extras the horse's mapping as the file's
    world in stirrup's ("stirrup_world", rig/io/gltf_shot.h) and the scene's fps."""
    export(context, [horse, rider], path, True)
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

