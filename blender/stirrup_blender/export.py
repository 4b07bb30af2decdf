# The characters and the shot exported with Blender's own glTF exporter, as the user has them: the deform
# bones, the armature objects' transforms, the meshes skinned to them; the action playing, as Blender plays
# it (NLA included). Selection, active object, mode and frame are put back as they were.
import contextlib
import os
import tempfile

import bpy
import numpy as np

from . import gltf_files, layer, program, tack, transforms

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
    +Y up, the actions as Blender plays them when `animations`, else the rest. Not "single armature" (the exporter's default), which
    would also export every other armature action of the .blend, a ride's among them, on this armature."""
    objects = []
    for arm in armatures:
        objects += [arm] + meshes_of(arm)
    objects += [o for o in extra if o not in objects]
    with contextlib.ExitStack() as flat, _selected(context, objects):
        if animations:  # a layered armature through one action holding its stack (the exporter plays no NLA)
            for arm in armatures:
                flat.enter_context(layer.flattened(context, arm))
        try:
            bpy.ops.export_scene.gltf(
                filepath=path, export_format="GLB", use_selection=True, export_yup=True, export_def_bones=True,
                export_skins=True, export_apply=False, export_animations=animations, export_nla_strips=False,
                export_force_sampling=True, export_frame_range=True, export_anim_single_armature=False, export_cameras=False, export_lights=False,
                export_extras=False, export_materials="EXPORT")
        except RuntimeError as e:
            raise program.StirrupError("Blender's glTF exporter failed on %s: %s" % (
                ", ".join(a.name for a in armatures), program.last_line(str(e))))
        if animations:
            exact_joints(context, armatures, path)
    return path


def exact_joints(context, armatures, path):
    """Rewrites the keyed joints of an export as Blender evaluates them. Rigify's IK bones scale a little
    (ik_stretch), and the exporter writes that as non-uniform scales that glTF's parent-child product turns
    into a shear it cannot hold: a hoof up to 6 mm from where Blender shows it. Here each joint's world in the
    file at each key is Blender's (G O P C: the object, the pose matrix, and the file's own axes for the bone,
    C, found at the bind), its pose scale dropped (the object's own scale kept), and each joint keyed relative
    to its parent's: positions and turns exact, the squash of a bone's length left out."""
    glb = gltf_files.Glb(path)
    times, worlds = gltf_files.keyed_worlds(glb) if glb.json.get("animations") else (None, None)
    if times is None:
        return
    scene = context.scene
    fps = scene.render.fps / scene.render.fps_base
    nodes = glb.json["nodes"]
    parent = glb.parents()
    jobs = []
    for arm in armatures:
        node_of = _skin_joints(glb, arm)
        if not node_of:
            continue
        o0 = gltf_files.armature_world(glb, arm.name)  # glTF axes: G O0
        ibm = gltf_files.inverse_binds(glb, node_of["_skin"])
        names = [n for n in node_of if n != "_skin" and n in arm.pose.bones]
        rest = {n: transforms.np_matrix(arm.data.bones[n].matrix_local) for n in names}
        c = {n: np.linalg.inv(o0 @ transforms.G @ rest[n]) @ np.linalg.inv(ibm[n]) for n in names}
        jobs.append((arm, names, node_of, c))
    now = scene.frame_current
    new_world = {}
    for k, t in enumerate(times):
        scene.frame_set(int(round(t * fps)))
        for arm, names, node_of, c in jobs:
            o = transforms.np_matrix(arm.matrix_world)
            s_o = abs(np.linalg.det(o[:3, :3])) ** (1.0 / 3.0)
            for n in names:
                w = transforms.G @ o @ transforms.np_matrix(arm.pose.bones[n].matrix) @ c[n]
                u, _, vt = np.linalg.svd(w[:3, :3])
                w[:3, :3] = (u @ vt) * s_o
                new_world.setdefault(node_of[n], np.zeros((len(times), 4, 4)))[k] = w
    scene.frame_set(now)
    for j, w in new_world.items():
        p = parent[j]
        pw = new_world[p] if p in new_world else (worlds[p] if p >= 0 else np.broadcast_to(np.eye(4), w.shape))
        local = np.linalg.inv(pw) @ w
        scale = np.cbrt(np.abs(np.linalg.det(local[:, :3, :3])))
        ch = glb.channels(j)
        values = {"translation": local[:, :3, 3], "rotation": gltf_files.quaternions(local[:, :3, :3] / scale[:, None, None]),
                  "scale": np.repeat(scale[:, None], 3, axis=1)}
        for path_name, v in values.items():
            if path_name in ch:
                glb.set_accessor(ch[path_name], v)
    glb.write(path)


def _skin_joints(glb, arm):
    """{bone name: joint node} of the skin whose joints hang from the armature node named like `arm`, with
    "_skin": the skin's index; {} when the file has none."""
    nodes = glb.json["nodes"]
    parent = glb.parents()
    for k, skin in enumerate(glb.json.get("skins", [])):
        joints = set(skin["joints"])
        top = [j for j in skin["joints"] if parent[j] not in joints]
        if top and parent[top[0]] >= 0 and nodes[parent[top[0]]].get("name") == arm.name:
            out = {nodes[j]["name"]: j for j in skin["joints"]}
            out["_skin"] = k
            return out
    return {}


def shot(context, horse, rider, horse_map, rider_map, path, tack_rig=None):
    """The scene's horse and rider as one shot, as they stand in Blender, rewritten for stirrup (docs/check.md,
    "A baked shot"): the armatures named "horse" and "rider", each mesh node carrying its character's role
    table by bone name (stirrup_role_joints), and in the scene's extras the horse's mapping as the file's
    world in stirrup's ("stirrup_world", rig/io/gltf_shot.h) and the scene's fps. With the tack's rig
    (tack.py), the tack goes with the horse: merge_tack. The scene's ground goes with them (ground_objects), so
    the check measures the hooves on it."""
    export(context, [horse, rider] + ([tack_rig] if tack_rig is not None else []), path, True, ground_objects())
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
    if tack_rig is not None:
        tack_skin = [k for k, a in roots.items() if a >= 0 and nodes[a].get("name") == tack_rig.name]
        if not tack_skin:
            raise program.StirrupError("%s: Blender's exporter wrote no armature named %s" % (path, tack_rig.name))
        horse_skin = [k for k, (kind, _) in cast.items() if kind == "horse"][0]
        merge_tack(glb, horse_skin, tack_skin[0])
        cast = {(k if k < tack_skin[0] else k - 1): v for k, v in cast.items()}
        horse_map = dict(horse_map, roles=dict(horse_map["roles"], **tack.point_roles(tack_rig)))
        cast = {k: ((kind, horse_map) if kind == "horse" else (kind, data)) for k, (kind, data) in cast.items()}
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



def merge_tack(glb, horse_skin, tack_skin):
    """The tack's rig merged into the horse, for stirrup to read the tack as the horse's (docs/blender.md,
    "The tack"): the tack's points (the rig's bones that copy none of the horse's) become joints of the
    horse's skin, with their inverse binds; the tack's meshes are skinned by the horse's skin, a bone that
    copies the horse's weighted as that bone of the horse's; the tack's skin goes."""
    js = glb.json
    nodes = js["nodes"]
    horse, tack = js["skins"][horse_skin], js["skins"][tack_skin]
    names = [nodes[j]["name"] for j in tack["joints"]]
    horse_index = {nodes[j]["name"]: k for k, j in enumerate(horse["joints"])}
    ibm_h = glb.accessor(horse["inverseBindMatrices"])
    ibm_t = glb.accessor(tack["inverseBindMatrices"])
    remap, added, extra_ibm = [], [], []
    for k, name in enumerate(names):
        if name in horse_index:  # a bone that copies the horse's
            remap.append(horse_index[name])
        else:  # a tack point
            remap.append(len(horse["joints"]) + len(added))
            added.append(tack["joints"][k])
            extra_ibm.append(ibm_t[k])
    horse["joints"] = horse["joints"] + added
    horse["inverseBindMatrices"] = glb.append_accessor(np.vstack([ibm_h] + [np.atleast_2d(m) for m in extra_ibm]), 5126, "MAT4")
    remap = np.array(remap)
    for node in nodes:
        if node.get("skin") == tack_skin:
            for prim in js["meshes"][node["mesh"]]["primitives"]:
                joints = glb.accessor(prim["attributes"]["JOINTS_0"]).astype(np.int64)
                prim["attributes"]["JOINTS_0"] = glb.append_accessor(remap[joints], 5123, "VEC4")
            node["skin"] = horse_skin
    del js["skins"][tack_skin]
    for node in nodes:
        if node.get("skin", -1) > tack_skin:
            node["skin"] -= 1
